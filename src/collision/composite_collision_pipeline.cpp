#include "fastcorot/collision/composite_collision_pipeline.h"

#include "fastcorot/core/error.h"

#include <utility>

namespace fastcorot {

template <class Real>
CompositeCollisionPipeline<Real>::CompositeCollisionPipeline(std::vector<std::shared_ptr<CollisionStage<Real>>> stages)
    : stages_(std::move(stages)), reports_(stages_.size()) {
  for (const auto& stage : stages_) {
    if (!stage) throw make_error("CompositeCollisionPipeline: a sub-pipeline is missing");
  }
}

template <class Real>
CollisionReport CompositeCollisionPipeline<Real>::begin_step(std::span<SimulatedObject<Real>> objects, Real dt, double time) {
  CollisionReport total;
  contacts_.clear();
  for (std::size_t s = 0; s < stages_.size(); ++s) {
    reports_[s] = stages_[s]->begin_step(objects, dt, time);
    const CollisionReport& r = reports_[s];
    total.contacts += r.contacts;
    total.model_pairs += r.model_pairs;
    total.element_pairs += r.element_pairs;
    total.degenerate_elements += r.degenerate_elements;
    total.detection_seconds += r.detection_seconds;
    const auto found = stages_[s]->contacts();
    contacts_.insert(contacts_.end(), found.begin(), found.end());
  }
  return total;
}

template <class Real>
void CompositeCollisionPipeline<Real>::end_step(std::span<SimulatedObject<Real>> objects, CollisionReport& report) {
  for (std::size_t s = 0; s < stages_.size(); ++s) {
    CollisionReport& r = reports_[s];
    stages_[s]->end_step(objects, r);
    report.crossed += r.crossed;
    if (r.crossed > 0 && r.deepest_crossing > report.deepest_crossing) {
      report.deepest_crossing = r.deepest_crossing;
      report.crossed_models = r.crossed_models;
    }
  }
}

template <class Real>
void CompositeCollisionPipeline<Real>::set_threads(int threads) {
  for (const auto& stage : stages_) stage->set_threads(threads);
}

template class CompositeCollisionPipeline<double>;

}  // namespace fastcorot
