#include "fastcorot/io/sphere_reader.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace fastcorot {

SphereData read_sphere_text(std::string_view text, const std::string& name) {
  SphereData out;
  std::istringstream in{std::string(text)};
  std::string line;
  std::getline(in, line);  // the header
  for (int number = 2; std::getline(in, line); ++number) {
    std::istringstream words(line);
    auto fail = [&](const char* what) {
      return make_error(name, ":", number, ": ", what, " (the line reads \"", line, "\")");
    };
    // Several statements may share a line, as SOFA reads words, not lines.
    for (std::string word; words >> word;) {
      if (word[0] == '#') break;
      if (word == "nums") {
        long count = 0;
        if (!(words >> count)) throw fail("nums: expected the number of spheres");
      } else if (word == "sphe") {
        long index = 0;
        Vec3<double> c;
        double r = 0;
        if (!(words >> index >> c.x() >> c.y() >> c.z() >> r)) throw fail("sphe: expected index x y z radius");
        if (!c.allFinite() || !std::isfinite(r)) throw fail("sphe: a value is not finite");
        if (r < 0) throw fail("sphe: the radius is negative");
        out.centers.push_back(c);
        out.radii.push_back(r);
      } else {
        out.warnings.push_back(name + ":" + std::to_string(number) + ": unknown keyword '" + word +
                               "' skipped with the rest of its line (as SOFA's SphereLoader does)");
        break;
      }
    }
  }
  return out;
}

SphereData read_sphere_file(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw make_error(path.string(), ": cannot open the sphere file");
  std::ostringstream text;
  text << file.rdbuf();
  if (text.str().empty()) throw make_error(path.string(), ": the sphere file is empty");
  return read_sphere_text(text.str(), path.string());
}

}  // namespace fastcorot
