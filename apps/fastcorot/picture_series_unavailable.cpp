// PictureSeries in a build without pictures (FASTCOROT_BUILD_RENDER=OFF): `--png` is an error.
#include "picture_series.h"

#include "fastcorot/core/error.h"

namespace fastcorot::cli {

struct PictureSeries::Impl {};

PictureSeries::PictureSeries(const std::string&, const PictureOptions&, const Simulation<double>&,
                             long) {
  throw make_error(
      "--png: this fastcorot was built without pictures (configured with "
      "FASTCOROT_BUILD_RENDER=OFF)");
}

PictureSeries::~PictureSeries() = default;

void PictureSeries::write(const Simulation<double>&) {}

}  // namespace fastcorot::cli
