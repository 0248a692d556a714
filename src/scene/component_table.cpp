#include "fastcorot/scene/component_table.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <sstream>

namespace fastcorot {

namespace {

const std::vector<ComponentSpec>& table() {
  static const std::vector<ComponentSpec> components = {
      {"MechanicalObject", "state", "Positions, velocities and rest positions of the points (template Vec3, Vec3d or Vec3f; simulated in double).",
       {{"position", "vec3s", "", "initial positions; default: the node's first topology's points"},
        {"velocity", "vec3s", "0", "initial velocities (one value is repeated to every point)"},
        {"rest_position", "vec3s", "", "rest positions; default: the transformed positions"},
        {"translation", "vec3", "0 0 0", "added to the positions after scaling and rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "per-axis scale, applied first"},
        {"dx", "real", "0", "translation along x (with dy, dz: SOFA's short form)"}, {"dy", "real", "0", "translation along y"},
        {"dz", "real", "0", "translation along z"}, {"rx", "real", "0", "rotation about x (degrees)"},
        {"ry", "real", "0", "rotation about y (degrees)"}, {"rz", "real", "0", "rotation about z (degrees)"},
        {"scale", "real", "1", "uniform scale"}, {"sx", "real", "1", "scale along x"},
        {"sy", "real", "1", "scale along y"}, {"sz", "real", "1", "scale along z"},
        {"src", "link", "", "take position from this loader"},
        {"topology", "link", "", "the topology giving the initial points"}}},
      {"RegularGridTopology", "topology", "A grid of n = (nx, ny, nz) points over [min, max], x fastest (SOFA's point order).",
       {{"n", "int3", "2 2 2", "points per axis"},
        {"min", "vec3", "0 0 0", "first corner"},
        {"max", "vec3", "1 1 1", "opposite corner"},
        {"nx", "int", "2", "points along x (with ny and nz, all three: replaces n)"}, {"ny", "int", "2", "points along y"},
        {"nz", "int", "2", "points along z"},
        {"xmin", "real", "0", "min.x (with the five others, all six: replace min and max, read as float as SOFA does)"},
        {"ymin", "real", "0", "min.y"}, {"zmin", "real", "0", "min.z"}, {"xmax", "real", "1", "max.x"},
        {"ymax", "real", "1", "max.y"}, {"zmax", "real", "1", "max.z"},
        {"scale", "real", "1", "multiplies xmin..zmax"},
        {"p0", "vec3", "min", "position of point 0 (the grid keeps the size of [min, max])"},
        {"drawHexahedra", "bool", "false", "accepted (display)"},
        {"position", "vec3s", "", "accepted: the grid's points are computed from n, min, max (SOFA scenes link it back to their state)"}}},
      {"TetrahedronSetTopologyContainer", "topology", "Tetrahedra (inline, from a loader with src, or filled by a Hexa2TetraTopologicalMapping).",
       {{"position", "vec3s", "", "points"},
        {"tetrahedra", "indices", "", "4 indices per tetrahedron"},
        {"edges", "indices", "", "explicit edge list (any order and orientation)"},
        {"triangles", "indices", "", "triangles (default: SOFA's triangle array of the tetrahedra)"},
        {"createTriangleArray", "bool", "false", "accepted: the triangles are made when asked for"},
        {"src", "link", "", "take position, tetrahedra and edges from this loader"}},
       {"MeshTopology", "TetrahedronSetTopology"}},
      {"Hexa2TetraTopologicalMapping", "mapping", "Splits the hexahedra of `input` (a RegularGridTopology) into 6 tetrahedra each, as SOFA does.",
       {{"input", "link", "", "the grid"},
        {"output", "link", "", "the TetrahedronSetTopologyContainer to fill"},
        {"swapping", "bool", "false", "alternate the split between neighbouring cells (conforming faces)"}}},
      {"TriangleSetTopologyContainer", "trianglecontainer", "Triangles (inline, from src, or the boundary a Tetra2TriangleTopologicalMapping fills it with), for pressure loads and BoxROI.",
       {{"position", "vec3s", "", "accepted (the points are the object's)"},
        {"triangles", "indices", "", "3 indices per triangle"},
        {"src", "link", "", "take triangles from this component"},
        {"fileTopology", "file", "", "accepted when empty"}}},
      {"SimpleTesselatedTetraTopologicalMapping", "mapping", "Fills `output` with `input`'s tetrahedra cut into 8 at their edge midpoints (new points after the input's, one per edge), in SOFA's order.",
       {{"input", "link", "", "the tetrahedral container"},
        {"output", "link", "", "the TetrahedronSetTopologyContainer to fill"}}},
      {"Tetra2TriangleTopologicalMapping", "mapping", "Fills `output` (a TriangleSetTopologyContainer) with the boundary triangles of `input`'s tetrahedra, in SOFA's order.",
       {{"input", "link", "", "the tetrahedral container"},
        {"output", "link", "", "the TriangleSetTopologyContainer to fill"},
        {"flipNormals", "bool", "false", "write each triangle (a, c, b)"},
        {"noInitialTriangles", "bool", "false", "leave the output empty"}}},
      {"MeshGmshLoader", "loader", "Reads a Gmsh .msh file (2.2 or 4.1, ASCII or binary).",
       {{"filename", "file", "", "mesh file, relative to the scene's folder"},
        {"translation", "vec3", "0 0 0", "applied after rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "applied first"},
        {"createSubelements", "bool", "true", "accepted; edges are derived as needed"}}},
      {"MeshVTKLoader", "loader", "Reads a VTK mesh: legacy .vtk (4.2, 5.1) or XML .vtu (ascii, base64, appended, zlib).",
       {{"filename", "file", "", "mesh file, relative to the scene's folder"},
        {"translation", "vec3", "0 0 0", "applied after rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "applied first"}}},
      {"GIDMeshLoader", "loader", "Reads a GiD ASCII mesh (.gidmsh): Tetrahedra or Triangle elements, as SOFA's GIDMeshLoader.",
       {{"filename", "file", "", "mesh file, found as SOFA finds data files (docs/scenes.md)"},
        {"translation", "vec3", "0 0 0", "applied after rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "applied first"}}},
      {"MeshOBJLoader", "surfaceloader", "Reads a Wavefront .obj surface (points, triangles, quads) for a visual model.",
       {{"filename", "file", "", "surface file, found as SOFA finds data files (docs/scenes.md)"},
        {"translation", "vec3", "0 0 0", "applied after rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "applied first"},
        {"scale", "real", "1", "uniform scale, multiplies scale3d"},
        {"handleSeams", "bool", "false", "accepted: texture and normal seams do not move points"},
        {"triangulate", "bool", "false", "accepted: quads are drawn as two triangles either way"},
        {"loadMaterial", "bool", "true", "accepted: the visual model's color is used"},
        {"createSubelements", "bool", "false", "accepted"}}},
      {"MeshSTLLoader", "surfaceloader", "Reads an STL surface (ASCII or binary) for a visual model.",
       {{"filename", "file", "", "surface file, found as SOFA finds data files (docs/scenes.md)"},
        {"translation", "vec3", "0 0 0", "applied after rotation"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx"},
        {"scale3d", "vec3", "1 1 1", "applied first"},
        {"scale", "real", "1", "uniform scale, multiplies scale3d"}}},
      {"OglModel", "visual", "A visual surface: drawn in pictures and the viewer, written as surface frames with --vtu; its points follow the object through the node's mapping.",
       {{"filename", "file", "", "surface file (or src, a surface loader)"},
        {"fileMesh", "file", "", "alias of filename"},
        {"color", "string", "1 1 1 1", "a colour name (red, gray, ...) or r g b [a]"},
        {"material", "string", "", "SOFA's material text; its Diffuse colour is used when no color is given"},
        {"translation", "vec3", "0 0 0", "applied after rotation (also dx, dy, dz)"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees (also rx, ry, rz)"},
        {"scale3d", "vec3", "1 1 1", "applied first (also scale, sx, sy, sz)"},
        {"dx", "real", "0", "translation along x"}, {"dy", "real", "0", "translation along y"},
        {"dz", "real", "0", "translation along z"}, {"rx", "real", "0", "rotation about x (degrees)"},
        {"ry", "real", "0", "rotation about y (degrees)"}, {"rz", "real", "0", "rotation about z (degrees)"},
        {"scale", "real", "1", "uniform scale"}, {"sx", "real", "1", "scale along x"},
        {"sy", "real", "1", "scale along y"}, {"sz", "real", "1", "scale along z"},
        {"handleDynamicTopology", "bool", "true", "accepted"}, {"useNormals", "bool", "true", "accepted"},
        {"updateNormals", "bool", "true", "accepted"}, {"computeTangents", "bool", "false", "accepted"},
        {"texturename", "string", "", "accepted: no textures are drawn"}, {"putOnlyTexCoords", "bool", "false", "accepted"},
        {"initRestPositions", "bool", "false", "accepted"}, {"primitiveType", "string", "DEFAULT", "accepted"}},
       {"OglModel", "VisualModel"}},
      {"BarycentricMapping", "visualmapping", "Maps the points of a visual model onto its parent object: onto the tetrahedra, or trilinearly onto the cells when the parent's first topology is a RegularGridTopology (as SOFA chooses).",
       {{"input", "link", "", "the parent's MechanicalObject (the default)"},
        {"output", "link", "", "the visual model (default: the node's)"},
        {"useRestPosition", "bool", "false", "place the points against the rest positions (else the positions at init)"},
        {"mapForces", "bool", "true", "accepted"}, {"mapConstraints", "bool", "true", "accepted"},
        {"mapMasses", "bool", "true", "accepted"}, {"isMechanical", "bool", "true", "accepted"}}},
      {"IdentityMapping", "visualmapping", "The visual model's points are the parent object's points, one for one.",
       {{"input", "link", "", "the parent's MechanicalObject (the default)"},
        {"output", "link", "", "the visual model (default: the node's)"}}},
      {"SubsetMapping", "visualmapping", "The visual model's points are some of the parent object's points: `indices`, `first`..`last`, else each point's match within `radius` (as SOFA finds them).",
       {{"input", "link", "", "the parent's MechanicalObject (the default)"},
        {"output", "link", "", "the visual model (default: the node's)"},
        {"indices", "indices", "", "the parent point of each point"},
        {"first", "int", "", "first parent index (with last, when indices are sequential)"},
        {"last", "int", "", "last parent index"},
        {"radius", "real", "1e-5", "search radius when no indices are given"},
        {"handleTopologyChange", "bool", "true", "accepted"}, {"ignoreNotFound", "bool", "false", "accepted: a point without a match is an error"},
        {"resizeToModel", "bool", "false", "accepted"}}},
      {"FastTetrahedralCorotationalForceField", "forcefield", "The corotational linear tetrahedral force field of SPEC.md.",
       {{"youngModulus", "reals", "5000", "E, one value or one per tetrahedron"},
        {"poissonRatio", "reals", "0.45", "nu in [0, 0.5), one value or one per tetrahedron"},
        {"method", "string", "qr", "qr (large), polar, polar2, none (linear, small)"},
        {"rayleighStiffness", "real", "0", "the force field's own stiffness-proportional damping"},
        {"drawing", "bool", "false", "draw the tetrahedra"},
        {"drawColor1", "string", "0 0 1 1", "colour of face 0"},
        {"drawColor2", "string", "0 0.5 1 1", "colour of face 1"},
        {"drawColor3", "string", "0 1 1 1", "colour of face 2"},
        {"drawColor4", "string", "0.5 1 1 1", "colour of face 3"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"}}},
      {"TetrahedronFEMForceField", "forcefield",
       "SOFA's linear tetrahedron with small, large (QR frame), polar or svd rotations (docs/tetrahedron-fem.md).",
       {{"youngModulus", "reals", "5000", "E, one value or one per tetrahedron"},
        {"poissonRatio", "reals", "0.45", "nu in [0, 0.5), one value or one per tetrahedron"},
        {"method", "string", "large", "small, large, polar or svd"},
        {"rayleighStiffness", "real", "0", "the force field's own stiffness-proportional damping"},
        {"localStiffnessFactor", "reals", "", "M factors: tetrahedron t's E times factor[t M / #T]"},
        {"computeVonMisesStress", "int", "0", "0 none, 1 from the corotational strain (not small), 2 from the Green strain"},
        {"computeGlobalMatrix", "bool", "false", "SOFA's assembled variant (alias assembling): the same forces for small and large; refused for polar and svd, where SOFA then computes no force"},
        {"assembling", "bool", "false", "alias of computeGlobalMatrix"},
        {"updateStiffnessMatrix", "bool", "false", "only false: J from the rest shape"},
        {"updateStiffness", "bool", "false", "accepted: the material does not change during a run"},
        {"plasticMaxThreshold", "real", "0", "largest plastic strain (2-norm); > 0 turns SOFA's plasticity on"},
        {"plasticYieldThreshold", "real", "0.0001", "elastic strain (2-norm) beyond which the plastic strain grows"},
        {"plasticCreep", "real", "0.9", "fraction of the elastic strain that becomes plastic per force evaluation"},
        {"gatherPt", "string", "", "accepted (SOFA's GPU version only)"},
        {"gatherBsize", "string", "", "accepted (SOFA's GPU version only)"},
        {"drawHeterogeneousTetra", "bool", "false", "display option, accepted"},
        {"showStressColorMap", "string", "Blue to Red", "display option, accepted"},
        {"showStressAlpha", "real", "1", "display option, accepted"},
        {"showElementGapScale", "real", "0.333", "display option, accepted"},
        {"drawing", "bool", "false", "draw the tetrahedra"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"}}},
      {"TetrahedralCorotationalFEMForceField", "forcefield",
       "SOFA's older corotational tetrahedron: small, large (QR frame) or polar, the same element as TetrahedronFEMForceField's (docs/tetrahedron-fem.md).",
       {{"youngModulus", "reals", "5000", "E, one value or one per tetrahedron"},
        {"poissonRatio", "reals", "0.45", "nu in [0, 0.5), one value or one per tetrahedron"},
        {"method", "string", "large", "small, polar, or large (any other name: large, as in SOFA)"},
        {"rayleighStiffness", "real", "0", "the force field's own stiffness-proportional damping"},
        {"localStiffnessFactor", "reals", "", "M factors: tetrahedron t's E times factor[t M / #T]"},
        {"computeGlobalMatrix", "bool", "false", "SOFA's assembled variant (alias assembling), as TetrahedronFEMForceField's"},
        {"assembling", "bool", "false", "alias of computeGlobalMatrix"},
        {"updateStiffnessMatrix", "bool", "false", "only false: J from the rest shape"},
        {"computeVonMisesStress", "bool", "false", "accepted: not computed (display only)"},
        {"drawing", "bool", "true", "draw the tetrahedra"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"}}},
      {"MeshSpringForceField", "forcefield", "Springs along the topology's edges and tetrahedra (SpringForceField's force and tangent), stiffness and damping divided by each rest length, as SOFA makes them.",
       {{"linesStiffness", "real", "0", "stiffness of the springs along the edges"},
        {"linesDamping", "real", "0", "damping of those springs"},
        {"tetrahedraStiffness", "real", "0", "stiffness of the springs along each tetrahedron's six edges"},
        {"tetrasStiffness", "real", "0", "older name of tetrahedraStiffness"},
        {"tetrahedraDamping", "real", "0", "damping of those springs"},
        {"tetrasDamping", "real", "0", "older name of tetrahedraDamping"},
        {"trianglesStiffness", "real", "0", "refused unless 0 (fastcorot makes no triangle springs)"},
        {"trianglesDamping", "real", "0", "refused unless 0"}, {"quadsStiffness", "real", "0", "refused unless 0"},
        {"quadsDamping", "real", "0", "refused unless 0"}, {"cubesStiffness", "real", "0", "refused unless 0"},
        {"cubesDamping", "real", "0", "refused unless 0"},
        {"noCompression", "bool", "false", "springs act only when stretched"},
        {"stiffness", "real", "100", "accepted: SpringForceField's default for springs given one by one, unused here (as in SOFA)"},
        {"damping", "real", "5", "accepted: unused, as stiffness"},
        {"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"topology", "link", "", "the topology (default: the node's)"},
        {"drawMode", "int", "0", "accepted (display)"}, {"drawSpringSize", "real", "8", "accepted (display)"},
        {"drawMinElongationRange", "real", "8", "accepted (display)"}, {"drawMaxElongationRange", "real", "15", "accepted (display)"}}},
      {"PlaneForceField", "forcefield", "Pushes points below the plane x . normal = d back out: f = -stiffness dist normal + damping dist v (include/fastcorot/fem/penalty_force_fields.h).",
       {{"normal", "vec3", "0 1 0", "the plane's normal (used as given)"},
        {"d", "real", "0", "the plane's offset along the normal"},
        {"stiffness", "real", "500", "penalty stiffness"},
        {"damping", "real", "5", "penalty damping"},
        {"maxForce", "real", "0", "largest force on a point (0: no limit)"},
        {"bilateral", "bool", "false", "act on both sides of the plane"},
        {"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"planeColor", "string", "", "accepted (display)"}}},
      {"ConicalForceField", "forcefield", "Keeps points inside a cone (apex coneCenter, axis coneHeight, half-angle coneAngle in degrees) by penalty forces.",
       {{"coneCenter", "vec3", "0 0 0", "the apex"},
        {"coneHeight", "vec3", "0 0 0", "the axis, its length the cone's height"},
        {"coneAngle", "real", "10", "half-angle in degrees"},
        {"stiffness", "real", "500", "penalty stiffness"},
        {"damping", "real", "5", "penalty damping"},
        {"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"color", "string", "", "accepted (display)"}}},
      {"TrianglePressureForceField", "forcefield", "A constant pressure vector on triangles: each gets pressure x its rest area, a third on each vertex (SOFA's useConstantForce).",
       {{"pressure", "vec3", "0 0 0", "force per unit area"},
        {"triangleList", "indices", "", "the triangles (of the node's triangle container, else of its topology)"},
        {"useConstantForce", "bool", "true", "only true is supported"},
        {"cauchyStress", "reals", "", "refused unless useConstantForce is true (then unused)"},
        {"topology", "link", "", "the topology whose triangles are listed"},
        {"showForces", "bool", "false", "accepted (display)"}}},
      {"DiagonalMass", "mass", "Lumped mass: each tetrahedron gives density |V| / 4 to each vertex.",
       {{"massDensity", "real", "", "density"},
        {"totalMass", "real", "", "total mass (wins over massDensity); 1 when neither is given"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"}}},
      {"UniformMass", "mass", "The same mass on every point.",
       {{"vertexMass", "real", "", "mass of each point"},
        {"totalMass", "real", "", "total mass, divided among the points (wins over vertexMass)"}}},
      {"MeshMatrixMass", "mass", "Linear-tetrahedron mass matrix (consistent, or lumped by row sums).",
       {{"massDensity", "real", "", "density"},
        {"totalMass", "real", "", "total mass (wins over massDensity); 1 when neither is given"},
        {"lumping", "bool", "false", "use the row sums as a diagonal mass"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"},
        {"printMass", "bool", "false", "accepted (a log option)"}}},
      {"FixedProjectiveConstraint", "constraint", "Holds points fixed (their velocity increments are projected to zero).",
       {{"indices", "indices", "0", "fixed points"},
        {"fixAll", "bool", "false", "fix every point"},
        {"activate_projectVelocity", "bool", "false", "also zero the velocities of fixed points after each step"}},
       {"FixedConstraint"}},
      {"PartialFixedProjectiveConstraint", "constraint", "Holds points fixed along some axes (their velocity increments' components along `fixedDirections` are projected to zero).",
       {{"indices", "indices", "0", "the points"},
        {"fixAll", "bool", "false", "every point"},
        {"fixedDirections", "int3", "1 1 1", "1 for each axis held, 0 for each free"},
        {"projectVelocity", "bool", "false", "also zero those velocity components after each step"}}},
      {"FixedPlaneProjectiveConstraint", "constraint", "Removes the component along `direction` of the velocity increments of points (dx <- dx - d (d . dx), as SOFA: d is not normalised); the points are `indices`, or those whose x . d lies strictly between dmin and dmax at init.",
       {{"direction", "vec3", "0 0 0", "the direction held"},
        {"dmin", "real", "0", "lower bound of x . d (with dmax, when different)"},
        {"dmax", "real", "0", "upper bound of x . d"},
        {"indices", "indices", "", "the points (added to those selected by dmin, dmax)"},
        {"topology", "link", "", "accepted"}}},
      {"PlaneProjectiveConstraint", "constraint", "Keeps points on the plane through `origin` with normal `normal`: increments and velocities projected onto the plane, positions projected onto it after each step.",
       {{"indices", "indices", "", "the points"},
        {"origin", "vec3", "0 0 0", "a point of the plane"},
        {"normal", "vec3", "0 0 0", "the plane's normal (normalised; zero: no projection of positions, increments kept)"},
        {"drawSize", "real", "0", "accepted (display)"},
        {"topology", "link", "", "accepted"}}},
      {"LineProjectiveConstraint", "constraint", "Keeps points on the line through `origin` along `direction`: increments and velocities projected onto it (the direction normalised), positions projected after each step.",
       {{"indices", "indices", "", "the points"},
        {"origin", "vec3", "0 0 0", "a point of the line"},
        {"direction", "vec3", "0 0 0", "the line's direction"},
        {"drawSize", "real", "0", "accepted (display)"},
        {"topology", "link", "", "accepted"}}},
      {"AffineMovementProjectiveConstraint", "constraint", "Moves points from where they start to rotation x + translation, linearly between beginConstraintTime and endConstraintTime (their increments and velocities projected to zero).",
       {{"indices", "indices", "", "the moved points"},
        {"rotation", "reals", "0 (SOFA's zero matrix)", "3x3 matrix, row by row"},
        {"translation", "vec3", "0 0 0", "added after the rotation"},
        {"beginConstraintTime", "real", "0", "the motion starts after this time"},
        {"endConstraintTime", "real", "20", "and ends at this time"},
        {"meshIndices", "indices", "", "accepted (SOFA's final positions of other points, for other components)"},
        {"quaternion", "string", "", "accepted (rigid states only)"},
        {"topology", "link", "", "accepted"}}},
      {"PatchTestMovementProjectiveConstraint", "constraint", "Moves points from where they start by the corners' movements interpolated (bi- or trilinearly, SOFA's weights from its corners of constrainedPoints), linearly between beginConstraintTime and endConstraintTime (their increments and velocities projected to zero).",
       {{"indices", "indices", "", "the moved points"},
        {"constrainedPoints", "vec3s", "", "the points whose extremes are the corners (SOFA's search)"},
        {"cornerMovements", "vec3s", "", "one movement per corner (4, or 8 in 3D); missing ones are zero, with a warning"},
        {"beginConstraintTime", "real", "0", "the motion starts after this time"},
        {"endConstraintTime", "real", "20", "and ends at this time"},
        {"meshIndices", "indices", "", "accepted (SOFA's final positions of other points, for other components)"},
        {"cornerPoints", "vec3s", "", "accepted (SOFA computes them)"},
        {"drawConstrainedPoints", "bool", "false", "accepted (display)"},
        {"topology", "link", "", "accepted"}}},
      {"AttachProjectiveConstraint", "constraint", "Ties points of object2 to points of object1 (indices2[i] to indices1[i]); one way, object2's points follow object1's (their increments zeroed), two ways, the increments of each pair are averaged; after each step object2's point moves halfway to object1's and the pair's velocities are averaged (times the factors), as SOFA does for 3D points.",
       {{"object1", "link", "", "the first object (a node, or its MechanicalObject); default: the node's own"},
        {"object2", "link", "", "the second object"},
        {"indices1", "indices", "", "points of object1"},
        {"indices2", "indices", "", "points of object2, as many"},
        {"twoWay", "bool", "false", "each object acts on the other"},
        {"constraintFactor", "reals", "1 per pair", "per pair, in [0, 1] (0: released)"},
        {"positionFactor", "real", "1", "factor of the end-of-step position projection"},
        {"velocityFactor", "real", "1", "factor of the end-of-step velocity projection"},
        {"responseFactor", "real", "1", "factor of the projection of increments (two ways)"},
        {"minDistance", "real", "-1", "only -1 (always attached) is supported"},
        {"freeRotations", "bool", "false", "accepted (rigid states only)"},
        {"lastFreeRotation", "bool", "false", "accepted (rigid states only)"},
        {"restRotations", "bool", "false", "accepted (rigid states only)"},
        {"lastPos", "vec3", "", "not supported (releasing points past a plane)"},
        {"lastDir", "vec3", "", "not supported (releasing points past a plane)"},
        {"clamp", "bool", "false", "only false is supported"}}},
      {"GenerateCylinder", "engine", "A tetrahedral cylinder along z (data tetrahedra and output_TetrahedraPosition, alias output_position), SOFA's points and tetrahedra in SOFA's order; linear tetrahedra only.",
       {{"radius", "real", "0.2", "radius"},
        {"height", "real", "1", "height"},
        {"origin", "vec3", "0 0 0", "centre of the base"},
        {"resCircumferential", "int", "6", "points around each ring (>= 3)"},
        {"resRadial", "int", "3", "rings (>= 1)"},
        {"resHeight", "int", "5", "layers of points along z (>= 2)"},
        {"openSurface", "bool", "true", "accepted (its triangle output is not made)"},
        {"BezierTetrahedronDegree", "int", "0", "only 0 or 1 (linear)"},
        {"BezierTriangleDegree", "int", "0", "only 0 or 1 (linear)"}}},
      {"PairBoxROI", "engine", "Selects the points inside inclusiveBox and not inside includedBox (bounds included).",
       {{"inclusiveBox", "reals", "", "xmin ymin zmin xmax ymax zmax"},
        {"includedBox", "reals", "", "xmin ymin zmin xmax ymax zmax"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"meshPosition", "vec3s", "", "accepted"},
        {"drawSize", "real", "", "accepted (display)"}}},
      {"BoxROI", "engine", "Selects the points (and tetrahedra) inside axis-aligned boxes, bounds included.",
       {{"box", "reals", "0 0 0 1 1 1", "xmin ymin zmin xmax ymax zmax, 6 numbers per box"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"strict", "bool", "true", "a tetrahedron or triangle is inside when all its vertices are (else its barycentre)"},
        {"triangles", "indices", "", "triangles to test for triangleIndices (default: the node's triangle container's, else its topology's)"},
        {"doUpdate", "bool", "true", "accepted; the selection is made at init"}}},
      {"ConstantForceField", "forcefield", "Constant forces on points (indices empty = every point).",
       {{"indices", "indices", "", "points receiving a force"},
        {"forces", "vec3s", "", "one force per index (wins)"},
        {"force", "vec3", "", "the same force on every index"},
        {"totalForce", "vec3", "", "divided equally among the indices"},
        {"indexFromEnd", "bool", "false", "index i means point n-1-i"}}},
      {"TopologicalChangeProcessor", "topologychange", "Removes (and adds) tetrahedra at given times: from its data or from a file of timed changes (docs/cutting.md).",
       {{"useDataInputs", "bool", "false", "take the change from timeToRemove and tetrahedraToRemove"},
        {"timeToRemove", "real", "0", "remove at the first step starting after this time"},
        {"tetrahedraToRemove", "indices", "", "tetrahedron indices (numbered as when the removal comes)"},
        {"interval", "real", "0", "repeat the removal every interval (0: once)"},
        {"filename", "file", "", "timed changes: T= time, REMOVE= N indices, ADD= Tetrahedra N 4N indices"},
        {"shift", "real", "0", "added to the time when reading the file"},
        {"loop", "bool", "false", "only false"},
        {"listChanges", "indices", "", "accepted, unused (as in SOFA)"},
        {"pointsToRemove", "indices", "", "only empty"},
        {"edgesToRemove", "indices", "", "only empty"},
        {"trianglesToRemove", "indices", "", "only empty"},
        {"quadsToRemove", "indices", "", "only empty"},
        {"hexahedraToRemove", "indices", "", "only empty"},
        {"saveIndicesAtInit", "bool", "false", "only false"},
        {"epsilonSnapPath", "real", "0.1", "accepted, unused"},
        {"epsilonSnapBorder", "real", "0.25", "accepted, unused"},
        {"draw", "bool", "false", "accepted, unused"},
        {"topology", "link", "", "the tetrahedral topology (default: the node's)"}}},
      {"EulerImplicitSolver", "odesolver", "Backward Euler with Rayleigh damping (SOFA's formulation).",
       {{"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"rayleighMass", "real", "0", "mass-proportional damping"},
        {"vdamping", "real", "0", "velocity decay rate"},
        {"firstOrder", "bool", "false", "first-order scheme"},
        {"trapezoidalScheme", "bool", "false", "trapezoidal factors (tr = 0.5)"},
        {"solveConstraint", "bool", "false", "accepted; no constraint solvers"},
        {"linearSolver", "link", "", "the linear solver (default: the first in its node or below, as in SOFA)"}}},
      {"NewmarkImplicitSolver", "odesolver", "Newmark-beta on accelerations with Rayleigh damping (SOFA's formulation, docs/sofa-solvers.md).",
       {{"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"rayleighMass", "real", "0", "mass-proportional damping"},
        {"vdamping", "real", "0", "velocity decay rate"},
        {"gamma", "real", "0.5", "Newmark's gamma"},
        {"beta", "real", "0.25", "Newmark's beta"},
        {"threadSafeVisitor", "bool", "false", "accepted"},
        {"linearSolver", "link", "", "the linear solver (default: the first in its node or below, as in SOFA)"}}},
      {"VariationalSymplecticSolver", "odesolver", "SOFA's variational midpoint integrator on positions and momenta (Newton iterations; include/fastcorot/sim/variational_symplectic_solver.h).",
       {{"newtonError", "real", "0.01", "Newton stops when the change of the increment over |x| is below it"},
        {"steps", "int", "5", "most Newton iterations"},
        {"rayleighStiffness", "real", "0", "stiffness-proportional damping"},
        {"rayleighMass", "real", "0", "mass-proportional damping"},
        {"explicitIntegration", "bool", "false", "the explicit form"},
        {"computeHamiltonian", "bool", "true", "accepted: the energy it reports is not computed"},
        {"useIncrementalPotentialEnergy", "bool", "true", "accepted"},
        {"saveEnergyInFile", "bool", "false", "accepted: no file is written (an info line says so)"},
        {"file", "string", "", "accepted"},
        {"threadSafeVisitor", "bool", "false", "accepted"},
        {"linearSolver", "link", "", "the linear solver (default: the first in its node or below, as in SOFA)"}}},
      {"EulerExplicitSolver", "odesolver", "Explicit Euler: symplectic (v += h a, then x += h v) or not (x first); a = M^-1 P f, a solve with the linear solver for a consistent mass.",
       {{"symplectic", "bool", "true", "update the velocities first"},
        {"threadSafeVisitor", "bool", "false", "accepted"},
        {"linearSolver", "link", "", "the linear solver (needed only for a consistent mass)"}}},
      {"RungeKutta4Solver", "odesolver", "Classical fourth-order Runge-Kutta on positions and velocities (four force evaluations per step).",
       {{"linearSolver", "link", "", "the linear solver (needed only for a consistent mass)"}}},
      {"StaticSolver", "odesolver", "Static equilibrium by Newton-Raphson on P f(x) = 0.",
       {{"newtonSolver", "link", "", "the NewtonRaphsonSolver (default: one with default settings)"},
        {"linearSolver", "link", "", "the linear solver (default: the first in its node or below, as in SOFA)"},
        {"newton_iterations", "int", "1", "older form: maxNbIterationsNewton"},
        {"absolute_correction_tolerance_threshold", "real", "1e-5", "older form: absoluteEstimateDifferenceThreshold"},
        {"relative_correction_tolerance_threshold", "real", "1e-5", "older form: relativeEstimateDifferenceThreshold"},
        {"absolute_residual_tolerance_threshold", "real", "1e-5", "older form: absoluteResidualStoppingThreshold"},
        {"relative_residual_tolerance_threshold", "real", "1e-5", "older form: mapped as SOFA maps it (onto relativeEstimateDifferenceThreshold)"},
        {"should_diverge_when_residual_is_growing", "bool", "false", "older form: no effect"}}},
      {"NewtonRaphsonSolver", "odesolver", "Newton iterations with line search, driven by a StaticSolver.",
       {{"maxNbIterationsNewton", "int", "1", "Newton iterations per step"},
        {"maxNbIterationsLineSearch", "int", "5", "step halvings tried"},
        {"lineSearchCoefficient", "real", "0.5", "step reduction factor"},
        {"relativeSuccessiveStoppingThreshold", "real", "1e-5", "|r_k| < t |r_(k-1)|"},
        {"relativeInitialStoppingThreshold", "real", "1e-5", "|r_k| < t |r_0|"},
        {"absoluteResidualStoppingThreshold", "real", "1e-5", "|r_k| < t"},
        {"relativeEstimateDifferenceThreshold", "real", "0", "|dx| < t |x| (0: off)"},
        {"absoluteEstimateDifferenceThreshold", "real", "0", "|dx| < t (0: off)"},
        {"updateStateWhenDiverged", "bool", "true", "accepted"},
        {"warnWhenLineSearchFails", "bool", "true", "accepted"},
        {"warnWhenDiverge", "bool", "true", "accepted"},
        {"linearSolver", "link", "", "the StaticSolver's linear solver (SOFA master's place for the link)"}}},
      {"CGLinearSolver", "linearsolver", "Matrix-free conjugate gradient with SOFA's stopping rules.",
       {{"iterations", "int", "25", "maximum iterations"},
        {"tolerance", "real", "1e-5", "stop when |r| / |b| <= tolerance"},
        {"threshold", "real", "1e-5", "stop when |p^T A p| <= threshold"},
        {"warmStart", "bool", "false", "only false: the solve starts from zero"}}},
      {"PCGLinearSolver", "linearsolver",
       "Preconditioned conjugate gradient as SOFA computes it (starts from its previous solution), with a Jacobi, block-Jacobi or sparse direct preconditioner.",
       {{"iterations", "int", "25", "maximum iterations"},
        {"tolerance", "real", "1e-5", "stop when r . P r <= tolerance |b|^2"},
        {"preconditioner", "link", "", "a BlockJacobiPreconditioner, JacobiPreconditioner or sparse direct solver; none: plain CG iterations"},
        {"preconditioners", "string", "", "older form: the preconditioner's name"},
        {"use_precond", "bool", "true", "false: ignore the preconditioner"},
        {"update_step", "int", "1", "rebuild the preconditioner every this many solves (older form of the system's assemblingRate)"},
        {"build_precond", "bool", "true", "false: build it at the first solve only"},
        {"linearSystem", "link", "", "a PreconditionedMatrixFreeSystem (default: the first in its node or below)"}}},
      {"PreconditionedMatrixFreeSystem", "linearsystem",
       "SOFA master's linear system of a PCGLinearSolver: holds how often the preconditioner is rebuilt.",
       {{"assemblingRate", "int", "1", "rebuild the preconditioner every this many solves"},
        {"update_step", "int", "1", "older name of assemblingRate"},
        {"preconditionerSystem", "link", "", "the preconditioner's MatrixLinearSystem"}}},
      {"MatrixLinearSystem", "linearsystem",
       "The matrix a SOFA preconditioner or direct solver assembles into; accepted for links to it (the solvers here build what they need themselves).",
       {}},
      {"BlockJacobiPreconditioner", "preconditioner",
       "The inverses of the system matrix's 3x3 diagonal blocks (for PCGLinearSolver), built without assembling the matrix.",
       {{"verbose", "bool", "false", "accepted"},
        {"linearSystem", "link", "", "a MatrixLinearSystem (accepted)"}}},
      {"JacobiPreconditioner", "preconditioner",
       "The inverse of the system matrix's diagonal (for PCGLinearSolver), built without assembling the matrix.",
       {{"verbose", "bool", "false", "accepted"},
        {"linearSystem", "link", "", "a MatrixLinearSystem (accepted)"}}},
      {"PrecomputedWarpPreconditioner", "preconditioner",
       "SOFA's R A0^-1 R^T (for PCGLinearSolver): A0 the system matrix of the first step, factorised once; R TetrahedronFEMForceField's point rotations (the mean of its elements' rotations around each point), taken whenever the preconditioner is rebuilt.",
       {{"linearSystem", "link", "", "a PrecomputedMatrixSystem or MatrixLinearSystem (accepted)"},
        {"linearSolver", "link", "", "SOFA's solver for the precomputation (accepted: A0 is factorised here)"},
        {"use_rotations", "bool", "true", "false: P = A0^-1"},
        {"use_file", "bool", "true", "accepted (SOFA caches A0^-1 in a file; nothing is written here)"},
        {"share_matrix", "bool", "true", "accepted"},
        {"jmjt_twostep", "bool", "true", "accepted (constraint corrections)"},
        {"draw_rotations_scale", "real", "0", "accepted (display)"}}},
      {"PrecomputedMatrixSystem", "linearsystem",
       "The matrix SOFA's PrecomputedWarpPreconditioner assembles into; accepted for links to it.",
       {}},
      {"EigenSimplicialLDLT", "linearsolver",
       "Sparse direct LDL^T solve of the assembled system; as a PCGLinearSolver's preconditioner, the factorisation it keeps for update_step solves.",
       {{"ordering", "string", "AMD", "accepted"},
        {"linearSystem", "link", "", "a MatrixLinearSystem (accepted)"}},
       {"SparseLDLSolver", "SparseCholeskySolver", "EigenSimplicialLLT", "EigenSparseLU"}},
  };
  return components;
}

constexpr std::array<std::string_view, 55> kIgnored = {
    "RequiredPlugin", "VisualStyle", "DefaultAnimationLoop", "DefaultVisualManagerLoop",
    "CollisionPipeline", "DefaultPipeline", "BruteForceBroadPhase", "BVHNarrowPhase",
    "BruteForceDetection", "MinProximityIntersection", "LocalMinDistance", "NewProximityIntersection",
    "DiscreteIntersection", "CollisionResponse", "DefaultContactManager", "TriangleCollisionModel",
    "LineCollisionModel", "PointCollisionModel", "SphereCollisionModel", "SphereLoader",
    "VisualGrid", "LineAxis", "OglSceneFrame", "TetrahedronSetTopologyModifier",
    "TetrahedronSetGeometryAlgorithms", "TriangleSetTopologyModifier",
    "TriangleSetGeometryAlgorithms", "InteractiveCamera", "LightManager", "DirectionalLight", "SpotLight",
    "PositionalLight", "BackgroundSetting", "Camera", "OglLabel", "ConstraintAttachButtonSetting",
    "AttachBodyButtonSetting", "Visual3DText", "OglShader", "OglShadowShader", "VisualMesh", "WriteState", "MeshExporter",
    "VisualModelOBJExporter", "CompareState", "ReadState", "EdgeSetTopologyContainer", "EdgeSetTopologyModifier",
    "EdgeSetGeometryAlgorithms", "PlaneConstraint", "ValuesFromPositions", "NaturalOrderingMethod",
    "AMDOrderingMethod", "METISOrderingMethod", "RCMOrderingMethod"};

std::string join_names(std::span<const AttributeSpec> attributes) {
  std::string list;
  for (const auto& a : attributes) list += (list.empty() ? "" : ", ") + std::string(a.name);
  return list;
}

std::string supported_names() {
  std::string list;
  for (const auto& spec : table()) list += (list.empty() ? "" : ", ") + std::string(spec.name);
  return list;
}

constexpr std::array<std::string_view, 8> kCommon = {"name", "template", "tags", "printLog", "listening",
                                                     "bbox", "componentState", "src"};

}  // namespace

const ComponentSpec* find_component(std::string_view name) {
  for (const auto& spec : table()) {
    if (spec.name == name) return &spec;
    if (std::find(spec.aliases.begin(), spec.aliases.end(), name) != spec.aliases.end()) return &spec;
  }
  return nullptr;
}

std::span<const ComponentSpec> supported_components() { return table(); }

bool is_ignored_component(std::string_view name) {
  return std::find(kIgnored.begin(), kIgnored.end(), name) != kIgnored.end();
}

std::span<const std::string_view> ignored_components() { return kIgnored; }

bool is_unknown_to_sofa(std::string_view name) {
  // Names SOFA's own example scenes carry but SOFA's object factory does not know: SOFA reports an
  // error for each and runs the scene without it.
  static constexpr std::array<std::string_view, 1> kUnknown = {"PlaneConstraint"};
  return std::find(kUnknown.begin(), kUnknown.end(), name) != kUnknown.end();
}

bool is_collision_component(std::string_view name) {
  static constexpr std::array<std::string_view, 16> kCollision = {
      "CollisionPipeline", "DefaultPipeline", "BruteForceBroadPhase", "BVHNarrowPhase", "BruteForceDetection",
      "MinProximityIntersection", "LocalMinDistance", "NewProximityIntersection", "DiscreteIntersection",
      "CollisionResponse", "DefaultContactManager", "TriangleCollisionModel", "LineCollisionModel",
      "PointCollisionModel", "SphereCollisionModel", "SphereLoader"};
  return std::find(kCollision.begin(), kCollision.end(), name) != kCollision.end();
}

bool is_common_attribute(std::string_view name) {
  return std::find(kCommon.begin(), kCommon.end(), name) != kCommon.end() || name.starts_with("draw") ||
         name.starts_with("show");
}

namespace {

// Edit distance between two names, letters compared without case (a typo, a swapped pair of
// letters or a different capital).
std::size_t name_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

// " (did you mean 'X'?)" for the closest candidate within a third of the name's length (at least
// 2 edits), else "".
template <class Names>
std::string suggestion(std::string_view name, const Names& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    const std::size_t d = name_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

}  // namespace

// SOFA components fastcorot knows it does not simulate, and why: a scene with one is refused in one
// line saying so (an unknown component's line would not say what is missing).
std::span<const std::pair<std::string_view, std::string_view>> refused_components() {
  static const std::array<std::pair<std::string_view, std::string_view>, 16> kRefused = {{
      {"FreeMotionAnimationLoop", "constraint-based animation (Lagrangian constraints) is not simulated"},
      {"GenericConstraintSolver", "Lagrangian constraint solvers are not simulated"},
      {"BlockGaussSeidelConstraintSolver", "Lagrangian constraint solvers are not simulated"},
      {"LCPConstraintSolver", "Lagrangian constraint solvers are not simulated"},
      {"UncoupledConstraintCorrection", "constraint corrections (Lagrangian constraints) are not simulated"},
      {"LinearSolverConstraintCorrection", "constraint corrections (Lagrangian constraints) are not simulated"},
      {"PrecomputedConstraintCorrection", "constraint corrections (Lagrangian constraints) are not simulated"},
      {"GenericConstraintCorrection", "constraint corrections (Lagrangian constraints) are not simulated"},
      {"BilateralLagrangianConstraint", "Lagrangian constraints are not simulated"},
      {"FixedLagrangianConstraint", "Lagrangian constraints are not simulated"},
      {"RigidMapping", "rigid bodies (Rigid3 states, RigidMapping) are not simulated"},
      {"HexahedronFEMForceField", "hexahedral FEM is not simulated (tetrahedra only)"},
      {"SparseGridTopology", "sparse grids (hexahedral FEM) are not simulated"},
      {"TriangularFEMForceField", "triangular FEM is not simulated (tetrahedra only)"},
      {"TetrahedronHyperelasticityFEMForceField", "hyperelastic FEM is not simulated (linear corotational only)"},
      {"StandardTetrahedralFEMForceField", "hyperelastic FEM is not simulated (linear corotational only)"},
  }};
  return kRefused;
}

std::string_view refusal_reason(std::string_view type) {
  for (const auto& [name, reason] : refused_components()) {
    if (name == type) return reason;
  }
  return {};
}

const ComponentSpec* check_scene_object(const SceneObject& object, std::vector<std::string>* warnings) {
  const ComponentSpec* spec = find_component(object.type);
  if (!spec) {
    if (is_ignored_component(object.type)) return nullptr;
    if (const std::string_view reason = refusal_reason(object.type); !reason.empty()) {
      throw make_error(object.location.to_string(), ": ", object.type, ": this scene needs what fastcorot does not have: ",
                       reason);
    }
    std::vector<std::string_view> names;
    for (const auto& s : table()) names.push_back(s.name);
    throw make_error(object.location.to_string(), ": unknown component '", object.type, "'",
                     suggestion(object.type, names), "; supported: ", supported_names(),
                     " (and display or collision components, which are ignored); see `fastcorot components`");
  }
  for (const auto& [attribute, value] : object.attributes) {
    if (is_common_attribute(attribute)) continue;
    bool known = false;
    for (const auto& a : spec->attributes) known = known || a.name == attribute;
    if (known) continue;
    std::vector<std::string_view> names;
    for (const auto& a : spec->attributes) names.push_back(a.name);
    const std::string hint = suggestion(attribute, names);
    if (!warnings) {
      throw make_error(object.location.to_string(), ": ", spec->name, ": unknown attribute '", attribute, "'",
                       hint, "; supported: ", join_names(spec->attributes));
    }
    warnings->push_back(object.location.to_string() + ": " + std::string(spec->name) + ": unknown attribute '" +
                        attribute + "' ignored" + hint + "; supported: " + join_names(spec->attributes));
  }
  return spec;
}

std::string component_documentation() {
  std::ostringstream out;
  for (const auto& spec : table()) {
    out << "### " << spec.name;
    if (!spec.aliases.empty()) {
      out << " (also";
      for (auto alias : spec.aliases) {
        if (alias != spec.name) out << " " << alias;
      }
      out << ")";
    }
    out << "\n\n" << spec.doc << "\n\n| attribute | type | default | meaning |\n|---|---|---|---|\n";
    for (const auto& a : spec.attributes) {
      out << "| `" << a.name << "` | " << a.type << " | " << (a.default_value.empty() ? "—" : a.default_value)
          << " | " << a.doc << " |\n";
    }
    out << "\n";
  }
  out << "Drawn only (no effect on the mechanics): OglModel (VisualModel) with its MeshOBJLoader or MeshSTLLoader,\n"
         "mapped by BarycentricMapping or IdentityMapping.\n\n";
  out << "Accepted without effect on the mechanics (one info line each):";
  for (auto name : kIgnored) {
    if (!is_collision_component(name)) out << " " << name;
  }
  out << ".\n\nIgnored with a warning each, as they change SOFA's mechanics (collisions and contacts are not "
         "simulated):";
  for (auto name : kIgnored) {
    if (is_collision_component(name)) out << " " << name;
  }
  out << ".\n\nRefused, the scene with them, in one line saying what is missing:";
  for (const auto& [name, reason] : refused_components()) out << "\n- " << name << ": " << reason;
  out << "\n";
  return out.str();
}

}  // namespace fastcorot
