// A component's flat index data read as tuples of N (edges, triangles, quads, tetrahedra), its
// length checked. Internal to src/scene.
#pragma once

#include "scene_data.h"

#include <array>
#include <cstddef>
#include <vector>

namespace fastcorot::scene_detail {

template <std::size_t N>
std::vector<std::array<Index, N>> index_tuples(SceneData& data, Component& component, const char* name) {
  const std::vector<Index> flat = data.indices(component, name);
  if (flat.size() % N != 0) throw make_error(component.where(), ": ", name, " needs ", N, " indices each");
  std::vector<std::array<Index, N>> out(flat.size() / N);
  for (std::size_t e = 0; e < out.size(); ++e) {
    for (std::size_t j = 0; j < N; ++j) out[e][j] = flat[N * e + j];
  }
  return out;
}

}  // namespace fastcorot::scene_detail
