#include "fastcorot/topology/point_order.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cstdlib>

namespace fastcorot {

namespace {

// Adjacency lists in compressed form: the neighbours of p are neighbour[first[p], first[p + 1]).
struct Adjacency {
  std::vector<Index> first, neighbour;
  Index degree(Index p) const { return first[static_cast<std::size_t>(p) + 1] - first[static_cast<std::size_t>(p)]; }
};

Adjacency adjacency(Index num_points, std::span<const Edge> edges) {
  Adjacency a;
  a.first.assign(static_cast<std::size_t>(num_points) + 1, 0);
  for (const Edge& e : edges) {
    for (const Index p : e) {
      if (p < 0 || p >= num_points) throw make_error("point order: edge point ", p, " outside [0, ", num_points, ")");
    }
    ++a.first[static_cast<std::size_t>(e[0]) + 1];
    ++a.first[static_cast<std::size_t>(e[1]) + 1];
  }
  for (std::size_t p = 0; p < static_cast<std::size_t>(num_points); ++p) a.first[p + 1] += a.first[p];
  a.neighbour.resize(static_cast<std::size_t>(a.first.back()));
  std::vector<Index> fill(a.first.begin(), a.first.end() - 1);
  for (const Edge& e : edges) {
    a.neighbour[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
    a.neighbour[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
  }
  return a;
}

// Breadth-first order of the part containing `start`, neighbours by increasing (degree, index);
// marks what it visits. Returns the visited points in order.
std::vector<Index> levels_from(const Adjacency& a, Index start, std::vector<char>& visited) {
  std::vector<Index> order{start}, next;
  visited[static_cast<std::size_t>(start)] = 1;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Index p = order[k];
    next.clear();
    for (Index i = a.first[static_cast<std::size_t>(p)]; i < a.first[static_cast<std::size_t>(p) + 1]; ++i) {
      const Index q = a.neighbour[static_cast<std::size_t>(i)];
      if (!visited[static_cast<std::size_t>(q)]) {
        visited[static_cast<std::size_t>(q)] = 1;
        next.push_back(q);
      }
    }
    std::sort(next.begin(), next.end(), [&](Index x, Index y) {
      return a.degree(x) != a.degree(y) ? a.degree(x) < a.degree(y) : x < y;
    });
    order.insert(order.end(), next.begin(), next.end());
  }
  return order;
}

}  // namespace

std::vector<Index> reverse_cuthill_mckee(Index num_points, std::span<const Edge> edges) {
  if (num_points < 0) throw make_error("point order: ", num_points, " points");
  const Adjacency a = adjacency(num_points, edges);
  std::vector<Index> by_degree(static_cast<std::size_t>(num_points));
  for (Index p = 0; p < num_points; ++p) by_degree[static_cast<std::size_t>(p)] = p;
  std::stable_sort(by_degree.begin(), by_degree.end(), [&](Index x, Index y) { return a.degree(x) < a.degree(y); });
  std::vector<char> visited(static_cast<std::size_t>(num_points), 0);
  std::vector<Index> sequence;  // Cuthill–McKee order, reversed at the end
  sequence.reserve(static_cast<std::size_t>(num_points));
  for (const Index candidate : by_degree) {
    if (visited[static_cast<std::size_t>(candidate)] || a.degree(candidate) == 0) continue;
    // One step towards a peripheral point: restart from the last point reached from a point of
    // least degree (the far end of its levels), which narrows the levels.
    const std::vector<Index> probe = levels_from(a, candidate, visited);
    for (const Index p : probe) visited[static_cast<std::size_t>(p)] = 0;
    const Index far = probe.back();
    const std::vector<Index> part = levels_from(a, far, visited);
    sequence.insert(sequence.end(), part.begin(), part.end());
  }
  std::reverse(sequence.begin(), sequence.end());
  for (Index p = 0; p < num_points; ++p) {
    if (a.degree(p) == 0) sequence.push_back(p);
  }
  std::vector<Index> order(static_cast<std::size_t>(num_points));
  for (std::size_t k = 0; k < sequence.size(); ++k) order[static_cast<std::size_t>(sequence[k])] = static_cast<Index>(k);
  return order;
}

double mean_edge_span(std::span<const Edge> edges, std::span<const Index> order) {
  if (edges.empty()) return 0;
  double sum = 0;
  for (const Edge& e : edges) {
    const Index a = order.empty() ? e[0] : order[static_cast<std::size_t>(e[0])];
    const Index b = order.empty() ? e[1] : order[static_cast<std::size_t>(e[1])];
    sum += std::abs(static_cast<double>(a) - static_cast<double>(b));
  }
  return sum / static_cast<double>(edges.size());
}

}  // namespace fastcorot
