// Cylinder validation mesh: radius 1, height 1, axis z, base at z = 0, top at z = 1, tetrahedra
// of characteristic length 0.15 (1091 nodes, 4452 tetrahedra with gmsh 4.8.4, Debian 12).
// Only the physical volume is saved, so the file holds the tetrahedra and the nodes they use
// (no surface triangles, no lines, no geometry points).
// Generated from the repository root with:
//   gmsh -3 examples/meshes/cylinder.geo -format msh41 -o examples/meshes/cylinder.msh
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 1, 1};
MeshSize{ PointsOf{ Volume{1}; } } = 0.15;
Physical Volume("cylinder", 1) = {1};
