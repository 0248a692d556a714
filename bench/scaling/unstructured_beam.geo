// An unstructured tetrahedral beam for bench/scaling/scaling.py: the 16 x 4 x 4 box of the benchmark
// beams, meshed by Gmsh's Delaunay mesher at element size `h` (gmsh 4.8 -3 -setnumber h 0.105 gives
// 1,006,969 tetrahedra in 40 s), as an ASCII Gmsh 4.1 file.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.1, Name "element size"} ];
Box(1) = {0, 6, -2, 16, 4, 4};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm3D = 1;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Physical Volume("beam") = {1};
