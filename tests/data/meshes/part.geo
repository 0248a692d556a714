// Two boxes sharing a face; only the right one is a physical group, so gmsh saves only its
// tetrahedra and nodes. With -setnumber Mesh.Renumber 0 the saved node tags keep their numbers
// from the whole model (non-contiguous, 5..88 with gmsh 4.8.4) in format 4.1.
// Meshed by generate.py in this folder.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.5, 0.5, 0.5};
Box(2) = {0.5, 0, 0, 0.5, 0.5, 0.5};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
MeshSize{ PointsOf{ Volume{:}; } } = 0.4;
Physical Volume("right", 7) = {2};
