// SOFA's RigidMass and UniformMass<Rigid3> (RigidMass.h, UniformMass.inl/.cpp). Reference values:
// SOFA's share/BehaviorModels/torus2.rigid and card.rigid (their numbers, as the files hold them),
// SOFA's UniformMass_test.cpp (card.rigid on 2 rigids: vertexMass 40, totalMass 80;
// checkRigidAttribute: vertexMass '1 1 2 0 0 0 4 0 7 8 9' gives inertia rows (2 0 0)(0 4 0)(7 8 9)),
// and M (v, ω) = (m v, m I ω) by hand.
#include "fastcorot/state/rigid_mass.h"

#include "fastcorot/core/error.h"

#include "../support/error_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using V3 = Vec3<double>;
using M3 = Mat3<double>;

using testing::contains;
using testing::error_of;

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("fastcorot_rigid_mass_" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// SOFA's share/BehaviorModels/torus2.rigid, with its CRLF line ends.
const char* torus2 =
    "Xsp 3.0\r\n"
    "vertexMass 5\r\n"
    "volm 8.7452405401\r\n"
    "inrt 1.3896649307 -0.0000003707 -0.0000000068 -0.0000003707 1.9546878360 0.0000000045 -0.0000000068 "
    "0.0000000045 3.2215295226\r\n"
    "center 0.0184738064 0.0000006143 -0.0000000243\r\n";

void expect_torus2(const RigidFile& file) {
  ASSERT_TRUE(file.vertex_mass && file.volume && file.inertia && file.center);
  EXPECT_EQ(*file.vertex_mass, 5.0);
  EXPECT_EQ(*file.volume, 8.7452405401);
  EXPECT_EQ((*file.inertia)(0, 0), 1.3896649307);
  EXPECT_EQ((*file.inertia)(1, 1), 1.9546878360);
  EXPECT_EQ((*file.inertia)(2, 2), 3.2215295226);
  EXPECT_EQ((*file.inertia)(0, 1), -0.0000003707);
  EXPECT_EQ((*file.inertia)(2, 0), -0.0000000068);
  EXPECT_EQ((*file.inertia)(1, 2), 0.0000000045);
  EXPECT_EQ(*file.center, V3(0.0184738064, 0.0000006143, -0.0000000243));
}

TEST(RigidMass, ReadsSofaTorus2RigidFile) {
  expect_torus2(read_rigid_file(write_temp("torus2.rigid", torus2)));
  // SOFA's own copy, beside the project when present.
  const auto sofa = std::filesystem::path(FASTCOROT_SOURCE_DIR) / "../shared/sofa-scenes/share/BehaviorModels/torus2.rigid";
  if (std::filesystem::exists(sofa)) expect_torus2(read_rigid_file(sofa.string()));

  UniformRigidMassInput<double> input;
  input.file = read_rigid_file(write_temp("torus2.rigid", torus2));
  const RigidMass<double> m = uniform_rigid_mass(input, 1, "UniformMass");
  EXPECT_EQ(m.mass, 5.0);
  EXPECT_EQ(m.volume, 8.7452405401);
  EXPECT_EQ(m.inertia(2, 2), 3.2215295226);
  EXPECT_EQ(m.inertia_mass()(1, 1), 5.0 * 1.9546878360);
}

TEST(RigidMass, FileKeywordsCommentsAndNumbersAcrossLines) {
  const std::string text =
      "Xsp 3.0 anything here is skipped\n"
      "# a comment vertexMass 99\n"
      "vertexMass 2.5 volm 0.5\n"
      "inrt 1 0 0\n 0 2 0\n 0 0 3\n"
      "cntr 0 0 0 frme 0 0 0 1 grav 0 -9.81 0 visc 0 stck 0 step 0.01 prec 1e-6\n";
  const RigidFile file = read_rigid_file(write_temp("keys.rigid", text));
  EXPECT_EQ(*file.vertex_mass, 2.5);
  EXPECT_EQ(*file.volume, 0.5);
  EXPECT_EQ(*file.inertia, M3(V3(1, 2, 3).asDiagonal()));
}

TEST(RigidMass, FileErrorsNameFileAndLine) {
  const std::string bad_number = write_temp("bad.rigid", "Xsp 3.0\nvertexMass 5\ninrt 1 0 0 0 x 0 0 0 1\n");
  std::string e = error_of([&] { read_rigid_file(bad_number); });
  EXPECT_TRUE(contains(e, bad_number + ":3:")) << e;
  EXPECT_TRUE(contains(e, "'inrt' needs 9 finite numbers, got 'x'")) << e;

  const std::string short_file = write_temp("short.rigid", "Xsp 3.0\nvertexMass 5\ninrt 1 0 0\n");
  e = error_of([&] { read_rigid_file(short_file); });
  EXPECT_TRUE(contains(e, short_file + ":3:")) << e;
  EXPECT_TRUE(contains(e, "file ends")) << e;

  const std::string unknown = write_temp("unknown.rigid", "Xsp 3.0\n\nmass 5\n");  // SOFA's key is vertexMass
  e = error_of([&] { read_rigid_file(unknown); });
  EXPECT_TRUE(contains(e, unknown + ":3: unknown keyword 'mass'")) << e;

  e = error_of([&] { read_rigid_file("/nonexistent/torus.rigid"); });
  EXPECT_TRUE(contains(e, "/nonexistent/torus.rigid: cannot open")) << e;
}

TEST(RigidMass, VertexMassText) {
  // SOFA's UniformMass_test checkRigidAttribute.
  const std::vector<double> full = {1, 1, 2, 0, 0, 0, 4, 0, 7, 8, 9};
  const RigidMass<double> m = parse_rigid_mass<double>(full, "UniformMass vertexMass");
  EXPECT_EQ(m.mass, 1.0);
  EXPECT_EQ(m.volume, 1.0);
  M3 expected;
  expected << 2, 0, 0, 0, 4, 0, 7, 8, 9;
  EXPECT_EQ(m.inertia, expected);
  // The mass alone: volume 1 and identity inertia stay.
  const std::vector<double> alone = {3};
  const RigidMass<double> a = parse_rigid_mass<double>(alone, "w");
  EXPECT_EQ(a.mass, 3.0);
  EXPECT_EQ(a.inertia, M3::Identity());
  const std::vector<double> five = {1, 1, 2, 0, 0};
  std::string e = error_of([&] { parse_rigid_mass<double>(five, "scene.scn:9 UniformMass"); });
  EXPECT_TRUE(contains(e, "scene.scn:9 UniformMass")) << e;
  EXPECT_TRUE(contains(e, "got 5 numbers")) << e;
  const std::vector<double> negative = {-1};
  e = error_of([&] { parse_rigid_mass<double>(negative, "w"); });
  EXPECT_TRUE(contains(e, "negative mass")) << e;
}

TEST(RigidMass, UniformMassSemantics) {
  // totalMass alone: split over the rigids, identity inertia (SOFA's default RigidMass).
  UniformRigidMassInput<double> total;
  total.total_mass = 6.0;
  RigidMass<double> m = uniform_rigid_mass(total, 3, "UniformMass");
  EXPECT_EQ(m.mass, 2.0);
  EXPECT_EQ(m.inertia, M3::Identity());
  EXPECT_EQ(m.inertia_mass(), 2.0 * M3::Identity());

  // vertexMass and totalMass: totalMass wins for the mass, the inertia of vertexMass stays.
  UniformRigidMassInput<double> both;
  const std::vector<double> vm = {1, 1, 2, 0, 0, 0, 4, 0, 0, 0, 9};
  both.vertex_mass = parse_rigid_mass<double>(vm, "w");
  both.total_mass = 10.0;
  m = uniform_rigid_mass(both, 4, "UniformMass");
  EXPECT_EQ(m.mass, 2.5);
  EXPECT_EQ(m.inertia(1, 1), 4.0);

  // SOFA's UniformMass_test loadFromAFileForRigid: card.rigid on 2 rigids, vertexMass 40 (total 80).
  const std::string card = write_temp("card.rigid",
      "Xsp 3.0\nvertexMass 40.0000000000\nvolm 0.0400000000\n"
      "inrt 0.4166666667 0.0000000000 0.0000000000 0.0000000000 0.0833666667 0.0000000000 0.0000000000 "
      "0.0000000000 0.3333666667\ncntr 0.0000000000 0.0000000000 0.0000000000\n");
  UniformRigidMassInput<double> file;
  file.file = read_rigid_file(card);
  m = uniform_rigid_mass(file, 2, "UniformMass");
  EXPECT_EQ(m.mass, 40.0);
  EXPECT_EQ(2 * m.mass, 80.0);
  EXPECT_EQ(m.inertia(1, 1), 0.0833666667);
  // The file's vertexMass drops a totalMass given without vertexMass.
  file.total_mass = 1.0;
  EXPECT_EQ(uniform_rigid_mass(file, 2, "UniformMass").mass, 40.0);
  // ... but not one given with vertexMass: then totalMass / n.
  file.vertex_mass = RigidMass<double>{};
  EXPECT_EQ(uniform_rigid_mass(file, 2, "UniformMass").mass, 0.5);

  std::string e = error_of([&] { uniform_rigid_mass(UniformRigidMassInput<double>{}, 1, "scene.scn:3 UniformMass"); });
  EXPECT_TRUE(contains(e, "scene.scn:3 UniformMass: no mass given")) << e;
  UniformRigidMassInput<double> negative;
  negative.total_mass = -1.0;
  e = error_of([&] { uniform_rigid_mass(negative, 1, "UniformMass"); });
  EXPECT_TRUE(contains(e, "totalMass")) << e;
}

TEST(RigidMass, WeightBlocksAndMassTimesVector) {
  RigidMass<double> m;
  m.mass = 2;
  m.inertia << 1, 0.1, 0, 0.1, 2, 0, 0, 0, 3;
  EXPECT_EQ(m.weight(V3(0, -9.81, 0)), V3(0, -19.62, 0));
  const RigidMassBlocks<double> blocks = mass_blocks(m);
  EXPECT_EQ(blocks.linear, 2.0 * M3::Identity());
  EXPECT_EQ(blocks.angular, 2.0 * m.inertia);

  // Two rigids, M (v, ω) by hand, scaled by 0.5, accumulated onto ones.
  const std::vector<V3> dx = {V3(1, 2, 3), V3(1, 0, 0), V3(-1, 0, 0), V3(0, 1, 1)};
  std::vector<V3> out(4, V3::Ones());
  add_m_dx<double>(m, dx, out, 0.5);
  EXPECT_LT((out[0] - V3(2, 3, 4)).norm(), 1e-15);         // 1 + 0.5·2·(1, 2, 3)
  EXPECT_LT((out[1] - V3(2, 1.1, 1)).norm(), 1e-15);       // 1 + 0.5·2·(1, 0.1, 0)
  EXPECT_LT((out[2] - V3(0, 1, 1)).norm(), 1e-15);
  EXPECT_LT((out[3] - V3(1.1, 3, 4)).norm(), 1e-15);       // 1 + (0.1, 2, 3)
  std::vector<V3> odd(3);
  EXPECT_THROW(add_m_dx<double>(m, std::span<const V3>(dx.data(), 3), odd, 1.0), Error);
}

}  // namespace
}  // namespace fastcorot
