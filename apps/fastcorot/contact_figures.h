// What the command line says about the collision stage (SOFA's collision pipeline): the contacts of
// a step as the dump writes them, and the figures over a run (contacts per step, model and element
// pairs, detection time) as `run` and `bench` print them, in text and in JSON. Design:
// docs/collision.md ("Seeing it"); formats: docs/cli.md.
#pragma once

#include <string>

#include "json_io.h"

#include "fastcorot/sim/simulation.h"

#include <iosfwd>

namespace fastcorot::cli {

// The last step's contacts as one dumped step holds them: {"count": n, "points": n × [[x, y, z]
// on the first element, [x, y, z] on the second], "normals": n × [nx, ny, nz]} (unit, from the
// first element to the second), in solve order (CollisionStage::contacts()).
json contacts_to_json(const CollisionStage<double>& stage);

// The collision stage's figures over a run: contacts per step and at the last step, the model
// and element pairs tested, degenerate elements skipped, the time in detection.
struct ContactTally {
  long steps = 0, contacts = 0, last = 0, max_contacts = 0, model_pairs = 0, element_pairs = 0, degenerate = 0;
  double seconds = 0;
  // Contacts that ended a step crossed (CollisionReport::crossed): how many over the run, the
  // deepest, and where it was first seen.
  long crossed = 0;
  double deepest_crossing = 0;
  long first_crossing_step = 0;
  std::string first_crossing_models;

  // Adds one step's report; returns the warning to print when this step is the first with a
  // contact that crossed (empty otherwise).
  std::string add(const CollisionReport& r);
  // One line: "contacts: M per step (at most X, last step L), E element pairs tested per step,
  // detection S s[; D degenerate element(s) skipped]".
  void summarise(std::ostream& out) const;
  // {"last_step", "max_per_step", "mean_per_step", "model_pairs_per_step",
  // "element_pairs_per_step", "degenerate_elements", "detection_seconds", "detection_share"};
  // the share is of `run_seconds`, the run's whole time (0 when it is not positive).
  json to_json(double run_seconds) const;
};

}  // namespace fastcorot::cli
