// `fastcorot view` in a build without the viewer (FASTCOROT_BUILD_VIEWER=OFF): an error.
#include "view_command.h"

#include "fastcorot/core/error.h"

namespace fastcorot::cli {

void view(const ViewOptions&, std::ostream&, std::ostream&) {
  throw make_error(
      "view: this fastcorot was built without the viewer (configured with "
      "FASTCOROT_BUILD_VIEWER=OFF)");
}

}  // namespace fastcorot::cli
