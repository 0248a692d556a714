#include "fastcorot/collision/collision_model.h"

#include "fastcorot/collision/intersections.h"
#include "fastcorot/core/error.h"
#include "fastcorot/state/rigid3.h"

#include <algorithm>

namespace fastcorot {

template <class Real>
CollisionPoints<Real> CollisionPoints<Real>::own(std::size_t object, std::vector<Index> blocks) {
  CollisionPoints p;
  p.object_ = object;
  p.blocks_ = std::move(blocks);
  p.x_.assign(p.blocks_.size(), Vec3<Real>::Zero());
  return p;
}

template <class Real>
CollisionPoints<Real> CollisionPoints<Real>::mapped(std::size_t object, std::shared_ptr<MechanicalMapping<Real>> mapping) {
  if (!mapping) throw make_error("CollisionPoints: no mapping");
  CollisionPoints p;
  p.object_ = object;
  p.mapping_ = std::move(mapping);
  p.x_.assign(p.mapping_->size(), Vec3<Real>::Zero());
  return p;
}

template <class Real>
CollisionPoints<Real> CollisionPoints<Real>::still(std::vector<Vec3<Real>> points) {
  CollisionPoints p;
  p.still_ = true;
  p.x_ = std::move(points);
  return p;
}

template <class Real>
CollisionPoints<Real> CollisionPoints<Real>::rigid(std::size_t object, std::vector<Index> linear_blocks) {
  CollisionPoints p = own(object, std::move(linear_blocks));
  p.rigid_ = true;
  return p;
}

template <class Real>
void CollisionPoints<Real>::update(std::span<const SimulatedObject<Real>> objects) {
  if (still_) return;
  const auto& x = objects[object_].system.state.position;
  if (x.size() != checked_size_) {  // the first step, or the object's points changed (cut while running)
    const Index extent = mapping_ ? mapping_->parent_extent()
                                  : (blocks_.empty() ? 0 : *std::max_element(blocks_.begin(), blocks_.end()) + (rigid_ ? 2 : 1));
    if (extent > static_cast<Index>(x.size())) {
      throw make_error(objects[object_].path, " lost points that a collision model reads (cut while running): contacts on a changing ",
                       "topology are not simulated yet");
    }
    checked_size_ = x.size();
  }
  if (mapping_) {
    mapping_->apply(x, x_);
    return;
  }
  for (std::size_t i = 0; i < blocks_.size(); ++i) x_[i] = x[static_cast<std::size_t>(blocks_[i])];
}

template <class Real>
void CollisionPoints<Real>::add_row_blocks(std::size_t i, Real weight, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  if (still_ || weight == 0) return;
  if (!mapping_) {
    out.emplace_back(blocks_[i], weight * Mat3<Real>::Identity());
    return;
  }
  mapping_->row_blocks(i, scratch_);
  for (const auto& [block, j] : scratch_) out.emplace_back(block, weight * j);
}

template <class Real>
void CollisionPoints<Real>::add_rigid_point_blocks(std::size_t i, const Vec3<Real>& r,
                                                   std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  if (!rigid_) throw make_error("CollisionPoints: add_rigid_point_blocks on points that are not rigid centres");
  out.emplace_back(blocks_[i], Mat3<Real>::Identity());
  out.emplace_back(blocks_[i] + 1, -cross_matrix(r));
}

template <class Real>
std::size_t CollisionModel<Real>::size() const {
  switch (kind) {
    case CollisionElements::lines: return edges.size();
    case CollisionElements::triangles: return triangles.size();
    default: return points->size();
  }
}

template <class Real>
int CollisionModel<Real>::update_tree() {
  const auto& x = points->positions();
  const std::size_t n = size();
  if (built_ && (!moving || points->is_still()) && tree_.size() == n) {
    return static_cast<int>(std::count(degenerate_.begin(), degenerate_.end(), char(1)));
  }
  boxes_.resize(n);
  degenerate_.assign(n, 0);
  const auto at = [&](Index p) -> const Vec3<Real>& { return x[static_cast<std::size_t>(p)]; };
  const auto set = [&](std::size_t e, const Vec3<Real>& low, const Vec3<Real>& high, Real grow) {
    boxes_[e].min = low.array() - grow;
    boxes_[e].max = high.array() + grow;
  };
  switch (kind) {  // one loop per kind, each element's box grown by the contact distance (a sphere's by its radius too)
    case CollisionElements::points:
      for (std::size_t e = 0; e < n; ++e) set(e, x[e], x[e], contact_distance);
      break;
    case CollisionElements::spheres:
      for (std::size_t e = 0; e < n; ++e) set(e, x[e], x[e], radii[e] + contact_distance);
      break;
    case CollisionElements::lines:
      for (std::size_t e = 0; e < n; ++e) {
        const Vec3<Real>&a = at(edges[e][0]), &b = at(edges[e][1]);
        set(e, a.cwiseMin(b), a.cwiseMax(b), contact_distance);
        degenerate_[e] = a == b;
      }
      break;
    case CollisionElements::triangles:
      for (std::size_t e = 0; e < n; ++e) {
        const Vec3<Real>&a = at(triangles[e][0]), &b = at(triangles[e][1]), &c = at(triangles[e][2]);
        set(e, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), contact_distance);
        degenerate_[e] = degenerate_triangle(a, b, c);
      }
      break;
  }
  if (built_ && tree_.size() == n) {
    tree_.refit(boxes_);
  } else {
    tree_.build(boxes_);
    built_ = true;
  }
  return static_cast<int>(std::count(degenerate_.begin(), degenerate_.end(), char(1)));
}

template <class Real>
void CollisionModel<Real>::update_neighbourhood() {
  if (!cone_topology || (neighbourhood_built_ && (!moving || points->is_still()))) return;
  compute_local_min_distance_neighbourhood<Real>(*cone_topology, points->positions(), neighbourhood);
  neighbourhood_built_ = true;
}

template <class Real>
bool can_collide(const CollisionModel<Real>& a, const CollisionModel<Real>& b) {
  if (!a.simulated && !b.simulated) return false;
  if (a.node == b.node) return a.self_collision && b.self_collision;
  for (int g : a.groups) {
    if (std::find(b.groups.begin(), b.groups.end(), g) != b.groups.end()) return false;
  }
  return true;
}

template class CollisionPoints<double>;
template struct CollisionModel<double>;
template bool can_collide(const CollisionModel<double>&, const CollisionModel<double>&);

}  // namespace fastcorot
