// How the corotational force field extracts each tetrahedron's rotation (SOFA's `method`
// attribute): `qr` (alias `large`), `polar`, `polar2`, or `none` (aliases `linear`, `small`: plain
// linear elasticity). See SPEC.md, "Forces".
#pragma once

#include <string>
#include <string_view>

namespace fastcorot {

enum class RotationMethod { qr, polar, polar2, none };

// Accepts SOFA's names and aliases (exact, lower case). Throws fastcorot::Error naming the value
// and listing the accepted names.
RotationMethod parse_rotation_method(std::string_view name);

// The canonical name: "qr", "polar", "polar2" or "none".
std::string to_string(RotationMethod method);

}  // namespace fastcorot
