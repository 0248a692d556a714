// `fastcorot run --png DIR`: a picture of every written frame (step 0, every K steps, the last),
// rendered offscreen (OSMesa, no display needed) to DIR/step_NNNNN.png. The camera is framed once
// on the initial state (with room below for sagging) and then held, so the frames make an
// animation. In a build without pictures (FASTCOROT_BUILD_RENDER=OFF) constructing one is an error.
#pragma once

#include "picture_options.h"

#include "fastcorot/sim/simulation.h"

#include <memory>
#include <string>

namespace fastcorot::cli {

class PictureSeries {
 public:
  // Creates `dir`; parses the options; frames the camera on `simulation` as it is now. `last_step`
  // sets the width of the step numbers in file names (at least 5 digits). Throws fastcorot::Error.
  PictureSeries(const std::string& dir, const PictureOptions& options,
                const Simulation<double>& simulation, long last_step);
  ~PictureSeries();

  // Writes DIR/step_NNNNN.png for the simulation's current step.
  void write(const Simulation<double>& simulation);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fastcorot::cli
