#include "json_io.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/atomic_file.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace fastcorot::cli {

json read_json_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error(path.string(), ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_json(buffer.str(), path.string());
}

json parse_json(std::string_view text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::exception& error) {
    // Not only parse_error: a number too large for a double is an out_of_range (found by fuzzing).
    throw make_error(source, ": malformed JSON (", error.what(), ")");
  }
}

double read_number(const json& value, const std::string& where) {
  if (!value.is_number()) throw make_error(where, ": expected a number, got ", value.dump());
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw make_error(where, ": expected a finite number, got ", value.dump());
  return number;
}

namespace {

const json& require_array(const json& value, const std::string& where) {
  if (!value.is_array()) throw make_error(where, ": expected a list, got ", value.dump());
  return value;
}

template <std::size_t N>
std::array<Index, N> read_index_tuple(const json& value, const std::string& where) {
  if (!value.is_array() || value.size() != N) {
    throw make_error(where, ": expected a list of ", N, " point indices, got ", value.dump());
  }
  std::array<Index, N> indices{};
  for (std::size_t i = 0; i < N; ++i) {
    const json& entry = value[i];
    if (!entry.is_number_integer() || entry.get<std::int64_t>() < 0 ||
        entry.get<std::int64_t>() > std::numeric_limits<Index>::max()) {
      throw make_error(where, ": expected non-negative integer indices, got ", value.dump());
    }
    indices[i] = static_cast<Index>(entry.get<std::int64_t>());
  }
  return indices;
}

}  // namespace

std::vector<Vec3<double>> read_points(const json& value, const std::string& where) {
  std::vector<Vec3<double>> points;
  for (std::size_t i = 0; i < require_array(value, where).size(); ++i) {
    const json& entry = value[i];
    const std::string here = where + "[" + std::to_string(i) + "]";
    if (!entry.is_array() || entry.size() != 3) {
      throw make_error(here, ": expected [x, y, z], got ", entry.dump());
    }
    points.emplace_back(read_number(entry[0], here), read_number(entry[1], here),
                        read_number(entry[2], here));
  }
  return points;
}

std::vector<Tetrahedron> read_tetrahedra(const json& value, const std::string& where) {
  std::vector<Tetrahedron> tetrahedra;
  for (std::size_t i = 0; i < require_array(value, where).size(); ++i) {
    tetrahedra.push_back(read_index_tuple<4>(value[i], where + "[" + std::to_string(i) + "]"));
  }
  return tetrahedra;
}

std::vector<Edge> read_edges(const json& value, const std::string& where) {
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < require_array(value, where).size(); ++i) {
    edges.push_back(read_index_tuple<2>(value[i], where + "[" + std::to_string(i) + "]"));
  }
  return edges;
}

std::vector<double> read_number_or_list(const json& value, const std::string& where) {
  if (value.is_number()) return {read_number(value, where)};
  if (!value.is_array() || value.empty()) {
    throw make_error(where, ": expected a number or a non-empty list of numbers, got ", value.dump());
  }
  std::vector<double> numbers;
  for (std::size_t i = 0; i < value.size(); ++i) {
    numbers.push_back(read_number(value[i], where + "[" + std::to_string(i) + "]"));
  }
  return numbers;
}

json points_to_json(std::span<const Vec3<double>> points, int coordinates) {
  json out = json::array();
  for (const auto& p : points) {
    json row = json::array();
    for (int c = 0; c < coordinates; ++c) row.push_back(p[c]);
    out.push_back(std::move(row));
  }
  return out;
}

json rows_to_json(std::span<const double> values, std::size_t width) {
  json out = json::array();
  for (std::size_t i = 0; i + width <= values.size(); i += width) out.push_back(std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(i), values.begin() + static_cast<std::ptrdiff_t>(i + width)));
  return out;
}

void write_text(const std::string& text, const std::string& path) {
  if (path.empty() || path == "-") {
    std::cout << text << '\n' << std::flush;
    if (!std::cout) throw make_error("cannot write to standard output");
    return;
  }
  write_stream_atomically(path, [&](std::ostream& out) { out << text << '\n'; });
}

}  // namespace fastcorot::cli
