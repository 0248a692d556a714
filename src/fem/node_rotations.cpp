#include "fastcorot/fem/node_rotations.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
std::vector<Mat3<Real>> node_rotations(const ForceField<Real>& field, Index points) {
  const std::vector<Mat3<Real>> element = field.rotations();
  const auto tetrahedra = field.mesh().tetrahedra();
  if (element.size() != tetrahedra.size()) {
    throw make_error(field.component(), ": ", element.size(), " rotations for ", tetrahedra.size(), " tetrahedra");
  }
  std::vector<Mat3<Real>> sum(static_cast<std::size_t>(points), Mat3<Real>::Zero());
  std::vector<int> count(static_cast<std::size_t>(points), 0);
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
    for (Index v : tetrahedra[t]) {
      if (v < 0 || v >= points) throw make_error(field.component(), ": point ", v, " outside a state of ", points);
      sum[static_cast<std::size_t>(v)] += element[t];
      ++count[static_cast<std::size_t>(v)];
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i) {
    if (count[i] == 0) {
      sum[i].setIdentity();
    } else {
      sum[i] /= static_cast<Real>(count[i]);
    }
  }
  return sum;
}

template std::vector<Mat3<float>> node_rotations(const ForceField<float>&, Index);
template std::vector<Mat3<double>> node_rotations(const ForceField<double>&, Index);

}  // namespace fastcorot
