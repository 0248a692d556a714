// What each fuzz target does with one input, shared by the libFuzzer entry points (fuzz_*.cpp) and
// the regression test that replays every input the fuzzers found (tests/apps/fuzz_regression_test.cpp).
// The contract under test: fastcorot refuses bad input with a fastcorot::Error and nothing else.
// Each function swallows that one exception; anything else escapes (libFuzzer reports it as a
// crash, as it reports sanitizer findings, leaks and hangs; the test fails on it).
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/io/surface_readers.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"
#include "json_io.h"
#include "probe_command.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fastcorot::fuzz {

template <class Read>
void value_or_error(Read&& read) {
  try {
    read();
  } catch (const fastcorot::Error&) {
  }
}

inline void gmsh(std::string_view bytes) {
  value_or_error([&] { read_gmsh_bytes(bytes, "fuzz.msh"); });
}

inline void vtk_legacy(std::string_view bytes) {
  value_or_error([&] { read_vtk_legacy_bytes(bytes, "fuzz.vtk"); });
}

inline void vtu(std::string_view bytes) {
  value_or_error([&] { read_vtu_bytes(bytes, "fuzz.vtu"); });
}

// The surface readers (OBJ and STL) on the same bytes.
inline void surface(std::string_view bytes) {
  value_or_error([&] { read_obj_bytes(bytes, "fuzz.obj"); });
  value_or_error([&] { read_stl_bytes(bytes, "fuzz.stl"); });
}

// A grid costs what it asks for: one digit more in a RegularGridTopology's `n` asks for ten times
// the points, and the fuzzer soon asks for billions (legitimate work, or std::bad_alloc, not a
// defect). Scenes whose grids hold more points than this are parsed but not built.
inline constexpr double kMaxGridPoints = 5000;

inline bool grids_are_small(const SceneNode& node) {
  for (const SceneObject& object : node.objects) {
    const auto n = object.attributes.find("n");
    if (object.type != "RegularGridTopology" || n == object.attributes.end()) continue;
    std::istringstream counts(n->second);
    double points = 1, count = 0;
    while (counts >> count) points *= std::abs(count);
    if (points > kMaxGridPoints) return false;
  }
  for (const SceneNode& child : node.children) {
    if (!grids_are_small(child)) return false;
  }
  return true;
}

// The scene text stands for a file in `folder` (examples/ in the fuzzer), so that relative
// includes and mesh file names in the seeds (meshes/cylinder.msh) resolve and reach the loaders.
inline void scene(std::string_view text, const std::filesystem::path& folder) {
  value_or_error([&] {
    const SceneNode root = parse_scene_text(std::string(text), folder / "fuzz_input.scn");
    if (grids_are_small(root)) build_scene(root);
  });
}

namespace detail {

inline double largest_number(const nlohmann::json& value) {
  if (value.is_number()) return std::abs(value.get<double>());
  double largest = 0;
  if (value.is_array() || value.is_object()) {
    for (const auto& item : value) largest = std::max(largest, largest_number(item));
  }
  return largest;
}

inline bool has_nan(const nlohmann::json& value) {
  if (value.is_number_float()) return std::isnan(value.get<double>());
  if (value.is_array() || value.is_object()) {
    for (const auto& item : value) {
      if (has_nan(item)) return true;
    }
  }
  return false;
}

}  // namespace detail

// Besides the error contract: a configuration of moderate size never yields a NaN force, rotation
// or stiffness product, whatever the method and however the current state is inverted or
// collapsed (docs/robustness.md, "Inverted and collapsed elements"). Numbers up to 1e6 cannot overflow the
// computation (E · L² · strain stays far below 1e308), so a NaN there is a defect.
inline void probe_json(std::string_view text) {
  value_or_error([&] {
    const nlohmann::json input = cli::parse_json(text, "fuzz.json");
    const nlohmann::json output = cli::probe(input, "fuzz.json");
    if (detail::largest_number(input) > 1e6) return;
    for (const char* key : {"force", "dforce", "rotations", "stiffness"}) {
      if (output.contains(key) && detail::has_nan(output[key])) {
        throw std::logic_error(std::string("NaN in the probe output \"") + key + "\" for a moderate input");
      }
    }
  });
}

}  // namespace fastcorot::fuzz
