#include "fastcorot/fem/rotation_method.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

RotationMethod parse_rotation_method(std::string_view name) {
  if (name == "qr" || name == "large") return RotationMethod::qr;
  if (name == "polar") return RotationMethod::polar;
  if (name == "polar2") return RotationMethod::polar2;
  if (name == "none" || name == "linear" || name == "small") return RotationMethod::none;
  throw make_error("method = \"", name,
                   "\": unknown rotation method; expected qr (alias large), polar, polar2 or none "
                   "(aliases linear, small)");
}

std::string to_string(RotationMethod method) {
  switch (method) {
    case RotationMethod::qr: return "qr";
    case RotationMethod::polar: return "polar";
    case RotationMethod::polar2: return "polar2";
    case RotationMethod::none: return "none";
  }
  return "unknown";
}

}  // namespace fastcorot
