// Writing VTK XML unstructured grids (.vtu) and ParaView collections (.pvd): the per-frame output
// of `fastcorot run --vtu` and of the drawn tetrahedra. Files are written atomically (atomic_file.h),
// so a reader never sees half a frame.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/state/rigid_blocks.h"

#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace fastcorot {

// A named per-point (or per-cell) field of 3-vectors or scalars for VTU output.
struct VtuField {
  std::string name;
  int components = 3;          // 1, 3 or 4 (a quaternion)
  std::vector<double> values;  // size = count × components
};

struct VtuCellBlock {
  int vtk_cell_type = 10;  // 10 = tetrahedron, 5 = triangle
  int nodes_per_cell = 4;
  std::vector<Index> connectivity;  // cells × nodes_per_cell
};

// One block of VTK tetrahedra (type 10) holding these tetrahedra.
VtuCellBlock tetrahedron_cells(std::span<const Tetrahedron> tetrahedra);

// Writes an unstructured grid (.vtu, base64 binary, uncompressed, UInt32 headers, little-endian)
// with the given point and cell fields; cell fields cover the cells of all blocks in order. Points
// and fields are written as Float64, connectivity and offsets as Int64, cell types as UInt8; a
// read_vtu of the file gives the points back bitwise. Throws fastcorot::Error naming the file for
// an index out of range, a field of the wrong size or component count, or a write failure.
void write_vtu(const std::filesystem::path& path, const std::vector<Vec3<double>>& points,
               const std::vector<VtuCellBlock>& cells, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields = {});

// Writes the frames of a system's rigid bodies: one VTK vertex per rigid at its centre, with point
// fields orientation (x y z w, SOFA's order), axis_x / axis_y / axis_z (the body's axes in the
// world: glyphs of these draw a frame per rigid), velocity and angular_velocity, force and torque
// (from the two blocks of the state vectors x, v and f).
void write_rigid_frames_vtu(const std::filesystem::path& path, const RigidBlocks<double>& rigids,
                            std::span<const Vec3<double>> x, std::span<const Vec3<double>> v,
                            std::span<const Vec3<double>> f);

// Writes a ParaView collection (.pvd) listing (time, file) pairs; file names relative to the .pvd.
// Times are written in the shortest form that reads back exactly; a non-finite time is an error.
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& time_steps);

}  // namespace fastcorot
