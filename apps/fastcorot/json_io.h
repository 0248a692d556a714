// Reading and writing the JSON shapes the command-line tools exchange (lists of points, of
// tetrahedra, of numbers), with errors that name the file, the key and the entry at fault.
#pragma once

#include "fastcorot/core/types.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot::cli {

using nlohmann::json;

// Parses a whole file; throws fastcorot::Error naming the file (and the parser's byte position).
json read_json_file(const std::filesystem::path& path);
// Parses JSON text; throws fastcorot::Error naming `source` (and the parser's byte position).
json parse_json(std::string_view text, const std::string& source);

// Each reader throws fastcorot::Error with `where` (e.g. "case.json: \"x\"") in the message.
std::vector<Vec3<double>> read_points(const json& value, const std::string& where);
std::vector<Tetrahedron> read_tetrahedra(const json& value, const std::string& where);
std::vector<Edge> read_edges(const json& value, const std::string& where);
double read_number(const json& value, const std::string& where);
// A number or a non-empty list of numbers.
std::vector<double> read_number_or_list(const json& value, const std::string& where);

json points_to_json(std::span<const Vec3<double>> points, int coordinates = 3);
// Values in rows of `width` (a Rigid3 state: 7 numbers per position, 6 per velocity).
json rows_to_json(std::span<const double> values, std::size_t width);

// Writes `text` to `path` (replacing it), or to standard output when path is empty or "-".
void write_text(const std::string& text, const std::string& path);

}  // namespace fastcorot::cli
