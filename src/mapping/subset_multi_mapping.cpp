#include "fastcorot/mapping/subset_multi_mapping.h"

#include "fastcorot/core/error.h"

#include <algorithm>

namespace fastcorot {

namespace {

template <class Real>
std::vector<std::size_t> input_starts(const std::vector<std::unique_ptr<MechanicalMapping<Real>>>& inputs) {
  std::vector<std::size_t> first;
  std::size_t n = 0;
  for (const auto& input : inputs) {
    first.push_back(n);
    n += input->size();
  }
  return first;
}

}  // namespace

template <class Real>
SubsetMultiMapping<Real>::SubsetMultiMapping(std::vector<std::unique_ptr<MechanicalMapping<Real>>> inputs,
                                             std::vector<std::pair<std::size_t, Index>> pairs)
    : inputs_([&] {
        // The picks are checked against the inputs before they are stacked.
        const auto first = input_starts(inputs);
        picked_.reserve(pairs.size());
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          const auto [k, j] = pairs[i];
          if (k >= inputs.size()) {
            throw make_error("indexPairs: point ", i, " takes input ", k, ", there are ", inputs.size(), " inputs");
          }
          if (j < 0 || static_cast<std::size_t>(j) >= inputs[k]->size()) {
            throw make_error("indexPairs: point ", i, " takes point ", j, " of input ", k, ", which has ", inputs[k]->size(), " points");
          }
          picked_.push_back(first[k] + static_cast<std::size_t>(j));
        }
        return StackedMapping<Real>(std::move(inputs));
      }()),
      stacked_(inputs_.size(), Vec3<Real>::Zero()) {}

template <class Real>
void SubsetMultiMapping<Real>::pick(std::span<Vec3<Real>> y) const {
  for (std::size_t i = 0; i < picked_.size(); ++i) y[i] = stacked_[picked_[i]];
}

template <class Real>
void SubsetMultiMapping<Real>::apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) {
  inputs_.apply(x, stacked_);
  pick(y);
}

// (Outputs may ask from several threads: these two use a buffer of their own.)
template <class Real>
void SubsetMultiMapping<Real>::positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const {
  std::vector<Vec3<Real>> stacked(inputs_.size());
  inputs_.positions(x, stacked);
  for (std::size_t i = 0; i < picked_.size(); ++i) y[i] = stacked[picked_[i]];
}

template <class Real>
void SubsetMultiMapping<Real>::velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const {
  std::vector<Vec3<Real>> stacked(inputs_.size());
  inputs_.velocities(x, v, stacked);
  for (std::size_t i = 0; i < picked_.size(); ++i) y[i] = stacked[picked_[i]];
}

template <class Real>
void SubsetMultiMapping<Real>::apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const {
  inputs_.apply_j(dx, stacked_);
  pick(dy);
}

template <class Real>
void SubsetMultiMapping<Real>::apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const {
  std::fill(stacked_.begin(), stacked_.end(), Vec3<Real>::Zero());
  for (std::size_t i = 0; i < picked_.size(); ++i) stacked_[picked_[i]] += f[i];
  inputs_.apply_jt(stacked_, parent);
}

template <class Real>
void SubsetMultiMapping<Real>::row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  inputs_.row_blocks(picked_[i], out);
}

template <class Real>
std::vector<double> SubsetMultiMapping<Real>::model_values() const {
  std::vector<double> values = inputs_.model_values();
  values.push_back(static_cast<double>(picked_.size()));
  for (std::size_t p : picked_) values.push_back(static_cast<double>(p));
  return values;
}

template class SubsetMultiMapping<double>;

}  // namespace fastcorot
