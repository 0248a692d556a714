// `fastcorot probe CASE.json [-o OUT.json]`: evaluates the corotational force field of SPEC.md on
// one mesh and configuration in double precision, so that its numbers can be compared with any
// other code. Input keys: points, tetrahedra (required); youngModulus, poissonRatio (number or one
// per tetrahedron; SOFA's defaults 5000 and 0.45), method ("qr"), x (current positions, default
// points), dx (optional), kFactor (1), edges (optional explicit edge list, any order/orientation).
// Output keys: force, dforce (when dx is given), energy, stiffness {size, triplets [row, col, value]},
// rotations, edges, restVolume. See docs/cli.md.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace fastcorot::cli {

// Throws fastcorot::Error naming `source` and the key at fault.
nlohmann::json probe(const nlohmann::json& input, const std::string& source);

// Reads the case file, writes the result to `output_path` (standard output when empty).
void probe_file(const std::string& case_path, const std::string& output_path);

}  // namespace fastcorot::cli
