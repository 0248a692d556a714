// NewProximity's helpers and ownership flags bit for bit against SOFA's own:
// tests/data/sofa_reference/new_proximity_helpers.txt was written by SOFA master 2a278d891f (-O3,
// double) running MeshNewProximityIntersection's doIntersectionTrianglePoint / LinePoint / LineLine,
// NewProximityIntersection::doIntersectionPointPoint, and TriangleCollisionModel's flag steps on
// MeshTopology and TriangleSetTopologyContainer (new_proximity_helpers_harness.cpp beside it);
// new_proximity_pairs.txt by its computeIntersection on element pairs of two small surfaces.
// Lines: `tp flags swap A a b c q | n [p0 p1 normal value]…`, `lp swap A a b q | …`,
// `ll A a b c e | …`, `pp A p q | …`, `flags container #T #P #E triangles edges | flags…`; hex floats.
// SOFA's helpers leave C to their callers: C = 0 here.
#include "fastcorot/collision/new_proximity.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

namespace fastcorot {
namespace {

using V = Vec3<double>;

double read_double(std::istream& in) {
  std::string word;
  in >> word;
  return std::strtod(word.c_str(), nullptr);
}
V read_point(std::istream& in) {
  const double x = read_double(in), y = read_double(in);
  return V(x, y, read_double(in));
}

void expect_same(const std::optional<ProximityOutput<double>>& out, std::istream& in, const std::string& line) {
  std::string bar;
  int count = 0;
  in >> bar >> count;
  ASSERT_EQ(bar, "|");
  ASSERT_EQ(out.has_value(), count == 1) << line;
  if (!out) return;
  const V p0 = read_point(in), p1 = read_point(in), normal = read_point(in);
  EXPECT_EQ(out->point[0], p0) << line;
  EXPECT_EQ(out->point[1], p1) << line;
  EXPECT_EQ(out->normal, normal) << line;
  EXPECT_EQ(out->value, read_double(in)) << line;
}

TEST(NewProximitySofa, HelpersAndFlagsMatchSofaBitForBit) {
  std::ifstream file(testing::sofa_reference_path("new_proximity_helpers.txt"));
  ASSERT_TRUE(file) << "missing new_proximity_helpers.txt";
  std::map<std::string, int> cases;
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string kind;
    in >> kind;
    ++cases[kind];
    if (kind == "tp") {
      int flags = 0, swap = 0;
      in >> flags >> swap;
      const double alarm = read_double(in);
      const V a = read_point(in), b = read_point(in), c = read_point(in), q = read_point(in);
      expect_same(new_proximity_triangle_point(a, b, c, q, flags, {alarm, 0.0}, swap != 0), in, line);
    } else if (kind == "lp") {
      int swap = 0;
      in >> swap;
      const double alarm = read_double(in);
      const V a = read_point(in), b = read_point(in), q = read_point(in);
      expect_same(new_proximity_line_point(a, b, q, {alarm, 0.0}, swap != 0), in, line);
    } else if (kind == "ll") {
      const double alarm = read_double(in);
      const V a = read_point(in), b = read_point(in), c = read_point(in), e = read_point(in);
      expect_same(new_proximity_line_line(a, b, c, e, {alarm, 0.0}), in, line);
    } else if (kind == "pp") {
      const double alarm = read_double(in);
      const V p = read_point(in), q = read_point(in);
      expect_same(new_proximity_point_point(p, q, {alarm, 0.0}), in, line);
    } else if (kind == "flags") {
      std::string container, bar;
      std::size_t triangle_count = 0, point_count = 0, edge_count = 0;
      in >> container >> triangle_count >> point_count >> edge_count;
      std::vector<Triangle> triangles(triangle_count);
      std::vector<Edge> edges(edge_count);
      for (auto& t : triangles) in >> t[0] >> t[1] >> t[2];
      for (auto& e : edges) in >> e[0] >> e[1];
      in >> bar;
      ASSERT_EQ(bar, "|");
      std::vector<int> expected(triangle_count);
      for (int& f : expected) in >> f;
      EXPECT_EQ(triangle_flags(triangles, point_count, edges), expected) << line;
    } else {
      FAIL() << "unknown line " << line;
    }
  }
  EXPECT_EQ(cases["tp"], 150);
  EXPECT_EQ(cases["lp"], 80);
  EXPECT_EQ(cases["ll"], 80);
  EXPECT_EQ(cases["pp"], 20);
  EXPECT_EQ(cases["flags"], 10);
}

// A surface of new_proximity_pairs.txt: `surface #P #T points triangles #E edges` (the edges are SOFA's
// LineCollisionModel elements over the same MeshTopology).
struct Surface {
  std::vector<V> x;
  std::vector<Triangle> triangles;
  std::vector<Edge> edges;
  std::vector<int> flags;
  TriangleElement<double> triangle(std::size_t i) const {
    const Triangle& t = triangles[i];
    return {x[t[0]], x[t[1]], x[t[2]], t, flags[i], Index(i)};
  }
};

TEST(NewProximitySofa, ElementPairsListSofasOutputsInSofasOrder) {
  // SOFA's MeshNewProximityIntersection::computeIntersection (Triangle–Triangle across two surfaces
  // and within the first, Triangle–Line), NewProximityIntersection alarm 0.2, contact 0.03, useLineLine
  // off then on (Triangle–Line only on), every pair with an output listed
  // (new_proximity_pairs_harness.cpp): each listed pair here gives the same list bit for bit, every
  // other pair nothing.
  std::ifstream file(testing::sofa_reference_path("new_proximity_pairs.txt"));
  ASSERT_TRUE(file) << "missing new_proximity_pairs.txt";
  std::vector<Surface> surfaces;
  std::map<std::tuple<std::string, bool, int, int>, std::string> listed;  // the rest of each line
  bool line_line = false;
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string kind;
    in >> kind;
    if (kind == "surface") {
      Surface s;
      std::size_t points = 0, triangles = 0, edges = 0;
      in >> points >> triangles;
      for (std::size_t i = 0; i < points; ++i) s.x.push_back(read_point(in));
      s.triangles.resize(triangles);
      for (auto& t : s.triangles) in >> t[0] >> t[1] >> t[2];
      in >> edges;
      s.edges.resize(edges);
      for (auto& e : s.edges) in >> e[0] >> e[1];
      s.flags = triangle_flags(s.triangles, points);
      surfaces.push_back(std::move(s));
    } else if (kind == "use_line_line") {
      in >> line_line;
    } else {
      int i = 0, j = 0;
      in >> i >> j;
      std::string rest;
      std::getline(in, rest);
      listed[{kind, line_line, i, j}] = rest;
    }
  }
  ASSERT_EQ(surfaces.size(), 2u);
  const Surface &one = surfaces[0], &two = surfaces[1];
  // Compares the outputs of one pair with SOFA's line (empty: none).
  const auto compare = [&](const std::string& kind, bool use, int i, int j, const std::vector<DetectionOutput<double>>& outputs) {
    const auto found = listed.find({kind, use, i, j});
    const std::string where = kind + " " + std::to_string(use) + " " + std::to_string(i) + " " + std::to_string(j);
    if (found == listed.end()) {
      EXPECT_TRUE(outputs.empty()) << where;
      return 0;
    }
    std::istringstream in(found->second);
    std::size_t count = 0;
    in >> count;
    EXPECT_EQ(outputs.size(), count) << where;
    for (std::size_t k = 0; k < std::min(count, outputs.size()); ++k) {
      std::int64_t id = 0;
      in >> id;
      EXPECT_EQ(outputs[k].id, id) << where << " #" << k;
      EXPECT_EQ(outputs[k].point[0], read_point(in)) << where << " #" << k;
      EXPECT_EQ(outputs[k].point[1], read_point(in)) << where << " #" << k;
      EXPECT_EQ(outputs[k].normal, read_point(in)) << where << " #" << k;
      EXPECT_EQ(outputs[k].value, read_double(in)) << where << " #" << k;
    }
    return 1;
  };
  int compared = 0;
  for (const bool use : {false, true}) {
    const ProximityDistances<double> d{0.2, 0.03};
    NewProximityPair<double> across{d, one.triangles.size(), two.triangles.size(), false, use};
    NewProximityPair<double> self{d, one.triangles.size(), one.triangles.size(), true, use};
    std::vector<DetectionOutput<double>> outputs;
    for (std::size_t i = 0; i < one.triangles.size(); ++i) {
      for (std::size_t j = 0; j < two.triangles.size(); ++j) {
        outputs.clear();
        new_proximity_intersection(one.triangle(i), two.triangle(j), across, outputs);
        compared += compare("tt", use, int(i), int(j), outputs);
      }
      for (std::size_t j = i + 1; j < one.triangles.size(); ++j) {
        outputs.clear();
        new_proximity_intersection(one.triangle(i), one.triangle(j), self, outputs);
        compared += compare("self", use, int(i), int(j), outputs);
      }
      if (!use) continue;
      for (std::size_t j = 0; j < two.edges.size(); ++j) {
        outputs.clear();
        const LineElement<double> segment{two.x[two.edges[j][0]], two.x[two.edges[j][1]], Index(j)};
        new_proximity_intersection(one.triangle(i), segment, across, outputs);
        compared += compare("tl", use, int(i), int(j), outputs);
      }
    }
  }
  EXPECT_EQ(compared, int(listed.size()));
}

}  // namespace
}  // namespace fastcorot
