// CompositeCollisionPipeline<Real>: SOFA's CompositeCollisionPipeline, several sub-pipelines (each
// a ContactPipeline with its own models, intersection method and contact manager: SOFA's
// SubCollisionPipeline) run one after the other in their listed order. A sub-pipeline's responses
// only make forces or constraints for the step, so running each's detection then responses in turn
// gives what SOFA's reset-all, detect-all, respond-all gives. Design: docs/collision.md.
#pragma once

#include "fastcorot/sim/collision_stage.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class CompositeCollisionPipeline final : public CollisionStage<Real> {
 public:
  explicit CompositeCollisionPipeline(std::vector<std::shared_ptr<CollisionStage<Real>>> stages);

  // The sub-pipelines' reports summed (the contacts, pairs and time), their contacts joined in order.
  CollisionReport begin_step(std::span<SimulatedObject<Real>> objects, Real dt, double time) override;
  std::span<const DetectedContact<Real>> contacts() const override { return contacts_; }
  // Each sub-pipeline's crossings measured on its own report, then summed; the deepest kept.
  void end_step(std::span<SimulatedObject<Real>> objects, CollisionReport& report) override;
  void set_threads(int threads) override;

 private:
  std::vector<std::shared_ptr<CollisionStage<Real>>> stages_;
  std::vector<CollisionReport> reports_;
  std::vector<DetectedContact<Real>> contacts_;
};

}  // namespace fastcorot
