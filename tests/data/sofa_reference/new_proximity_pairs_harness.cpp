// Throwaway harness (not part of fastcorot): SOFA's MeshNewProximityIntersection::computeIntersection
// on element pairs of two triangle surfaces, its outputs (id, points, normal, value) as hex floats.
#include <sofa/component/collision/detection/intersection/MeshNewProximityIntersection.h>
#include <sofa/component/collision/detection/intersection/NewProximityIntersection.h>
#include <sofa/component/collision/geometry/TriangleCollisionModel.h>
#include <sofa/component/collision/geometry/LineCollisionModel.h>
#include <sofa/component/collision/geometry/PointCollisionModel.h>
#include <sofa/component/statecontainer/MechanicalObject.h>
#include <sofa/component/topology/container/constant/MeshTopology.h>
#include <sofa/simulation/Node.h>
#include <sofa/simulation/Simulation.h>
#include <sofa/simulation/graph/init.h>
#include <sofa/simulation/common/init.h>
#include <cstdio>
#include <random>
using namespace sofa;
using namespace sofa::component::collision::geometry;
using sofa::type::Vec3;
using Vec3Types = sofa::defaulttype::Vec3Types;
using Out = sofa::type::vector<sofa::core::collision::DetectionOutput>;
std::mt19937 rng(77);
double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
void pv(const Vec3& v) { std::printf(" %a %a %a", v[0], v[1], v[2]); }
struct Surface {
  sofa::simulation::Node::SPtr node;
  typename sofa::component::statecontainer::MechanicalObject<Vec3Types>::SPtr mo;
  sofa::component::topology::container::constant::MeshTopology::SPtr topo;
  TriangleCollisionModel<Vec3Types>::SPtr tri; LineCollisionModel<Vec3Types>::SPtr line; PointCollisionModel<Vec3Types>::SPtr point;
  std::vector<Vec3> x; std::vector<std::array<int,3>> t;
};
void make(Surface& s, sofa::simulation::Node* root, const char* name, double z, double shift, int n, double h) {
  // n×n points, random diagonals and flips
  for (int y = 0; y < n; ++y) for (int xx = 0; xx < n; ++xx) s.x.push_back(Vec3(h * xx + shift + U(-0.05, 0.05), h * y + U(-0.05, 0.05), z + U(-0.08, 0.08)));
  for (int y = 0; y + 1 < n; ++y) for (int xx = 0; xx + 1 < n; ++xx) {
    int a = n*y+xx, b = a+1, c = a+n+1, d = a+n; std::array<int,3> t1, t2;
    if (rng() % 2) { t1 = {a,b,c}; t2 = {a,c,d}; } else { t1 = {a,b,d}; t2 = {b,c,d}; }
    if (rng() % 4 == 0) std::swap(t1[1], t1[2]);
    s.t.push_back(t1); s.t.push_back(t2);
  }
  s.node = root->createChild(name);
  s.mo = sofa::core::objectmodel::New<sofa::component::statecontainer::MechanicalObject<Vec3Types>>();
  s.mo->resize(s.x.size());
  { auto w = sofa::helper::getWriteAccessor(*s.mo->write(sofa::core::vec_id::write_access::position)); for (size_t i = 0; i < s.x.size(); ++i) w[i] = s.x[i]; }
  s.topo = sofa::core::objectmodel::New<sofa::component::topology::container::constant::MeshTopology>();
  { auto& st = *s.topo->d_seqTriangles.beginEdit(); for (auto& tt : s.t) st.push_back({(unsigned)tt[0], (unsigned)tt[1], (unsigned)tt[2]}); s.topo->d_seqTriangles.endEdit(); }
  s.tri = sofa::core::objectmodel::New<TriangleCollisionModel<Vec3Types>>();
  s.line = sofa::core::objectmodel::New<LineCollisionModel<Vec3Types>>();
  s.point = sofa::core::objectmodel::New<PointCollisionModel<Vec3Types>>();
  s.node->addObject(s.mo); s.node->addObject(s.topo); s.node->addObject(s.tri); s.node->addObject(s.line); s.node->addObject(s.point);
}
void print(const char* kind, int i, int j, const Out& o) {
  std::printf("%s %d %d %d", kind, i, j, int(o.size()));
  for (auto& d : o) { std::printf(" %lld", (long long)d.id); pv(d.point[0]); pv(d.point[1]); pv(d.normal); std::printf(" %a", d.value); }
  std::printf("\n");
}
int main() {
  sofa::simulation::common::init(); sofa::simulation::graph::init();
  auto root = sofa::simulation::getSimulation()->createNewGraph("root");
  Surface s1, s2; make(s1, root.get(), "one", 0, 0, 4, 0.15); make(s2, root.get(), "two", 0.12, 0.1, 3, 0.25);
  auto inter = sofa::core::objectmodel::New<sofa::component::collision::detection::intersection::NewProximityIntersection>();
  inter->setAlarmDistance(0.2); inter->setContactDistance(0.03);
  root->addObject(inter);
  sofa::simulation::node::initRoot(root.get());
  sofa::component::collision::detection::intersection::MeshNewProximityIntersection mnp(inter.get(), false);
  for (const Surface* s : {&s1, &s2}) {
    std::printf("surface %d %d", int(s->x.size()), int(s->t.size()));
    for (auto& v : s->x) pv(v);
    for (auto& tt : s->t) std::printf(" %d %d %d", tt[0], tt[1], tt[2]);
    std::printf(" %d", int(s->line->getSize()));
    for (unsigned e = 0; e < s->line->getSize(); ++e) { Line l(s->line.get(), e); std::printf(" %d %d", int(l.i1()), int(l.i2())); }
    std::printf("\n");
  }
  for (const bool lineLine : {false, true}) {
    inter->d_useLineLine.setValue(lineLine);
    std::printf("use_line_line %d\n", int(lineLine));
    for (unsigned i = 0; i < s1.t.size(); ++i) for (unsigned j = 0; j < s2.t.size(); ++j) {
      Triangle a(s1.tri.get(), i), b(s2.tri.get(), j); Out o; mnp.computeIntersection(a, b, &o, inter.get()); if (!o.empty()) print("tt", i, j, o); }
    for (unsigned i = 0; i < s1.t.size(); ++i) for (unsigned j = i + 1; j < s1.t.size(); ++j) {
      Triangle a(s1.tri.get(), i), b(s1.tri.get(), j); Out o; mnp.computeIntersection(a, b, &o, inter.get()); if (!o.empty()) print("self", i, j, o); }
    for (unsigned i = 0; i < s1.t.size(); ++i) for (unsigned j = 0; j < s2.line->getSize(); ++j) {
      Triangle a(s1.tri.get(), i); Line b(s2.line.get(), j); Out o; mnp.computeIntersection(a, b, &o, inter.get()); if (!o.empty() && lineLine) print("tl", i, j, o); }
  }
}
