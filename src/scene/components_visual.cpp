// Surface loaders, visual models and the mappings that carry them on the tetrahedra.
#include "component_families.h"

namespace fastcorot::scene_detail {

std::vector<ComponentSpec> visual_components() {
  return {
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
        {"resizeToModel", "bool", "false", "accepted"}}}
  };
}

}  // namespace fastcorot::scene_detail
