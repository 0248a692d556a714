#include "fastcorot/state/rigid_mass.h"

#include "fastcorot/core/error.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace fastcorot {

template <class Real>
RigidMassBlocks<Real> mass_blocks(const RigidMass<Real>& m) {
  return {Mat3<Real>::Identity() * m.mass, m.inertia_mass()};
}

template <class Real>
void add_m_dx(const RigidMass<Real>& m, std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor) {
  if (dx.size() != out.size() || dx.size() % 2 != 0) {
    throw make_error("UniformMass<Rigid3>: add_m_dx needs two Vec3 blocks per rigid in dx and out, got ",
                     dx.size(), " and ", out.size());
  }
  // SOFA scales the mass (mass and inertiaMassMatrix) by the factor before multiplying.
  const Real mass = m.mass * factor;
  const Mat3<Real> inertia_mass = m.inertia_mass() * factor;
  for (std::size_t i = 0; i < dx.size(); i += 2) {
    out[i] += dx[i] * mass;
    out[i + 1] += inertia_mass * dx[i + 1];
  }
}

template <class Real>
RigidMass<Real> parse_rigid_mass(std::span<const double> values, const std::string& where) {
  if (values.size() != 1 && values.size() != 2 && values.size() != 11) {
    throw make_error(where, ": vertexMass of a Rigid3 mass is 'mass volume' and 9 inertia numbers "
                     "(or the mass alone), got ", values.size(), " numbers");
  }
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) throw make_error(where, ": vertexMass has a non-finite value (number ", k + 1, ")");
  }
  if (values[0] < 0) throw make_error(where, ": vertexMass has a negative mass ", values[0]);
  RigidMass<Real> m;
  m.mass = Real(values[0]);
  if (values.size() >= 2) m.volume = Real(values[1]);
  if (values.size() == 11) {
    for (int k = 0; k < 9; ++k) m.inertia(k / 3, k % 3) = Real(values[2 + k]);
  }
  return m;
}

namespace {

struct Token {
  std::string text;
  int line;
};

// The whitespace-separated words of a file after its first line, with their line numbers (SOFA
// reads with fscanf("%s"), so line ends, tabs and carriage returns all separate words).
std::vector<Token> words_after_first_line(std::istream& in) {
  std::vector<Token> tokens;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1) continue;
    std::istringstream words(line);
    std::string word;
    while (words >> word) tokens.push_back({word, number});
  }
  return tokens;
}

class RigidFileReader {
 public:
  RigidFileReader(std::string path, std::vector<Token> tokens) : path_(std::move(path)), tokens_(std::move(tokens)) {}

  RigidFile read() {
    RigidFile file;
    while (next_ < tokens_.size()) {
      const Token& key = tokens_[next_++];
      const std::string& k = key.text;
      if (k == "inrt") {
        Mat3<double> inertia;
        for (int i = 0; i < 9; ++i) inertia(i / 3, i % 3) = number(key, 9);
        file.inertia = inertia;
      } else if (k == "cntr" || k == "center") {
        Vec3<double> center;
        for (int i = 0; i < 3; ++i) center[i] = number(key, 3);
        file.center = center;
      } else if (k == "vertexMass") {
        file.vertex_mass = number(key, 1);
        if (*file.vertex_mass < 0) {
          throw make_error(path_, ":", key.line, ": negative vertexMass ", *file.vertex_mass);
        }
      } else if (k == "volm") {
        file.volume = number(key, 1);
      } else if (k == "frme") {
        for (int i = 0; i < 4; ++i) number(key, 4);
      } else if (k == "grav") {
        for (int i = 0; i < 3; ++i) number(key, 3);
      } else if (k == "visc" || k == "stck" || k == "step" || k == "prec") {
        number(key, 1);
      } else if (k[0] == '#') {
        while (next_ < tokens_.size() && tokens_[next_].line == key.line) ++next_;
      } else {
        throw make_error(path_, ":", key.line, ": unknown keyword '", k, "' (SOFA's .rigid keywords: vertexMass, "
                         "volm, inrt, cntr/center, frme, grav, visc, stck, step, prec, # comments)");
      }
    }
    return file;
  }

 private:
  // The next word as a finite number, for keyword `key` which takes `count` of them.
  double number(const Token& key, int count) {
    if (next_ >= tokens_.size()) {
      throw make_error(path_, ":", key.line, ": '", key.text, "' needs ", count, " number", count > 1 ? "s" : "",
                       ", the file ends before");
    }
    const Token& word = tokens_[next_++];
    const char* begin = word.text.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || *end != '\0' || !std::isfinite(value)) {
      throw make_error(path_, ":", word.line, ": '", key.text, "' needs ", count, " finite number",
                       count > 1 ? "s" : "", ", got '", word.text, "'");
    }
    return value;
  }

  std::string path_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

}  // namespace

RigidFile read_rigid_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw make_error(path, ": cannot open the rigid file");
  return RigidFileReader(path, words_after_first_line(in)).read();
}

template <class Real>
RigidMass<Real> uniform_rigid_mass(const UniformRigidMassInput<Real>& input, Index rigid_count,
                                   const std::string& where) {
  RigidMass<Real> m = input.vertex_mass.value_or(RigidMass<Real>{});
  if (!(m.mass >= 0)) throw make_error(where, ": vertexMass must be a finite mass >= 0, got ", m.mass);
  bool vertex_mass_set = input.vertex_mass.has_value();
  bool total_mass_set = input.total_mass.has_value();
  if (input.file) {
    const RigidFile& file = *input.file;
    if (file.inertia) m.inertia = file.inertia->template cast<Real>();
    if (file.volume) m.volume = Real(*file.volume);
    if (file.vertex_mass) {
      m.mass = Real(*file.vertex_mass);
      // A file's vertexMass stands for the attribute when the scene gave none, and then SOFA
      // drops totalMass.
      if (!vertex_mass_set) {
        vertex_mass_set = true;
        total_mass_set = false;
      }
    }
  }
  if (!vertex_mass_set && !total_mass_set && !input.file) {
    throw make_error(where, ": no mass given: set vertexMass, totalMass or filename (SOFA's UniformMass has "
                     "no default since its PR #3927)");
  }
  if (total_mass_set) {
    const double total = *input.total_mass;
    if (!(total >= 0) || !std::isfinite(total)) {
      throw make_error(where, ": totalMass must be a finite mass >= 0, got ", total);
    }
    // SOFA divides when it has rigids (else it warns and keeps the mass).
    if (rigid_count > 0) m.mass = Real(total / Real(rigid_count));
  }
  return m;
}

#define FASTCOROT_INSTANTIATE(Real)                                                                            \
  template struct RigidMass<Real>;                                                                             \
  template RigidMassBlocks<Real> mass_blocks(const RigidMass<Real>&);                                          \
  template void add_m_dx(const RigidMass<Real>&, std::span<const Vec3<Real>>, std::span<Vec3<Real>>, Real);    \
  template RigidMass<Real> parse_rigid_mass(std::span<const double>, const std::string&);                      \
  template RigidMass<Real> uniform_rigid_mass(const UniformRigidMassInput<Real>&, Index, const std::string&);
FASTCOROT_INSTANTIATE(float)
FASTCOROT_INSTANTIATE(double)
#undef FASTCOROT_INSTANTIATE

}  // namespace fastcorot
