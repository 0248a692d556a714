// A 1 x 0.5 x 0.5 box meshed coarsely (44 nodes, 90 tetrahedra with gmsh 4.8.4). No physical
// groups, so gmsh saves every element: points (type 15), lines (1), triangles (2), tetrahedra (4).
// Meshed by generate.py in this folder, e.g. `gmsh -3 box.geo -format msh41 -o box_gmsh_v41_ascii.msh`.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.5};
MeshSize{ PointsOf{ Volume{1}; } } = 0.4;
