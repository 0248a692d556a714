// CompositeCollisionPipeline: sub-pipelines run in their order, their reports summed, their contacts
// joined, their crossings measured on each one's own report (stand-in stages record the calls).
#include "fastcorot/collision/composite_collision_pipeline.h"
#include "fastcorot/core/error.h"
#include "fastcorot/sim/simulation.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

class RecordingStage final : public CollisionStage<double> {
 public:
  RecordingStage(std::string name, CollisionReport report, std::vector<DetectedContact<double>> contacts, int crossed, double deepest,
                 std::vector<std::string>& calls)
      : name_(std::move(name)), report_(report), contacts_(std::move(contacts)), crossed_(crossed), deepest_(deepest), calls_(calls) {}
  CollisionReport begin_step(std::span<SimulatedObject<double>>, double, double) override {
    calls_.push_back("begin " + name_);
    return report_;
  }
  std::span<const DetectedContact<double>> contacts() const override { return contacts_; }
  void end_step(std::span<SimulatedObject<double>>, CollisionReport& report) override {
    calls_.push_back("end " + name_);
    EXPECT_EQ(report.contacts, report_.contacts) << "its own report, not the sum";
    report.crossed += crossed_;
    report.deepest_crossing = deepest_;
    report.crossed_models = name_;
  }
  void set_threads(int threads) override { calls_.push_back("threads " + name_ + " " + std::to_string(threads)); }

 private:
  std::string name_;
  CollisionReport report_;
  std::vector<DetectedContact<double>> contacts_;
  int crossed_;
  double deepest_;
  std::vector<std::string>& calls_;
};

DetectedContact<double> contact(double x) {
  DetectedContact<double> c;
  c.point[0] = Vec3<double>(x, 0, 0);
  c.point[1] = Vec3<double>(x, 1, 0);
  c.normal = Vec3<double>(0, 1, 0);
  return c;
}

TEST(CompositeCollisionPipeline, RunsItsSubPipelinesInOrderAndSumsTheirReports) {
  std::vector<std::string> calls;
  CollisionReport a{.contacts = 2, .model_pairs = 1, .element_pairs = 10, .degenerate_elements = 1, .detection_seconds = 0.5};
  CollisionReport b{.contacts = 3, .model_pairs = 4, .element_pairs = 7, .degenerate_elements = 0, .detection_seconds = 0.25};
  CompositeCollisionPipeline<double> composite({std::make_shared<RecordingStage>("a", a, std::vector{contact(1), contact(2)}, 1, 0.1, calls),
                                                std::make_shared<RecordingStage>("b", b, std::vector{contact(3)}, 2, 0.3, calls)});
  composite.set_threads(2);
  std::vector<SimulatedObject<double>> objects;
  CollisionReport total = composite.begin_step(objects, 0.01, 0);
  EXPECT_EQ(total.contacts, 5);
  EXPECT_EQ(total.model_pairs, 5);
  EXPECT_EQ(total.element_pairs, 17);
  EXPECT_EQ(total.degenerate_elements, 1);
  EXPECT_EQ(total.detection_seconds, 0.75);
  ASSERT_EQ(composite.contacts().size(), 3u);
  EXPECT_EQ(composite.contacts()[0].point[0].x(), 1);
  EXPECT_EQ(composite.contacts()[2].point[0].x(), 3);
  composite.end_step(objects, total);
  EXPECT_EQ(total.crossed, 3);
  EXPECT_EQ(total.deepest_crossing, 0.3);
  EXPECT_EQ(total.crossed_models, "b");
  EXPECT_EQ(calls, (std::vector<std::string>{"threads a 2", "threads b 2", "begin a", "begin b", "end a", "end b"}));
  // A second step starts from no contacts.
  composite.begin_step(objects, 0.01, 0.01);
  EXPECT_EQ(composite.contacts().size(), 3u);
  EXPECT_THROW(CompositeCollisionPipeline<double>({nullptr}), Error);
}

}  // namespace
}  // namespace fastcorot
