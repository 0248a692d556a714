// SOFA's sphere files (.sph, read by its SphereLoader): collision spheres as centres and radii.
#pragma once

#include "fastcorot/core/types.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

struct SphereData {
  std::vector<Vec3<double>> centers;
  std::vector<double> radii;
  std::vector<std::string> warnings;  // "file:line: ..." for each keyword skipped (SOFA warns too)
};

// The first line (the "sph 1.0" header) is skipped unread, as SOFA's loader skips it; then words:
// `sphe index x y z r` (a sphere; the index is not used), `nums N` (a count, not checked), a word
// starting with `#` (a comment to the end of the line); any other word is skipped with the rest of
// its line and a warning. Throws fastcorot::Error "file:line: ..." for a sphere or count that does
// not read as numbers, a non-finite value, or a negative radius.
SphereData read_sphere_text(std::string_view text, const std::string& name);
SphereData read_sphere_file(const std::filesystem::path& path);

}  // namespace fastcorot
