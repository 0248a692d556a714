#include "fastcorot/mapping/rigid_mapping.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <utility>

namespace fastcorot {

template <class Real>
RigidMapping<Real>::RigidMapping(std::string where, std::span<const RigidCoord<Real>> rigids,
                                 std::span<const Vec3<Real>> child_positions,
                                 std::span<const Vec3<Real>> child_rest_positions,
                                 const RigidMappingOptions<Real>& options)
    : where_(std::move(where)), rigid_count_(rigids.size()) {
  const bool has_initial_points = options.initial_points && !options.initial_points->empty();
  // SOFA's getPoints: useX0 reads the child's rest positions (before initialPoints); reinit fills
  // initialPoints from the child only when it is empty and useX0 is off.
  const char* source = "initialPoints";
  if (options.use_x0) {
    local_points_.assign(child_rest_positions.begin(), child_rest_positions.end());
    source = "rest_position of the child (useX0)";
  } else if (has_initial_points) {
    local_points_ = *options.initial_points;
  } else {
    local_points_.assign(child_positions.begin(), child_positions.end());
    source = "position of the child";
  }
  const std::size_t n = local_points_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!local_points_[i].allFinite()) throw make_error(where_, ": point ", i, " of ", source, " is not finite");
  }
  if (n > 0 && rigid_count_ == 0) throw make_error(where_, ": ", n, " mapped points but the input state has no rigid");

  rigid_of_point_.assign(n, 0);
  if (!options.rigid_index_per_point.empty()) {
    if (options.rigid_index_per_point.size() != n) {
      throw make_error(where_, ": rigidIndexPerPoint has ", options.rigid_index_per_point.size(),
                       " entries for ", n, " mapped points (SOFA would ignore it and use index)");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Index k = options.rigid_index_per_point[i];
      if (k < 0 || std::size_t(k) >= rigid_count_) {
        throw make_error(where_, ": rigidIndexPerPoint[", i, "] = ", k, " is out of range [0, ", rigid_count_, ")");
      }
      rigid_of_point_[i] = k;
    }
  } else if (n > 0) {
    const Index k = options.index;
    if (k < 0 || std::size_t(k) >= rigid_count_) {
      throw make_error(where_, ": index ", k, options.index_from_end ? " (from the end)" : "",
                       " is out of range [0, ", rigid_count_, ")");
    }
    rigid_of_point_.assign(n, options.index_from_end ? Index(rigid_count_ - 1 - std::size_t(k)) : k);
  }

  if (options.global_to_local_coords && !options.use_x0 && !has_initial_points) {
    for (std::size_t i = 0; i < n; ++i) {
      const RigidCoord<Real>& frame = rigids[std::size_t(rigid_of_point_[i])];
      local_points_[i] = frame.inverse_rotate(local_points_[i] - frame.center);
    }
  }
  rotated_.resize(n);
  apply(rigids);
}

template <class Real>
void RigidMapping<Real>::check_rigid_count(std::size_t rigids, const char* what) const {
  if (rigids != rigid_count_) {
    throw make_error(where_, ": ", what, " for ", rigids, " rigids, the mapping was made for ", rigid_count_);
  }
}

template <class Real>
void RigidMapping<Real>::apply(std::span<const RigidCoord<Real>> rigids, std::span<Vec3<Real>> out) {
  check_rigid_count(rigids.size(), "apply");
  if (out.size() != size()) throw make_error(where_, ": apply into ", out.size(), " points, the mapping has ", size());
  for (std::size_t i = 0; i < size(); ++i) {
    const RigidCoord<Real>& frame = rigids[std::size_t(rigid_of_point_[i])];
    rotated_[i] = frame.rotate(local_points_[i]);
    out[i] = rotated_[i] + frame.center;
  }
}

template <class Real>
std::vector<Vec3<Real>> RigidMapping<Real>::apply(std::span<const RigidCoord<Real>> rigids) {
  std::vector<Vec3<Real>> out(size());
  apply(rigids, out);
  return out;
}

template <class Real>
void RigidMapping<Real>::apply_j(std::span<const Vec3<Real>> rigid_derivs, std::span<Vec3<Real>> out) const {
  if (rigid_derivs.size() % 2 != 0) throw make_error(where_, ": apply_j needs two Vec3 blocks per rigid");
  check_rigid_count(rigid_derivs.size() / 2, "apply_j");
  if (out.size() != size()) throw make_error(where_, ": apply_j into ", out.size(), " points, the mapping has ", size());
  for (std::size_t i = 0; i < size(); ++i) {
    const std::size_t k = std::size_t(rigid_of_point_[i]);
    out[i] = rigid_derivs[2 * k] + rigid_derivs[2 * k + 1].cross(rotated_[i]);
  }
}

template <class Real>
std::vector<Vec3<Real>> RigidMapping<Real>::apply_j(std::span<const Vec3<Real>> rigid_derivs) const {
  std::vector<Vec3<Real>> out(size());
  apply_j(rigid_derivs, out);
  return out;
}

template <class Real>
void RigidMapping<Real>::apply_jt(std::span<const Vec3<Real>> point_forces, std::span<Vec3<Real>> rigid_blocks) const {
  if (point_forces.size() != size()) {
    throw make_error(where_, ": apply_jt of ", point_forces.size(), " forces, the mapping has ", size(), " points");
  }
  if (rigid_blocks.size() % 2 != 0) throw make_error(where_, ": apply_jt needs two Vec3 blocks per rigid");
  check_rigid_count(rigid_blocks.size() / 2, "apply_jt");
  for (std::size_t i = 0; i < size(); ++i) {
    const std::size_t k = std::size_t(rigid_of_point_[i]);
    rigid_blocks[2 * k] += point_forces[i];
    rigid_blocks[2 * k + 1] += rotated_[i].cross(point_forces[i]);
  }
}

template <class Real>
typename RigidMapping<Real>::SparseMatrix RigidMapping<Real>::jacobian() const {
  const Index rows = Index(3 * size());
  SparseMatrix j(rows, Index(6 * rigid_count_));
  j.reserve(Eigen::VectorXi::Constant(rows, 3));
  for (std::size_t i = 0; i < size(); ++i) {
    const Index row = Index(3 * i);
    const Index col = 6 * rigid_of_point_[i];
    const Vec3<Real>& r = rotated_[i];
    // v + ω × r = v - [r]× ω; column blocks [linear | angular].
    j.insert(row, col) = 1;
    j.insert(row, col + 4) = r[2];
    j.insert(row, col + 5) = -r[1];
    j.insert(row + 1, col + 1) = 1;
    j.insert(row + 1, col + 3) = -r[2];
    j.insert(row + 1, col + 5) = r[0];
    j.insert(row + 2, col + 2) = 1;
    j.insert(row + 2, col + 3) = r[1];
    j.insert(row + 2, col + 4) = -r[0];
  }
  j.makeCompressed();
  return j;
}

template class RigidMapping<float>;
template class RigidMapping<double>;

}  // namespace fastcorot
