// Internal to the scene builder: the data of SOFA's engines SubsetTopology, MeshTetraStuffing,
// MeshSplittingEngine, TransformEngine and PointsFromIndices as SceneData::compute asks for them
// (their inputs' defaults and their outputs), computed at load as SOFA computes them at init. One
// file per engine: subset_topology.cpp, mesh_tetra_stuffing_engine.cpp, mesh_splitting_engine.cpp,
// transform_engine.cpp, points_from_indices.cpp.
#pragma once

#include "scene_data.h"

#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace fastcorot::scene_detail {

// Data `name` of a SubsetTopology (boxes or spheres selecting points and elements, renumbered
// locally on request).
Numbers subset_topology(SceneData& scene, Component& c, const std::string& name);
// Data `name` of a MeshTetraStuffing (fastcorot/topology/mesh_tetra_stuffing.h).
Numbers mesh_tetra_stuffing(SceneData& scene, Component& c, const std::string& name);
// Data `name` of a MeshSplittingEngine (points shared among sub-meshes by index lists).
Numbers mesh_splitting_engine(SceneData& scene, Component& c, const std::string& name);
// Data `name` of a TransformEngine (input_position scaled, rotated, translated).
Numbers transform_engine(SceneData& scene, Component& c, const std::string& name);
// Data `name` of a PointsFromIndices (the points of position at indices).
Numbers points_from_indices(SceneData& scene, Component& c, const std::string& name);

// What the component's src="@..." provides for `name` (same-named data of the linked component),
// or nullopt when it has no src.
std::optional<Numbers> from_src(SceneData& scene, Component& c, const std::string& name);

// Groups a flat list of indices into cells of N, each index checked against `point_count`: throws
// fastcorot::Error naming c and the data.
template <std::size_t N>
std::vector<std::array<Index, N>> cells_from(const Numbers& values, const Component& c, const std::string& name,
                                             std::size_t point_count) {
  if (values.size() % N != 0) {
    throw make_error(c.where(), ": ", name, " needs ", N, " point indices per element, got ", values.size(),
                     " numbers");
  }
  std::vector<std::array<Index, N>> cells(values.size() / N);
  for (std::size_t e = 0; e < cells.size(); ++e) {
    for (std::size_t k = 0; k < N; ++k) {
      const double v = values[N * e + k];
      if (!(v >= 0) || v >= static_cast<double>(point_count) || v != std::floor(v)) {
        throw make_error(c.where(), ": ", name, ": element ", e, " has point ", v, ", not an index below the ",
                         point_count, " points");
      }
      cells[e][k] = static_cast<Index>(v);
    }
  }
  return cells;
}

}  // namespace fastcorot::scene_detail
