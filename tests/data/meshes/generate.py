#!/usr/bin/python3
"""Regenerates the test meshes of this folder with the real tools (see README.md).

Needs Debian's gmsh, python3-meshio and python3-vtk9 (run with /usr/bin/python3):
    apt-get install -y gmsh python3-meshio python3-vtk9
    /usr/bin/python3 tests/data/meshes/generate.py

Every file holds the same mesh (box.geo: 44 points; 8 vertex cells, 28 lines, 84 triangles and
90 tetrahedra with gmsh 4.8.4) in a different format, except part_* (part.geo, non-contiguous
node tags). The gmsh files are meshed from the .geo each time; meshio and VTK convert
box_gmsh_v41_ascii.msh, keeping the point order and the cell order of the file.
"""

import os
import subprocess

import meshio
import numpy as np
import vtk
from vtk.util import numpy_support

HERE = os.path.dirname(os.path.abspath(__file__))


def path(name):
    return os.path.join(HERE, name)


def run_gmsh(geo, out, *options):
    subprocess.run(["gmsh", "-3", path(geo), *options, "-o", path(out)], check=True,
                   stdout=subprocess.DEVNULL)


def gmsh_files():
    run_gmsh("box.geo", "box_gmsh_v22_ascii.msh", "-format", "msh22")
    run_gmsh("box.geo", "box_gmsh_v22_binary.msh", "-format", "msh22", "-bin")
    run_gmsh("box.geo", "box_gmsh_v41_ascii.msh", "-format", "msh41")
    run_gmsh("box.geo", "box_gmsh_v41_binary.msh", "-format", "msh41", "-bin")
    run_gmsh("box.geo", "box_gmsh_v41_parametric.msh", "-format", "msh41",
             "-setnumber", "Mesh.SaveParametric", "1")
    run_gmsh("part.geo", "part_gmsh_v22_ascii.msh", "-format", "msh22")
    run_gmsh("part.geo", "part_gmsh_v41_ascii.msh", "-format", "msh41",
             "-setnumber", "Mesh.Renumber", "0")
    run_gmsh("part.geo", "part_gmsh_v41_binary.msh", "-format", "msh41", "-bin",
             "-setnumber", "Mesh.Renumber", "0")


def clean(mesh):
    """A fresh copy with points, cells and the gmsh:geometrical cell data (an array the readers
    must skip); meshio's writers modify the mesh they write and stumble on gmsh's cell sets."""
    cells = [meshio.CellBlock(c.type, c.data.copy()) for c in mesh.cells]
    geometrical = [d.copy() for d in mesh.cell_data["gmsh:geometrical"]]
    return meshio.Mesh(mesh.points.copy(), cells, cell_data={"gmsh:geometrical": geometrical})


def meshio_files(source):
    def mesh():
        return clean(source)

    meshio.vtk.write(path("box_meshio_v42_ascii.vtk"), mesh(), fmt_version="4.2", binary=False)
    meshio.vtk.write(path("box_meshio_v42_binary.vtk"), mesh(), fmt_version="4.2", binary=True)
    meshio.vtk.write(path("box_meshio_v51_ascii.vtk"), mesh(), fmt_version="5.1", binary=False)
    meshio.vtk.write(path("box_meshio_v51_binary.vtk"), mesh(), fmt_version="5.1", binary=True)
    meshio.vtu.write(path("box_meshio_ascii.vtu"), mesh(), binary=False)
    meshio.vtu.write(path("box_meshio_binary.vtu"), mesh(), binary=True, compression=None)
    meshio.vtu.write(path("box_meshio_binary_zlib.vtu"), mesh())  # meshio's default
    meshio.vtu.write(path("box_meshio_binary_zlib_uint64.vtu"), mesh(), header_type="UInt64")
    small = meshio.Mesh(source.points.astype(np.float32),
                        [meshio.CellBlock(c.type, c.data.astype(np.int32)) for c in source.cells])
    meshio.vtu.write(path("box_meshio_float32_int32.vtu"), small, binary=True, compression=None)


VTK_TYPE = {"vertex": vtk.VTK_VERTEX, "line": vtk.VTK_LINE, "triangle": vtk.VTK_TRIANGLE,
            "tetra": vtk.VTK_TETRA}


def vtk_grid(mesh, points_type=np.float64):
    grid = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(mesh.points.astype(points_type), deep=True))
    grid.SetPoints(points)
    for block in mesh.cells:
        for cell in block.data:
            grid.InsertNextCell(VTK_TYPE[block.type], len(cell), [int(i) for i in cell])
    # A point and a cell field, as a simulation result would carry: arrays the readers must skip.
    displacement = numpy_support.numpy_to_vtk(0.01 * mesh.points, deep=True)
    displacement.SetName("displacement")
    grid.GetPointData().AddArray(displacement)
    ids = numpy_support.numpy_to_vtk(np.arange(grid.GetNumberOfCells(), dtype=np.int32), deep=True)
    ids.SetName("cell_id")
    grid.GetCellData().AddArray(ids)
    return grid


def write_vtu(grid, name, mode, compress=True, header=64, encode=False, big_endian=False):
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path(name))
    writer.SetInputData(grid)
    {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
     "appended": writer.SetDataModeToAppended}[mode]()
    if compress:
        writer.SetCompressorTypeToZLib()
    else:
        writer.SetCompressorTypeToNone()
    writer.SetHeaderType(writer.UInt64 if header == 64 else writer.UInt32)
    writer.SetEncodeAppendedData(encode)
    if big_endian:
        writer.SetByteOrderToBigEndian()
    else:
        writer.SetByteOrderToLittleEndian()
    assert writer.Write() == 1


def write_legacy(grid, name, version, binary):
    writer = vtk.vtkUnstructuredGridWriter()
    writer.SetFileName(path(name))
    writer.SetInputData(grid)
    writer.SetFileVersion(version)
    if binary:
        writer.SetFileTypeToBinary()
    else:
        writer.SetFileTypeToASCII()
    assert writer.Write() == 1


def vtk_files(mesh):
    grid = vtk_grid(mesh)
    # ParaView's default .vtu: appended raw data, zlib, UInt64 headers.
    write_vtu(grid, "box_vtk_appended_raw_zlib_uint64.vtu", "appended")
    # vtkXMLUnstructuredGridWriter's own default: appended base64, zlib, UInt32 headers.
    write_vtu(grid, "box_vtk_appended_base64_zlib.vtu", "appended", header=32, encode=True)
    write_vtu(grid, "box_vtk_appended_raw.vtu", "appended", compress=False)
    write_vtu(grid, "box_vtk_appended_raw_zlib_bigendian.vtu", "appended", big_endian=True)
    write_vtu(grid, "box_vtk_binary_zlib_uint32.vtu", "binary", header=32)
    write_vtu(grid, "box_vtk_binary.vtu", "binary", compress=False)
    write_vtu(grid, "box_vtk_ascii.vtu", "ascii")
    write_vtu(vtk_grid(mesh, np.float32), "box_vtk_float32.vtu", "appended")
    write_legacy(grid, "box_vtk_v42_ascii.vtk", 42, binary=False)
    write_legacy(grid, "box_vtk_v42_binary.vtk", 42, binary=True)
    write_legacy(grid, "box_vtk_v51_ascii.vtk", 51, binary=False)
    write_legacy(grid, "box_vtk_v51_binary.vtk", 51, binary=True)


def main():
    gmsh_files()
    mesh = meshio.read(path("box_gmsh_v41_ascii.msh"))
    meshio_files(mesh)
    vtk_files(mesh)


if __name__ == "__main__":
    main()
