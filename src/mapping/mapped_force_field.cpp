#include "fastcorot/mapping/mapped_force_field.h"

#include "fastcorot/core/error.h"

#include <map>
#include <utility>

namespace fastcorot {

template <class Real>
MappedForceField<Real>::MappedForceField(std::shared_ptr<ForceField<Real>> inner, PointMapping<Real> map, Index parent_points)
    : inner_(std::move(inner)), map_(std::move(map)), parent_mesh_(parent_points, std::vector<Tetrahedron>{}) {
  const auto mapped = static_cast<Index>(map_.size());
  if (inner_->mesh().num_points() != mapped) {
    throw make_error(inner_->component(), ": acts on ", inner_->mesh().num_points(), " points, its mapped state has ", mapped);
  }
  if (map_.parent_extent() > parent_points) {
    throw make_error(inner_->component(), ": its mapping reaches point ", map_.parent_extent() - 1, " of a state of ",
                     parent_points, " points");
  }
  x_.resize(map_.size());
  dx_.resize(map_.size());
  f_.resize(map_.size());
}

template <class Real>
void MappedForceField<Real>::set_velocity(std::span<const Vec3<Real>> v) {
  if (v.empty()) {
    v_.clear();
    inner_->set_velocity({});
    return;
  }
  v_.resize(map_.size());
  map_.apply(v, v_);
  inner_->set_velocity(v_);
}

template <class Real>
void MappedForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  map_.apply(x, x_);
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_force(x_, f_);
  map_.apply_jt(f_, f);
}

template <class Real>
void MappedForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  map_.apply(x, x_);
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_force_only(x_, f_);
  map_.apply_jt(f_, f);
}

template <class Real>
void MappedForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                        Real b_factor) const {
  map_.apply(dx, dx_);
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_dforce(dx_, f_, k_factor, b_factor);
  map_.apply_jt(f_, df);
}

template <class Real>
std::vector<Eigen::Triplet<Real>> MappedForceField<Real>::inner_blocks(Real k_factor, Real b_factor) const {
  TripletSink<Real> sink;
  inner_->add_stiffness(sink, k_factor, 0, b_factor);
  return std::move(sink.triplets);
}

template <class Real>
void MappedForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  // Group the inner entries by mapped block (i, j), then spread each block over the parents of i
  // and j: block (p, q) of Jᵀ K J gets w_ip w_jq K_ij.
  std::map<std::pair<Index, Index>, Mat3<Real>> blocks;
  for (const auto& t : inner_blocks(k_factor, b_factor)) {
    auto [it, added] = blocks.try_emplace({t.row() / 3, t.col() / 3}, Mat3<Real>::Zero());
    it->second(t.row() % 3, t.col() % 3) += t.value();
  }
  constexpr auto slots = static_cast<std::size_t>(PointMapping<Real>::kSlots);
  for (const auto& [ij, block] : blocks) {
    const auto i = static_cast<std::size_t>(ij.first), j = static_cast<std::size_t>(ij.second);
    for (std::size_t k = 0; k < slots; ++k) {
      if (map_.weights[i][k] == 0) continue;
      for (std::size_t l = 0; l < slots; ++l) {
        if (map_.weights[j][l] == 0) continue;
        sink.add_block(offset + 3 * map_.vertices[i][k], offset + 3 * map_.vertices[j][l],
                       block * (map_.weights[i][k] * map_.weights[j][l]));
      }
    }
  }
}

template <class Real>
void MappedForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  // The parent's diagonal blocks of Jᵀ K J: every pair of mapped points (i, j) sharing a parent p.
  class DiagonalSink final : public MatrixSink<Real> {
   public:
    explicit DiagonalSink(std::span<Mat3<Real>> d) : d_(d) {}
    void add_block(Index row, Index col, const Mat3<Real>& block) override {
      if (row == col) d_[static_cast<std::size_t>(row / 3)] += block;
    }

   private:
    std::span<Mat3<Real>> d_;
  } sink(diagonal);
  add_stiffness(sink, k_factor, 0, b_factor);
}

template <class Real>
Real MappedForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  std::vector<Vec3<Real>> y(map_.size());
  map_.apply(x, y);
  return inner_->potential_energy(y);
}

template <class Real>
void MappedForceField<Real>::end_step(std::span<const Vec3<Real>> x) {
  map_.apply(x, x_);
  inner_->end_step(x_);
}

template <class Real>
void MappedForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error(inner_->component(), ": topological changes of a force field in a mapped node are not supported");
}

template <class Real>
void MappedForceField<Real>::apply(const TopologyChange&) {
  throw make_error(inner_->component(), ": topological changes of a force field in a mapped node are not supported");
}

template <class Real>
std::vector<double> MappedForceField<Real>::model_values() const {
  std::vector<double> values = inner_->model_values();
  values.push_back(static_cast<double>(map_.size()));
  for (std::size_t i = 0; i < map_.size(); ++i) {
    for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<Real>::kSlots); ++k) {
      if (map_.weights[i][k] == 0) continue;
      values.push_back(static_cast<double>(map_.vertices[i][k]));
      values.push_back(static_cast<double>(map_.weights[i][k]));
    }
  }
  return values;
}

template <class Real>
std::size_t MappedForceField<Real>::memory_bytes() const {
  return inner_->memory_bytes() + map_.size() * (sizeof(map_.vertices[0]) + sizeof(map_.weights[0]) + 4 * sizeof(Vec3<Real>));
}

template class MappedForceField<double>;
template class MappedForceField<float>;

}  // namespace fastcorot
