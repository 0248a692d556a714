// Throwaway harness (not part of fastcorot): runs SOFA's own NewProximity helpers and topology
// containers on generated inputs and prints inputs and outputs as hex floats.
#include <sofa/component/collision/detection/intersection/MeshNewProximityIntersection.inl>
#include <sofa/component/topology/container/constant/MeshTopology.h>
#include <sofa/component/topology/container/dynamic/TriangleSetTopologyContainer.h>
#include <sofa/core/objectmodel/BaseObject.h>
#include <cstdio>
#include <random>
using namespace sofa;
using sofa::type::Vec3;
using MNP = sofa::component::collision::detection::intersection::MeshNewProximityIntersection;
using NP = sofa::component::collision::detection::intersection::NewProximityIntersection;
using Out = sofa::type::vector<sofa::core::collision::DetectionOutput>;
std::mt19937 rng(2024);
double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
Vec3 R(double s = 1) { return Vec3(U(-s, s), U(-s, s), U(-s, s)); }
void pv(const Vec3& v) { std::printf(" %a %a %a", v[0], v[1], v[2]); }
void po(const Out& o) {
  std::printf(" | %d", int(o.size()));
  for (auto& d : o) { pv(d.point[0]); pv(d.point[1]); pv(d.normal); std::printf(" %a", d.value); }
  std::printf("\n");
}
Vec3 nearTri(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v[3] = {a, b, c};
  switch (rng() % 4) {
    case 0: return R(1.5);
    case 1: return v[rng() % 3] + R(0.1);
    case 2: { int k = rng() % 3; return v[k] + (v[(k + 1) % 3] - v[k]) * U(0, 1) + R(0.1); }
    default: { double s = U(0, 1), t = U(0, 1) * (1 - s); Vec3 n = cross(b - a, c - a); n.normalize();
               return a + (b - a) * s + (c - a) * t + n * U(-0.5, 0.5); }
  }
}
template <class Topo>
void flags(const char* name, const std::vector<std::array<int,3>>& tris, int np, const std::vector<std::array<int,2>>& edges) {
  auto t = sofa::core::objectmodel::New<Topo>();
  if constexpr (std::is_same_v<Topo, sofa::component::topology::container::constant::MeshTopology>) {
    auto& st = *t->d_seqTriangles.beginEdit(); for (auto& x : tris) st.push_back({(unsigned)x[0], (unsigned)x[1], (unsigned)x[2]}); t->d_seqTriangles.endEdit();
    if (!edges.empty()) { auto& se = *t->d_seqEdges.beginEdit(); for (auto& e : edges) se.push_back({(unsigned)e[0], (unsigned)e[1]}); t->d_seqEdges.endEdit(); }
    t->setNbPoints(np);
  } else {
    auto& st = *t->d_triangle.beginEdit(); for (auto& x : tris) st.push_back({(unsigned)x[0], (unsigned)x[1], (unsigned)x[2]}); t->d_triangle.endEdit();
    if (!edges.empty()) { auto& se = *t->d_edge.beginEdit(); for (auto& e : edges) se.push_back({(unsigned)e[0], (unsigned)e[1]}); t->d_edge.endEdit(); }
    t->setNbPoints(np);
  }
  t->init();
  std::printf("flags %s %d %d %d", name, int(tris.size()), np, int(edges.size()));
  for (auto& x : tris) std::printf(" %d %d %d", x[0], x[1], x[2]);
  for (auto& e : edges) std::printf(" %d %d", e[0], e[1]);
  std::printf(" |");
  for (unsigned i = 0; i < tris.size(); ++i) {  // TriangleCollisionModel::getTriangleFlags, same steps
    int f = 0; auto tr = t->getTriangle(i);
    for (unsigned j = 0; j < 3; ++j) if (t->getTrianglesAroundVertex(tr[j])[0] == i) f |= 1 << j;
    const auto& e = t->getEdgesInTriangle(i);
    for (unsigned j = 0; j < 3; ++j) { const auto& tae = t->getTrianglesAroundEdge(e[j]);
      if (tae[0] == i) f |= (1 << 3) << j; if (tae.size() == 1) f |= (1 << 6) << j; }
    std::printf(" %d", f);
  }
  std::printf("\n");
}
int main() {
  for (int k = 0; k < 150; ++k) {
    Vec3 a = R(), b = R(), c = R();
    Vec3 q = nearTri(a, b, c); int fl = rng() % 64; bool sw = rng() % 2; double alarm = 0.8;
    Out o; Vec3 n; MNP::doIntersectionTrianglePoint(alarm * alarm, fl, a, b, c, n, q, &o, 0, sw);
    std::printf("tp %d %d %a", fl, int(sw), alarm); pv(a); pv(b); pv(c); pv(q); po(o);
  }
  for (int k = 0; k < 80; ++k) {
    Vec3 a = R(), b = R(); Vec3 q = k % 2 ? R(1.5) : Vec3((k % 4 ? a : b) + R(0.2)); bool sw = rng() % 2; double alarm = 0.9;
    Out o; MNP::doIntersectionLinePoint(alarm * alarm, a, b, q, &o, 0, sw);
    std::printf("lp %d %a", int(sw), alarm); pv(a); pv(b); pv(q); po(o);
  }
  for (int k = 0; k < 80; ++k) {
    Vec3 a = R(), b = R(), c = R(), e = R(); double alarm = 0.7;
    if (k % 20 == 0) { c = a + Vec3(0, 0.3, 0); e = b + Vec3(0, 0.3, 0); }  // parallel
    Out o; MNP::doIntersectionLineLine(alarm * alarm, a, b, c, e, &o, 0);
    std::printf("ll %a", alarm); pv(a); pv(b); pv(c); pv(e); po(o);
  }
  for (int k = 0; k < 20; ++k) {
    Vec3 p = R(), q = R(); double alarm = 1.2; Out o; NP::doIntersectionPointPoint(alarm * alarm, p, q, &o, 0);
    std::printf("pp %a", alarm); pv(p); pv(q); po(o);
  }
  using MT = sofa::component::topology::container::constant::MeshTopology;
  using TS = sofa::component::topology::container::dynamic::TriangleSetTopologyContainer;
  std::vector<std::array<int,3>> tet = {{0,1,2},{0,3,1},{1,3,2},{0,2,3}};
  std::vector<std::array<int,2>> sorted = {{0,1},{0,2},{0,3},{1,2},{1,3},{2,3}};
  flags<MT>("mesh", tet, 4, {}); flags<TS>("set", tet, 4, {});
  flags<MT>("mesh", tet, 4, sorted); flags<TS>("set", tet, 4, sorted);
  // 4×4 grid, random diagonals and random orientation flips; then with edges stored (min, max)
  std::vector<std::array<int,3>> grid; std::vector<std::array<int,2>> ge;
  for (int y = 0; y < 4; ++y) for (int x = 0; x < 4; ++x) {
    int a = 5*y+x, b = a+1, c = a+6, d = a+5; std::array<int,3> t1, t2;
    if (rng() % 2) { t1 = {a,b,c}; t2 = {a,c,d}; } else { t1 = {a,b,d}; t2 = {b,c,d}; }
    if (rng() % 3 == 0) std::swap(t1[1], t1[2]);
    if (rng() % 3 == 0) std::swap(t2[0], t2[2]);
    grid.push_back(t1); grid.push_back(t2);
  }
  for (auto& t : grid) for (int j = 0; j < 3; ++j) { int u = std::min(t[j], t[(j+1)%3]), v = std::max(t[j], t[(j+1)%3]);
    bool have = false; for (auto& e : ge) have |= e[0] == u && e[1] == v; if (!have) ge.push_back({u, v}); }
  flags<MT>("mesh", grid, 25, {}); flags<TS>("set", grid, 25, {});
  flags<MT>("mesh", grid, 25, ge); flags<TS>("set", grid, 25, ge);
  std::vector<std::array<int,3>> fan = {{0,1,2},{1,0,3},{0,1,4},{4,1,5}};
  flags<MT>("mesh", fan, 6, {}); flags<TS>("set", fan, 6, {});
}
