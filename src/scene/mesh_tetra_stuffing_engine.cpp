// SOFA's MeshTetraStuffing engine (Sofa.Component.Engine.Generate): reads the surface
// (inputPoints with inputTriangles and/or inputQuads) and its options, and gives outputPoints,
// outputTetrahedra (also outputTetras) and the box used (vbbox), computed once
// (fastcorot/topology/mesh_tetra_stuffing.h).
#include "engine_data.h"

#include "fastcorot/topology/mesh_tetra_stuffing.h"

namespace fastcorot::scene_detail {

Numbers mesh_tetra_stuffing(SceneData& scene, Component& c, const std::string& name) {
  const bool output = name == "outputPoints" || name == "outputTetrahedra" || name == "outputTetras" ||
                      (name == "vbbox" && !c.has("vbbox"));
  if (!output) return {};
  const auto points = points_from(scene.data(c, "inputPoints"), c, "inputPoints");
  const auto triangles = cells_from<3>(scene.data(c, "inputTriangles"), c, "inputTriangles", points.size());
  const auto quads = cells_from<4>(scene.data(c, "inputQuads"), c, "inputQuads", points.size());
  TetraStuffingOptions options;
  if (c.has("vbbox")) {
    const Numbers& box = scene.data(c, "vbbox");
    if (box.size() != 6) throw make_error(c.where(), ": vbbox needs 6 numbers (xmin ymin zmin xmax ymax zmax)");
    options.bbox = {Vec3<double>(box[0], box[1], box[2]), Vec3<double>(box[3], box[4], box[5])};
  }
  options.size = scene.real(c, "size", -8.0);
  options.alpha_long = scene.real(c, "alphaLong", 0.24999);
  options.alpha_short = scene.real(c, "alphaShort", 0.42978);
  options.snap_points = scene.boolean(c, "snapPoints", false);
  options.split_tetrahedra = c.has("splitTetrahedra") ? scene.boolean(c, "splitTetrahedra", false)
                                                     : scene.boolean(c, "splitTetras", false);
  TetraStuffing stuffed;
  try {
    stuffed = stuff_tetrahedra(points, triangles, quads, options);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
  Numbers out_points, out_tetrahedra;
  for (const auto& p : stuffed.points) out_points.insert(out_points.end(), {p[0], p[1], p[2]});
  for (const auto& t : stuffed.tetrahedra) {
    for (Index v : t) out_tetrahedra.push_back(static_cast<double>(v));
  }
  const Numbers box = {stuffed.bbox[0][0], stuffed.bbox[0][1], stuffed.bbox[0][2],
                       stuffed.bbox[1][0], stuffed.bbox[1][1], stuffed.bbox[1][2]};
  // Every output at once: the stuffing runs once.
  c.cache.emplace("outputPoints", out_points);
  c.cache.emplace("outputTetrahedra", out_tetrahedra);
  c.cache.emplace("outputTetras", out_tetrahedra);
  if (!c.has("vbbox")) c.cache.emplace("vbbox", box);
  if (name == "outputPoints") return out_points;
  if (name == "vbbox") return box;
  return out_tetrahedra;
}

}  // namespace fastcorot::scene_detail
