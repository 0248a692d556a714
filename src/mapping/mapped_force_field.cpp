#include "fastcorot/mapping/mapped_force_field.h"

#include "fastcorot/core/error.h"

#include <map>
#include <utility>

namespace fastcorot {

template <class Real>
MappedForceField<Real>::MappedForceField(std::shared_ptr<ForceField<Real>> inner, std::unique_ptr<MechanicalMapping<Real>> map,
                                         Index parent_points)
    : inner_(std::move(inner)), map_(std::move(map)), parent_mesh_(parent_points, std::vector<Tetrahedron>{}) {
  const auto mapped = static_cast<Index>(map_->size());
  if (inner_->mesh().num_points() != mapped) {
    throw make_error(inner_->component(), ": acts on ", inner_->mesh().num_points(), " points, its mapped state has ", mapped);
  }
  if (map_->parent_extent() > parent_points) {
    throw make_error(inner_->component(), ": its mapping reaches point ", map_->parent_extent() - 1, " of a state of ",
                     parent_points, " points");
  }
  x_.resize(map_->size());
  dx_.resize(map_->size());
  f_.resize(map_->size());
}

template <class Real>
void MappedForceField<Real>::set_velocity(std::span<const Vec3<Real>> v) {
  // The mapped velocities J v need J at the positions add_force is given: they are made there.
  parent_velocity_ = v;
  if (v.empty()) inner_->set_velocity({});
}

template <class Real>
void MappedForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  map_->apply(x, x_);
  if (!parent_velocity_.empty()) {
    v_.resize(map_->size());
    map_->apply_j(parent_velocity_, v_);
    inner_->set_velocity(v_);
  }
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_force(x_, f_);
  map_->apply_jt(f_, f);
}

template <class Real>
void MappedForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  map_->apply(x, x_);
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_force_only(x_, f_);
  map_->apply_jt(f_, f);
}

template <class Real>
void MappedForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                        Real b_factor) const {
  map_->apply_j(dx, dx_);
  std::fill(f_.begin(), f_.end(), Vec3<Real>::Zero());
  inner_->add_dforce(dx_, f_, k_factor, b_factor);
  map_->apply_jt(f_, df);
}

template <class Real>
std::vector<Eigen::Triplet<Real>> MappedForceField<Real>::inner_blocks(Real k_factor, Real b_factor) const {
  TripletSink<Real> sink;
  inner_->add_stiffness(sink, k_factor, 0, b_factor);
  return std::move(sink.triplets);
}

template <class Real>
void MappedForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  // Group the inner entries by mapped block (i, j), then spread each block over the parent blocks
  // of i and j: block (p, q) of Jᵀ K J gets J_ipᵀ K_ij J_jq.
  std::map<std::pair<Index, Index>, Mat3<Real>> blocks;
  for (const auto& t : inner_blocks(k_factor, b_factor)) {
    auto [it, added] = blocks.try_emplace({t.row() / 3, t.col() / 3}, Mat3<Real>::Zero());
    it->second(t.row() % 3, t.col() % 3) += t.value();
  }
  std::vector<std::pair<Index, Mat3<Real>>> row_i, row_j;
  for (const auto& [ij, block] : blocks) {
    map_->row_blocks(static_cast<std::size_t>(ij.first), row_i);
    map_->row_blocks(static_cast<std::size_t>(ij.second), row_j);
    for (const auto& [p, jp] : row_i) {
      for (const auto& [q, jq] : row_j) sink.add_block(offset + 3 * p, offset + 3 * q, jp.transpose() * block * jq);
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
  std::vector<Vec3<Real>> y(map_->size());
  map_->positions(x, y);
  return inner_->potential_energy(y);
}

template <class Real>
void MappedForceField<Real>::end_step(std::span<const Vec3<Real>> x) {
  map_->apply(x, x_);
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
  const std::vector<double> mapping = map_->model_values();
  values.insert(values.end(), mapping.begin(), mapping.end());
  return values;
}

template <class Real>
std::size_t MappedForceField<Real>::memory_bytes() const {
  constexpr std::size_t slots = PointMapping<Real>::kSlots;
  return inner_->memory_bytes() + map_->size() * (slots * (sizeof(Index) + sizeof(Real)) + 4 * sizeof(Vec3<Real>));
}

template class MappedForceField<double>;
template class MappedForceField<float>;

}  // namespace fastcorot
