// The responses of ContactPipeline (contact_pipeline.h): what one model pair's detection outputs
// become this step: penalty contacts, stick springs, or the contacts of its Lagrangian
// constraint (FrictionContactConstraint's unilateral rows, StickContactConstraint's bilateral ones).
#include "fastcorot/collision/contact_jacobian.h"
#include "fastcorot/collision/contact_pipeline.h"
#include "fastcorot/sim/simulation.h"

#include <algorithm>
#include <cmath>

namespace fastcorot {

template <class Real>
PenaltyContact<Real> ContactPipeline<Real>::contact(const ModelPair& pair, const Output& output) const {
  const auto& m1 = models_[pair.first];
  const auto& m2 = models_[pair.second];
  PenaltyContact<Real> c;
  // The contact points as SOFA's mappers place them: weights in the element, applied to its points.
  c.y1 = add_side(m1, output.first, output.proximity.point[0], c.side1);
  c.y2 = add_side(m2, output.second, output.proximity.point[1], c.side2);
  c.normal = output.proximity.normal;
  // SOFA's BarycentricPenalityContact: d = contactDistance + cd₁ + cd₂, k = ks₁ ks₂ / d.
  c.distance = contact_distance(pair, output);
  const Real ks = m1.contact_stiffness * m2.contact_stiffness;
  c.stiffness = c.distance != 0 ? ks / c.distance : ks;
  return c;
}

template <class Real>
Real ContactPipeline<Real>::contact_distance(const ModelPair& pair, const Output& output) const {
  const auto& m1 = models_[pair.first];
  const auto& m2 = models_[pair.second];
  // The method's contact distance (none for DiscreteIntersection) and the models'; a sphere's
  // contact mapper adds its radius (a rigid sphere's too, though its contact point is already on
  // its surface: SOFA's RigidContactMapper, docs/collision.md §9 quirk 8).
  const Real method = parameters_.method == IntersectionMethod::discrete ? Real(0) : parameters_.contact_distance;
  Real d = method + m1.contact_distance + m2.contact_distance;
  if (m1.kind == CollisionElements::spheres) d += m1.radii[static_cast<std::size_t>(output.first)];
  if (m2.kind == CollisionElements::spheres) d += m2.radii[static_cast<std::size_t>(output.second)];
  return d;
}

template <class Real>
std::vector<std::size_t> ContactPipeline<Real>::kept_by_id(const std::vector<Output>& outputs) {
  // Per id, the output of the smallest value, the first of equal ones; kept in output order.
  std::vector<std::pair<std::int64_t, std::size_t>> by_id(outputs.size());
  for (std::size_t i = 0; i < outputs.size(); ++i) by_id[i] = {outputs[i].id, i};
  std::sort(by_id.begin(), by_id.end());
  std::vector<std::size_t> order;
  for (std::size_t g = 0; g < by_id.size();) {
    std::size_t best = by_id[g].second, end = g + 1;
    for (; end < by_id.size() && by_id[end].first == by_id[g].first; ++end) {
      if (outputs[by_id[end].second].proximity.value < outputs[best].proximity.value) best = by_id[end].second;
    }
    order.push_back(best);
    g = end;
  }
  std::sort(order.begin(), order.end());
  return order;
}

template <class Real>
int ContactPipeline<Real>::penalty_response(std::size_t k, const std::vector<Output>& outputs,
                                            std::vector<std::vector<PenaltyContact<Real>>>& contacts) {
  const ModelPair& pair = pairs_[k];
  const std::vector<std::size_t> order = kept_by_id(outputs);
  const auto& a = *models_[pair.first].points;
  const auto& b = *models_[pair.second].points;
  for (const std::size_t i : order) {
    PenaltyContact<Real> c = contact(pair, outputs[i]);
    record(pair, outputs[i]);
    if (!responses_.explicit_pairs[k]) {
      contacts[a.is_still() ? b.object() : a.object()].push_back(std::move(c));
      continue;
    }
    // SOFA's explicit penalty: the force at the step's start positions, a load on both sides.
    const Real pen = c.distance - (c.y2 - c.y1).dot(c.normal);
    if (!(pen > 0)) continue;
    const Vec3<Real> force = c.normal * (c.stiffness * pen);
    if (!a.is_still()) {
      for (const auto& [block, j] : c.side1) responses_.explicit_forces[a.object()]->add(block, j.transpose() * -force);
    }
    if (!b.is_still()) {
      for (const auto& [block, j] : c.side2) responses_.explicit_forces[b.object()]->add(block, j.transpose() * force);
    }
  }
  return static_cast<int>(order.size());
}

template <class Real>
std::vector<const typename ContactPipeline<Real>::Output*> ContactPipeline<Real>::without_duplicates(const std::vector<Output>& outputs) {
  // SOFA's Lagrangian contact responses drop an output whose two points are both near a kept one's:
  // |Δp₀|² + |Δp₁|² below 1e-8 (a float constant, widened).
  const Real near = static_cast<Real>(static_cast<double>(0.00000001f));
  std::vector<const Output*> kept;
  for (const Output& o : outputs) {
    bool duplicate = false;
    for (std::size_t i = 0; i < kept.size() && !duplicate; ++i) {
      duplicate = (o.proximity.point[0] - kept[i]->proximity.point[0]).squaredNorm() +
                      (o.proximity.point[1] - kept[i]->proximity.point[1]).squaredNorm() <
                  near;
    }
    if (!duplicate) kept.push_back(&o);
  }
  return kept;
}

template <class Real>
void ContactPipeline<Real>::contact_sides(const ModelPair& pair, const Output& o, ContactSide<Real>& first, ContactSide<Real>& second) const {
  const auto& m1 = models_[pair.first];
  const auto& m2 = models_[pair.second];
  first.still = m1.points->is_still();
  first.object = first.still ? 0 : m1.points->object();
  second.still = m2.points->is_still();
  second.object = second.still ? 0 : m2.points->object();
  first.position = add_side(m1, o.first, o.proximity.point[0], first.blocks);
  second.position = add_side(m2, o.second, o.proximity.point[1], second.blocks);
}

template <class Real>
int ContactPipeline<Real>::friction_response(std::size_t k, const std::vector<Output>& outputs) {
  const ModelPair& pair = pairs_[k];
  const auto kept = without_duplicates(outputs);
  std::vector<UnilateralContact<Real>> contacts(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Output& o = *kept[i];
    UnilateralContact<Real>& c = contacts[i];
    contact_sides(pair, o, c.first, c.second);
    c.normal = o.proximity.normal;
    c.distance = contact_distance(pair, o);
    record(pair, o);
  }
  responses_.constraints[k]->set_contacts(std::move(contacts));
  return static_cast<int>(kept.size());
}


template <class Real>
int ContactPipeline<Real>::stick_response(std::size_t k, const std::vector<Output>& outputs, std::span<const SimulatedObject<Real>> objects,
                                          std::vector<std::vector<StickSpring<Real>>>& springs) {
  const ModelPair& pair = pairs_[k];
  const auto& m1 = models_[pair.first];
  const auto& m2 = models_[pair.second];
  const auto& a = *m1.points;
  const auto& b = *m2.points;
  auto& alive = stick_springs_[k];
  const auto positions = [&](const CollisionPoints<Real>& side) -> std::span<const Vec3<Real>> {
    return objects[side.object()].system.state.position;
  };
  if (!outputs.empty()) {
    // SOFA's BarycentricStickContact: the springs made again from this step's outputs, each at rest
    // (R = the second point minus the first), ks₁ + ks₂, damping cf₁ + cf₂.
    alive.clear();
    for (const std::size_t i : kept_by_id(outputs)) {
      const auto& p = outputs[i].proximity;
      StickSpring<Real> spring;
      spring.y1 = add_side(m1, outputs[i].first, p.point[0], spring.side1);
      spring.y2 = add_side(m2, outputs[i].second, p.point[1], spring.side2);
      spring.rest = p.point[1] - p.point[0];
      spring.stiffness = m1.contact_stiffness + m2.contact_stiffness;
      spring.damping = m1.contact_friction + m2.contact_friction;
      alive.push_back(std::move(spring));
      record(pair, outputs[i]);
    }
  } else {
    // No output: SOFA keeps the contact alive with its springs, their ends following the bodies.
    for (auto& spring : alive) {
      if (!a.is_still()) spring.y1 = contact_point<Real>(spring.side1, spring.y1, positions(a), last_positions_[a.object()]);
      if (!b.is_still()) spring.y2 = contact_point<Real>(spring.side2, spring.y2, positions(b), last_positions_[b.object()]);
    }
  }
  const auto velocity = [&](const CollisionPoints<Real>& side, const ContactBlocks<Real>& blocks) -> Vec3<Real> {
    if (side.is_still()) return Vec3<Real>::Zero();
    return contact_apply_j<Real>(blocks, std::span<const Vec3<Real>>(objects[side.object()].system.state.velocity));
  };
  for (auto& spring : alive) {
    spring.relative_velocity = velocity(b, spring.side2) - velocity(a, spring.side1);
    if (!responses_.explicit_pairs[k]) {
      springs[a.is_still() ? b.object() : a.object()].push_back(spring);
      continue;
    }
    // Between two bodies' solvers: the force at the step's start positions, a load on both sides.
    const Vec3<Real> force = (spring.y2 - spring.y1 - spring.rest) * spring.stiffness + spring.relative_velocity * spring.damping;
    for (const auto& [block, j] : spring.side1) responses_.explicit_forces[a.object()]->add(block, j.transpose() * force);
    for (const auto& [block, j] : spring.side2) responses_.explicit_forces[b.object()]->add(block, j.transpose() * -force);
  }
  return static_cast<int>(alive.size());
}


template <class Real>
int ContactPipeline<Real>::stick_constraint_response(std::size_t k, const std::vector<Output>& outputs,
                                                     std::span<const SimulatedObject<Real>> objects) {
  const ModelPair& pair = pairs_[k];
  auto& alive = stick_contacts_[k];
  if (!outputs.empty()) {
    // SOFA's StickContactConstraint: the bilateral pairs made again from this step's outputs, each at
    // rest as found.
    alive.clear();
    for (const Output* o : without_duplicates(outputs)) {
      StickContact<Real> c;
      contact_sides(pair, *o, c.first, c.second);
      c.rest = o->proximity.point[1] - o->proximity.point[0];
      alive.push_back(std::move(c));
      record(pair, *o);
    }
  } else {
    // No output: SOFA keeps the constraint alive, its points following the bodies.
    for (auto& c : alive) {
      for (ContactSide<Real>* side : {&c.first, &c.second}) {
        if (side->still) continue;
        side->position = contact_point<Real>(side->blocks, side->position, objects[side->object].system.state.position,
                                             last_positions_[side->object]);
      }
    }
  }
  responses_.stick_constraints[k]->set_contacts(alive);
  return static_cast<int>(alive.size());
}

template PenaltyContact<double> ContactPipeline<double>::contact(const ModelPair&, const Output&) const;
template double ContactPipeline<double>::contact_distance(const ModelPair&, const Output&) const;
template std::vector<std::size_t> ContactPipeline<double>::kept_by_id(const std::vector<Output>&);
template int ContactPipeline<double>::penalty_response(std::size_t, const std::vector<Output>&, std::vector<std::vector<PenaltyContact<double>>>&);
template std::vector<const ContactPipeline<double>::Output*> ContactPipeline<double>::without_duplicates(const std::vector<Output>&);
template void ContactPipeline<double>::contact_sides(const ModelPair&, const Output&, ContactSide<double>&, ContactSide<double>&) const;
template int ContactPipeline<double>::friction_response(std::size_t, const std::vector<Output>&);
template int ContactPipeline<double>::stick_response(std::size_t, const std::vector<Output>&, std::span<const SimulatedObject<double>>,
                                                     std::vector<std::vector<StickSpring<double>>>&);
template int ContactPipeline<double>::stick_constraint_response(std::size_t, const std::vector<Output>&, std::span<const SimulatedObject<double>>);

}  // namespace fastcorot
