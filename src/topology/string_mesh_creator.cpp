#include "fastcorot/topology/string_mesh_creator.h"

#include "fastcorot/core/error.h"

#include <limits>

namespace fastcorot {

StringMesh string_mesh(long long resolution) {
  if (resolution < 0 || resolution == 1 || resolution > std::numeric_limits<Index>::max()) {
    throw make_error("resolution = ", resolution, ": needs 0 or at least 2 points (and fewer than 2^31)");
  }
  StringMesh mesh;
  const auto n = static_cast<Index>(resolution);
  for (Index x = 0; x < n; ++x) mesh.points.emplace_back(static_cast<double>(x) * 1. / static_cast<double>(n - 1), 0, 0);
  for (Index e = 1; e < n; ++e) mesh.edges.push_back({e - 1, e});
  return mesh;
}

}  // namespace fastcorot
