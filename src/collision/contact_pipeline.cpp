#include "fastcorot/collision/contact_pipeline.h"

#include "fastcorot/collision/self_collision.h"
#include "fastcorot/core/parallel.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <chrono>

namespace fastcorot {

template <class Real>
std::vector<typename ContactPipeline<Real>::ModelPair> ContactPipeline<Real>::rule_pairs(const std::vector<CollisionModel<Real>>& models,
                                                                                         const Parameters& p) {
  std::vector<ModelPair> pairs;
  for (std::size_t later = 0; later < models.size(); ++later) {
    // SOFA's broad phase pairs a simulated model with selfCollision with itself first.
    const auto& m = models[later];
    if (m.self_collision && m.simulated && !m.points->is_still() && has_rule(p, m, m)) pairs.push_back({later, later});
    for (std::size_t earlier = 0; earlier < later; ++earlier) {
      if (!can_collide(models[earlier], models[later])) continue;
      if (models[earlier].points->is_still() && models[later].points->is_still()) continue;  // nothing can move
      // SOFA's broad phase asks for the intersector of (new model, earlier one) and swaps them into
      // the intersector's order (Triangle before Line before Sphere before Point).
      ModelPair pair{later, earlier};
      if (element_rank(models[earlier].kind) > element_rank(models[later].kind)) std::swap(pair.first, pair.second);
      // Among spheres, SOFA's intersectors take a Vec3 sphere before a rigid one.
      const auto rigid = [&](std::size_t m) { return models[m].kind == CollisionElements::spheres && models[m].points->is_rigid(); };
      if (models[earlier].kind == models[later].kind && rigid(pair.first) && !rigid(pair.second)) std::swap(pair.first, pair.second);
      if (has_rule(p, models[pair.first], models[pair.second])) pairs.push_back(pair);
    }
  }
  return pairs;
}

template <class Real>
ContactPipeline<Real>::ContactPipeline(Parameters parameters, std::vector<CollisionModel<Real>> models, Responses responses)
    : parameters_(parameters), models_(std::move(models)), responses_(std::move(responses)) {
  for (const auto& m : models_) {
    if (!m.points) throw make_error(m.where, ": a collision model without points");
  }
  pairs_ = rule_pairs(models_, parameters_);
  if (responses_.kind.size() != pairs_.size()) {
    throw make_error("the collision pipeline has ", pairs_.size(), " model pairs but ", responses_.kind.size(), " responses");
  }
  responses_.explicit_pairs.resize(pairs_.size(), 0);
  responses_.constraints.resize(pairs_.size());
  responses_.stick_constraints.resize(pairs_.size());
  check_pairs();
  stick_springs_.resize(pairs_.size());
  stick_contacts_.resize(pairs_.size());
}

template <class Real>
void ContactPipeline<Real>::check_pairs() {
  const auto& r = responses_;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::string& where = models_[pairs_[k].first].where;
    const Response kind = r.kind[k];
    if (kind == Response::friction && !r.constraints[k]) throw make_error(where, ": no contact constraint for its pair");
    if (kind == Response::stick_constraint && !r.stick_constraints[k]) throw make_error(where, ": no stick constraint for its pair");
    if (kind != Response::penalty && kind != Response::stick_springs) continue;
    const auto& a = *models_[pairs_[k].first].points;
    const auto& b = *models_[pairs_[k].second].points;
    const bool is_explicit = r.explicit_pairs[k] != 0;
    if (!is_explicit && !a.is_still() && !b.is_still() && a.object() != b.object()) {
      throw make_error(where, " and ", models_[pairs_[k].second].where,
                       " are on two bodies each integrated by its own ODE solver: their contacts can only be explicit");
    }
    for (const auto* side : {&a, &b}) {
      if (side->is_still()) continue;
      const auto o = side->object();
      const bool present = is_explicit                ? o < r.explicit_forces.size() && r.explicit_forces[o]
                           : kind == Response::penalty ? o < r.penalties.size() && r.penalties[o]
                                                       : o < r.sticks.size() && r.sticks[o];
      if (!present) throw make_error(where, ": no contact force field on its object");
    }
  }
}

template <class Real>
std::vector<typename ContactPipeline<Real>::Output> ContactPipeline<Real>::narrow_phase(const ModelPair& pair, CollisionReport& report) const {
  const auto& m1 = models_[pair.first];
  const auto& m2 = models_[pair.second];
  const ProximityDistances<Real> d = pair_distances(parameters_, m1, m2);
  std::vector<std::pair<Index, Index>> candidates;
  if (pair.first == pair.second) {
    // A model against itself: SOFA's CollisionElementIterator::canCollideWith takes each pair once,
    // (i, j) with i < j, before the elements' own rules prune it.
    m1.tree().self_pairs(d.alarm, candidates);
  } else {
    AabbTree<Real>::pairs(m1.tree(), m2.tree(), d.alarm, candidates);
  }
  const bool one_node = m1.node == m2.node;
  if (!candidates.empty()) ++report.model_pairs;
  report.element_pairs += static_cast<long>(candidates.size());
  // Fixed chunks of the candidates (in SOFA's traversal order), their outputs joined in chunk order.
  const Chunks chunks(candidates.size());
  std::vector<std::vector<Output>> found(chunks.count);
  run_tasks(threads_, static_cast<int>(chunks.count), [&](int c) {
    const auto k = static_cast<std::size_t>(c);
    std::span<const std::pair<Index, Index>> chunk(candidates.data() + chunks.begin(k), chunks.end(k) - chunks.begin(k));
    std::vector<std::pair<Index, Index>> kept;
    if (one_node) {  // elements of one node: the pairs SOFA's canCollideWith lets through
      for (const auto& [e1, e2] : chunk) {
        if (can_collide_elements<Real>(models_, pair.first, e1, pair.second, e2) && !elements_touch(m1, e1, m2, e2)) kept.emplace_back(e1, e2);
      }
      chunk = kept;
    }
    intersect_elements(parameters_, m1, m2, chunk, d, found[k]);
  });
  if (found.size() == 1) return std::move(found.front());
  std::vector<Output> outputs;
  for (auto& part : found) outputs.insert(outputs.end(), part.begin(), part.end());
  return outputs;
}

template <class Real>
Vec3<Real> ContactPipeline<Real>::add_side(const CollisionModel<Real>& model, Index element, const Vec3<Real>& p,
                                           std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  const auto& x = model.points->positions();
  const auto e = static_cast<std::size_t>(element);
  const auto at = [&](Index i) -> const Vec3<Real>& { return x[static_cast<std::size_t>(i)]; };
  switch (model.kind) {
    case CollisionElements::points: model.points->add_row_blocks(e, Real(1), out); return x[e];
    case CollisionElements::spheres:
      // SOFA's mappers: a Vec3 sphere's contact is its centre (identity); a rigid sphere's is the
      // detected point, carried by the rigid (RigidContactMapper).
      if (!model.points->is_rigid()) {
        model.points->add_row_blocks(e, Real(1), out);
        return x[e];
      }
      model.points->add_rigid_point_blocks(e, p - x[e], out);
      return p;
    case CollisionElements::lines: {
      const Edge& s = model.edges[e];
      const Vec3<Real> ab = at(s[1]) - at(s[0]);
      const Real length2 = ab.dot(ab);
      const Real alpha = length2 > 0 ? (p - at(s[0])).dot(ab) / length2 : Real(0);
      model.points->add_row_blocks(static_cast<std::size_t>(s[0]), 1 - alpha, out);
      model.points->add_row_blocks(static_cast<std::size_t>(s[1]), alpha, out);
      return at(s[0]) * (1 - alpha) + at(s[1]) * alpha;
    }
    case CollisionElements::triangles: {
      const Triangle& t = model.triangles[e];
      const Vec3<Real> ab = at(t[1]) - at(t[0]), ac = at(t[2]) - at(t[0]), ap = p - at(t[0]);
      const Real a00 = ab.dot(ab), a11 = ac.dot(ac), a01 = ab.dot(ac), det = a00 * a11 - a01 * a01;
      const Real alpha = (ap.dot(ab) * a11 - ap.dot(ac) * a01) / det, beta = (ap.dot(ac) * a00 - ap.dot(ab) * a01) / det;
      model.points->add_row_blocks(static_cast<std::size_t>(t[0]), 1 - alpha - beta, out);
      model.points->add_row_blocks(static_cast<std::size_t>(t[1]), alpha, out);
      model.points->add_row_blocks(static_cast<std::size_t>(t[2]), beta, out);
      return at(t[0]) * (1 - alpha - beta) + at(t[1]) * alpha + at(t[2]) * beta;
    }
  }
  return p;
}

template <class Real>
void ContactPipeline<Real>::record(const ModelPair& pair, const Output& output) {
  const auto& p = output.proximity;
  detected_.push_back({{p.point[0], p.point[1]}, p.normal});
  if (p.null_distance) return;  // its normal is arbitrary: no side to cross
  Watch w;
  w.normal = p.normal;
  const Index elements[2] = {output.first, output.second};
  const std::size_t models[2] = {pair.first, pair.second};
  for (int side = 0; side < 2; ++side) {
    const CollisionModel<Real>& m = models_[models[side]];
    const auto& x = m.points->positions();
    const auto at = [&](Index i) -> const Vec3<Real>& { return x[static_cast<std::size_t>(i)]; };
    const auto e = static_cast<std::size_t>(elements[side]);
    w.model[side] = models[side];
    switch (m.kind) {
      case CollisionElements::spheres: return;  // not watched
      case CollisionElements::points:
        w.points[side] = {elements[side], 0, 0};
        w.weights[side] = {Real(1), Real(0), Real(0)};
        w.count[side] = 1;
        break;
      case CollisionElements::lines: {
        const Edge& s = m.edges[e];
        const Vec3<Real> ab = at(s[1]) - at(s[0]);
        const Real alpha = ab.squaredNorm() > 0 ? (p.point[side] - at(s[0])).dot(ab) / ab.squaredNorm() : Real(0);
        w.points[side] = {s[0], s[1], 0};
        w.weights[side] = {1 - alpha, alpha, Real(0)};
        w.count[side] = 2;
        break;
      }
      case CollisionElements::triangles: {
        const Triangle& t = m.triangles[e];
        const Vec3<Real> ab = at(t[1]) - at(t[0]), ac = at(t[2]) - at(t[0]), ap = p.point[side] - at(t[0]);
        const Real a00 = ab.dot(ab), a11 = ac.dot(ac), a01 = ab.dot(ac), det = a00 * a11 - a01 * a01;
        if (!(std::abs(det) > 0)) return;
        const Real alpha = (ap.dot(ab) * a11 - ap.dot(ac) * a01) / det, beta = (ap.dot(ac) * a00 - ap.dot(ab) * a01) / det;
        w.points[side] = t;
        w.weights[side] = {1 - alpha - beta, alpha, beta};
        w.count[side] = 3;
        break;
      }
    }
  }
  watch_.push_back(w);
}

template <class Real>
void ContactPipeline<Real>::end_step(std::span<SimulatedObject<Real>> objects, CollisionReport& report) {
  if (watch_.empty()) return;
  std::vector<CollisionPoints<Real>*> done;
  for (const Watch& w : watch_) {
    for (const std::size_t m : w.model) {
      CollisionPoints<Real>* points = models_[m].points.get();
      if (std::find(done.begin(), done.end(), points) != done.end()) continue;
      points->update(objects);  // the end positions (begin_step updates them again)
      done.push_back(points);
    }
  }
  for (const Watch& w : watch_) {
    Vec3<Real> y[2];
    for (int side = 0; side < 2; ++side) {
      const auto& x = models_[w.model[side]].points->positions();
      y[side] = Vec3<Real>::Zero();
      for (int i = 0; i < w.count[side]; ++i) y[side] += x[static_cast<std::size_t>(w.points[side][static_cast<std::size_t>(i)])] * w.weights[side][static_cast<std::size_t>(i)];
    }
    const Real gap = (y[1] - y[0]).dot(w.normal);
    if (!(gap < 0)) continue;
    ++report.crossed;
    if (-gap > report.deepest_crossing) {
      report.deepest_crossing = static_cast<double>(-gap);
      report.crossed_models = models_[w.model[0]].where + " and " + models_[w.model[1]].where;
    }
  }
}

template <class Real>
CollisionReport ContactPipeline<Real>::begin_step(std::span<SimulatedObject<Real>> objects, Real, double) {
  const auto start = std::chrono::steady_clock::now();
  CollisionReport report;
  // The models of a node share their points: each set of points updated once.
  std::vector<CollisionPoints<Real>*> points;
  for (auto& m : models_) {
    if (std::find(points.begin(), points.end(), m.points.get()) == points.end()) points.push_back(m.points.get());
  }
  run_tasks(threads_, static_cast<int>(points.size()), [&](int i) { points[static_cast<std::size_t>(i)]->update(objects); });
  std::vector<int> degenerate(models_.size(), 0);
  run_tasks(threads_, static_cast<int>(models_.size()), [&](int i) {
    auto& m = models_[static_cast<std::size_t>(i)];
    try {
      degenerate[static_cast<std::size_t>(i)] = m.update_tree();
      m.update_neighbourhood();
    } catch (const Error& error) {
      throw error_at(m.where, error);
    }
  });
  for (const int d : degenerate) report.degenerate_elements += d;
  auto& r = responses_;
  std::vector<std::vector<PenaltyContact<Real>>> contacts(r.penalties.size());
  detected_.clear();
  watch_.clear();
  for (auto& forces : r.explicit_forces) {
    if (forces) forces->clear();
  }
  std::vector<std::vector<StickSpring<Real>>> springs(r.sticks.size());
  bool kept_alive = false;  // a response that follows its points from the last step's positions
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const Response kind = r.kind[k];
    if (kind == Response::none) continue;
    const std::vector<Output> outputs = narrow_phase(pairs_[k], report);
    switch (kind) {
      case Response::friction: report.contacts += friction_response(k, outputs); break;
      case Response::stick_constraint: report.contacts += stick_constraint_response(k, outputs, objects); break;
      case Response::stick_springs: report.contacts += stick_response(k, outputs, objects, springs); break;
      case Response::penalty: report.contacts += penalty_response(k, outputs, contacts); break;
      case Response::none: break;
    }
    kept_alive = kept_alive || kind == Response::stick_springs || kind == Response::stick_constraint;
  }
  for (std::size_t o = 0; o < r.penalties.size(); ++o) {
    if (r.penalties[o]) r.penalties[o]->set_contacts(std::move(contacts[o]), objects[o].system.state.position);
  }
  for (std::size_t o = 0; o < r.sticks.size(); ++o) {
    if (r.sticks[o]) r.sticks[o]->set_springs(std::move(springs[o]), objects[o].system.state.position);
  }
  if (kept_alive) last_positions_.resize(objects.size());
  for (std::size_t o = 0; o < last_positions_.size(); ++o) {
    last_positions_[o].assign(objects[o].system.state.position.begin(), objects[o].system.state.position.end());
  }
  report.detection_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

template class ContactPipeline<double>;

}  // namespace fastcorot
