#include "fastcorot/sim/visual_surface.h"

namespace fastcorot {

std::vector<Vec3<double>> VisualSurface::points(std::span<const Vec3<double>> x) const {
  if (rigid) {
    std::vector<Vec3<double>> out(rigid->size());
    rigid->positions(x, out);
    return out;
  }
  std::vector<Vec3<double>> out(map.size());
  if (through) {
    std::vector<Vec3<double>> inner(through->size());
    through->positions(x.subspan(static_cast<std::size_t>(through_offset)), inner);
    map.apply(inner, out);
    return out;
  }
  map.apply(x, out);
  return out;
}

}  // namespace fastcorot
