// PrecomputedConstraintCorrection in scenes: with a linear (small-strain) beam, whose matrix never
// changes, FixedLagrangianConstraint with the precomputed compliance gives the
// FixedProjectiveConstraint trajectory to the constraint solver's tolerance (KKT = projection when W
// is exact); SOFA's cache file is written under its name, read back (the same W to the bit), and a
// truncated one refused naming it; with rotations a turning corotational beam stays nearer the
// projective trajectory than without; what cannot be precomputed is refused in one line.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/precomputed_constraint_correction.h"
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const char* kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";
const std::string kLeftEnd = "<BoxROI name=\"box\" box=\"-0.01 -0.01 -0.01 0.01 0.21 0.21\"/>";

// A beam of 6 × 2 × 2 points (24: C is 72 × 72) from x = 0 to 1, TetrahedronFEMForceField `method`.
std::string beam(const std::string& method, const std::string& extra, const std::string& field = "") {
  return "<Node name=\"beam\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology name=\"grid\" n=\"6 2 2\" min=\"0 0 0\" max=\"1 0.2 0.2\"/><MechanicalObject name=\"dofs\"/>" +
         (field.empty() ? "<TetrahedronFEMForceField youngModulus=\"5e4\" poissonRatio=\"0.3\" method=\"" + method + "\"/>" : field) +
         "<UniformMass totalMass=\"1\"/>" + kLeftEnd + extra + "</Node>";
}

std::string lagrangian(const std::string& method, const std::string& correction, const std::string& field = "") {
  return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"5000\" tolerance=\"1e-15\"/>" +
         beam(method, "<FixedLagrangianConstraint indices=\"@box.indices\"/>" + correction, field);
}

double max_difference(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

bool warned(const LoadedScene& scene, const std::string& text) {
  for (const auto& line : scene.warnings) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

std::filesystem::path fresh_folder(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(PrecomputedCorrectionScene, LinearBeamFollowsTheProjectiveTrajectory) {
  const auto dir = fresh_folder("fastcorot_precomputed_linear");
  LoadedScene projective = build_scene_text(beam("small", "<FixedProjectiveConstraint indices=\"@box.indices\"/>"), kRoot);
  LoadedScene precomputed =
      build_scene_text(lagrangian("small", "<PrecomputedConstraintCorrection fileDir=\"" + dir.string() + "\"/>"), kRoot);
  ASSERT_TRUE(precomputed.simulation.constraints);
  const auto& a = projective.simulation.objects[0].system.state;
  const auto& b = precomputed.simulation.objects[0].system.state;
  double sag = 0;
  for (int step = 1; step <= 100; ++step) {
    projective.simulation.step();
    precomputed.simulation.step();
    ASSERT_LT(max_difference(a.position, b.position), 1e-10) << "step " << step;
    ASSERT_LT(max_difference(a.velocity, b.velocity), 1e-8) << "step " << step;
    sag = std::max(sag, -a.position[5].y());
  }
  EXPECT_GT(sag, 1e-3) << "the beam bends under its weight";
  EXPECT_TRUE(precomputed.simulation.constraint_report().converged);
  EXPECT_TRUE(std::filesystem::exists(dir / "beam-72-0.01.comp")) << "SOFA's name: node, rows, dt";
  std::filesystem::remove_all(dir);
}

TEST(PrecomputedCorrectionScene, CacheFileIsWrittenThenReadBack) {
  const auto dir = fresh_folder("fastcorot_precomputed_cache");
  const std::string scene = lagrangian("large", "<PrecomputedConstraintCorrection fileDir=\"" + dir.string() + "\"/>");
  LoadedScene first = build_scene_text(scene, kRoot);
  const auto file = dir / "beam-72-0.01.comp";
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_EQ(std::filesystem::file_size(file), 72u * 72u * sizeof(double));
  const auto said = [](const LoadedScene& s, const std::string& text) {
    for (const auto& line : s.info) {
      if (line.find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(said(first, "computed and written"));
  const auto compliance_of = [](const LoadedScene& s) -> const DenseMatrix<double>& {
    const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(s.simulation.constraints.get());
    const auto* correction = dynamic_cast<const PrecomputedConstraintCorrection<double>*>(loop->corrections.at(0).get());
    if (!correction) throw Error("no precomputed correction");
    return correction->compliance();
  };
  const auto w_of = [](const LoadedScene& s) {
    return dynamic_cast<const FreeMotionAnimationLoop<double>*>(s.simulation.constraints.get())->problem().w;
  };
  const DenseMatrix<double> c = compliance_of(first);
  // Twice C in the file: the next scene reads it (rather than computing C again).
  write_compliance_file(file, DenseMatrix<double>(2 * c));
  LoadedScene doubled = build_scene_text(scene, kRoot);
  EXPECT_TRUE(said(doubled, "read from"));
  EXPECT_EQ(compliance_of(doubled), DenseMatrix<double>(2 * c));
  // C itself written back: the same W and trajectory to the bit.
  write_compliance_file(file, c);
  LoadedScene second = build_scene_text(scene, kRoot);
  first.simulation.step();
  second.simulation.step();
  doubled.simulation.step();
  EXPECT_EQ(w_of(first), w_of(second));
  EXPECT_EQ(DenseMatrix<double>(2 * w_of(first)), w_of(doubled));
  EXPECT_EQ(first.simulation.objects[0].system.state.position, second.simulation.objects[0].system.state.position);
  // recompute with fileDir: SOFA's loadCompliance still reads fileDir's file (recompute only skips
  // the search of the data paths).
  LoadedScene third = build_scene_text(
      lagrangian("large", "<PrecomputedConstraintCorrection recompute=\"1\" fileDir=\"" + dir.string() + "\"/>"), kRoot);
  EXPECT_TRUE(said(third, "read from"));
  // A truncated file: refused, naming it.
  std::filesystem::resize_file(file, 100);
  const std::string error = scene_error(lagrangian("large", "<PrecomputedConstraintCorrection fileDir=\"" + dir.string() + "\"/>"));
  EXPECT_NE(error.find(file.string()), std::string::npos) << error;
  EXPECT_NE(error.find("PrecomputedConstraintCorrection"), std::string::npos) << error;
  // fileCompliance names the file to read (SOFA's .comp files, found as mesh files are).
  std::filesystem::resize_file(file, 0);
  std::filesystem::remove(file);
  build_scene_text(scene, kRoot);
  const auto renamed = dir / "mine.comp";
  std::filesystem::rename(file, renamed);
  LoadedScene named = build_scene_text(lagrangian("large", "<PrecomputedConstraintCorrection fileCompliance=\"" + renamed.string() + "\"/>"), kRoot);
  EXPECT_TRUE(said(named, "read from " + renamed.string()));
  std::filesystem::remove_all(dir);
}

TEST(PrecomputedCorrectionScene, RotationsAreSofasUnderEachSolver) {
  // SOFA master: under its Gauss–Seidel family rotations="1" changes nothing (warned here); under
  // LCPConstraintSolver the response is turned by the point rotations, which keeps a turning beam
  // nearer the projective trajectory than the unrotated response.
  const auto dir = fresh_folder("fastcorot_precomputed_rotations");
  const std::string where = " fileDir=\"" + dir.string() + "\"";
  const std::string heavy = "<TetrahedronFEMForceField youngModulus=\"2e3\" poissonRatio=\"0.3\" method=\"large\"/>";
  LoadedScene plain = build_scene_text(lagrangian("", "<PrecomputedConstraintCorrection" + where + "/>", heavy), kRoot);
  LoadedScene asked = build_scene_text(lagrangian("", "<PrecomputedConstraintCorrection rotations=\"1\"" + where + "/>", heavy), kRoot);
  EXPECT_TRUE(warned(asked, "has no effect under SOFA master's Gauss–Seidel family"));
  for (int step = 0; step < 20; ++step) {
    plain.simulation.step();
    asked.simulation.step();
  }
  EXPECT_EQ(plain.simulation.objects[0].system.state.position, asked.simulation.objects[0].system.state.position);
  // LCP with mu = 0: the fixed points' rows as frictionless contacts, so both beams are held only
  // where the rows push; compare the rotated and unrotated responses on the same rows.
  const auto lcp = [&](const std::string& rotations) {
    return "<FreeMotionAnimationLoop/><LCPConstraintSolver mu=\"0\" maxIt=\"5000\" tolerance=\"1e-15\"/>" +
           beam("", "<FixedLagrangianConstraint indices=\"@box.indices\"/><PrecomputedConstraintCorrection" + rotations + where + "/>", heavy);
  };
  LoadedScene unturned = build_scene_text(lcp(""), kRoot);
  LoadedScene turning = build_scene_text(lcp(" rotations=\"1\""), kRoot);
  double apart = 0;
  for (int step = 0; step < 30; ++step) {
    unturned.simulation.step();
    turning.simulation.step();
    apart = std::max(apart, max_difference(unturned.simulation.objects[0].system.state.position,
                                           turning.simulation.objects[0].system.state.position));
  }
  EXPECT_GT(apart, 1e-6) << "the LCP response is turned";
  std::filesystem::remove_all(dir);
}

TEST(PrecomputedCorrectionScene, RefusesWhatItCannotPrecompute) {
  const auto dir = fresh_folder("fastcorot_precomputed_refusals");
  const std::string where = " fileDir=\"" + dir.string() + "\"";
  // rotations without a rotation finder (FastTetrahedralCorotationalForceField has none in SOFA).
  const std::string fast = "<TetrahedronSetTopologyContainer name=\"tets\"/><Hexa2TetraTopologicalMapping input=\"@grid\" "
                           "output=\"@tets\"/><FastTetrahedralCorotationalForceField youngModulus=\"5e4\" poissonRatio=\"0.3\"/>";
  LoadedScene unrotated = build_scene_text(lagrangian("", "<PrecomputedConstraintCorrection rotations=\"1\"" + where + "/>", fast), kRoot);
  EXPECT_TRUE(warned(unrotated, "finds no point rotations"));
  EXPECT_EQ(scene_error(lagrangian("", "<PrecomputedConstraintCorrection" + where + "/>", fast)), "");
  // Two kinds of correction on one object.
  EXPECT_NE(scene_error(lagrangian("large", "<PrecomputedConstraintCorrection" + where + "/><LinearSolverConstraintCorrection/>"))
                .find("one kind of correction"),
            std::string::npos);
  EXPECT_NE(scene_error(lagrangian("large", "<LinearSolverConstraintCorrection/><PrecomputedConstraintCorrection" + where + "/>"))
                .find("one kind of correction"),
            std::string::npos);
  // An ODE solver without SOFA's integration factors.
  const std::string explicit_beam =
      "<FreeMotionAnimationLoop/><Node name=\"beam\"><EulerExplicitSolver/><RegularGridTopology n=\"2 2 2\" min=\"0 0 0\" "
      "max=\"1 1 1\"/><MechanicalObject/><UniformMass totalMass=\"1\"/><PrecomputedConstraintCorrection" + where + "/></Node>";
  EXPECT_NE(scene_error(explicit_beam).find("integration factors"), std::string::npos) << scene_error(explicit_beam);
  // A fileCompliance that cannot be loaded: SOFA's report, as a warning, then C computed.
  LoadedScene missing =
      build_scene_text(lagrangian("large", "<PrecomputedConstraintCorrection fileCompliance=\"missing.comp\"" + where + "/>"), kRoot);
  bool warned = false;
  for (const auto& line : missing.warnings) warned = warned || line.find("missing.comp\" cannot be loaded") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_TRUE(std::filesystem::exists(dir / "beam-72-0.01.comp"));
  // The refused example of the component table is another component now.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/><AugmentedLagrangianConstraint/>").find("not simulated yet"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fastcorot
