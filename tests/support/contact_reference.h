// A contact scene of tests/data/sofa_reference run against SOFA's own trajectory: at each step SOFA
// dumped, the positions within `relative` of the largest displacement, and (with
// `contacts`/`rows`) the contacts and constraint rows SOFA counted.
#pragma once

#include "fastcorot/scene/scene_builder.h"

#include "support/sofa_reference.h"

#include <gtest/gtest.h>

namespace fastcorot::testing {

struct ContactCounts {
  bool contacts = true;  // the collision report's contacts equal SOFA's detection outputs
  bool rows = true;      // the constraint rows equal SOFA's
};

inline void expect_contact_trajectory(const std::string& scene_file, const std::string& trajectory_file, double relative,
                                      ContactCounts counts = {}) {
  LoadedScene scene = load_scene_file(sofa_reference_path(scene_file));
  const auto reference = load_sofa_trajectory(trajectory_file);
  auto& simulation = scene.simulation;
  ASSERT_TRUE(simulation.collisions) << scene_file;
  const auto& x = simulation.objects[0].system.state.position;
  const auto rest = json_points(reference["steps"]["0"]["points"]);
  for (const long step : dumped_steps(reference)) {
    while (simulation.steps_done() < step) simulation.step();
    const auto& frame = reference["steps"][std::to_string(step)];
    const auto d = compare_points(x, json_points(frame["points"]), rest);
    EXPECT_LE(d.difference, relative * d.displacement + 1e-15) << scene_file << " step " << step;
    if (step == 0) continue;
    if (counts.contacts) {
      EXPECT_EQ(simulation.collision_report().contacts, frame["contacts"].get<int>()) << scene_file << " step " << step;
    }
    if (counts.rows) {
      EXPECT_EQ(simulation.constraint_report().rows, frame["constraints"].get<int>()) << scene_file << " step " << step;
    }
  }
}

}  // namespace fastcorot::testing
