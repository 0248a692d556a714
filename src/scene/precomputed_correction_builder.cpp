#include "precomputed_correction_builder.h"

#include "fastcorot/constraint/precomputed_constraint_correction.h"
#include "fastcorot/core/error.h"
#include "fastcorot/sim/rotation_finder.h"

#include <filesystem>
#include <optional>

namespace fastcorot::scene_detail {

std::unique_ptr<ConstraintCorrection<double>> build_precomputed_correction(SceneData& data, std::vector<std::string>& info,
                                                                           Component& c, Simulation<double>& simulation,
                                                                           const StateLocation& where, bool lcp) {
  auto& object = simulation.objects[where.object];
  if (where.rigid || is_rigid_template(data.text(c, "template", "Vec3d"))) {
    throw make_error("on Rigid3 states it is not simulated yet (points only)");
  }
  if (where.offset != 0 || where.size != object.system.size()) {
    throw make_error("its MechanicalObject is one of several under the ODE solver of ", object.path,
                     ": the precomputed compliance is the whole object's (use one MechanicalObject per solver)");
  }
  if (!object.ode_solver->integration_factors(simulation.dt)) {
    throw make_error("the ODE solver of ", object.path, " does not give SOFA's integration factors (SOFA precomputes through an "
                     "EulerImplicitSolver)");
  }
  typename PrecomputedConstraintCorrection<double>::Parameters p;
  using Rotations = typename PrecomputedConstraintCorrection<double>::Rotations;
  p.regularization = data.real(c, "regularizationTerm", 0.0);
  if (data.boolean(c, "rotations", false)) {
    if (!has_rotation_finder(object.system)) {
      data.warn(c.where() + ": rotations=\"1\" finds no point rotations (a TetrahedronFEMForceField or HexahedronFEMForceField "
                "on " + object.path + "): not rotated, as SOFA warns and does not rotate");
    } else if (lcp) {
      p.rotations = Rotations::response;  // SOFA's applyContactForce turns dx = C Hᵀλ
    } else {
      data.warn(c.where() + ": rotations=\"1\" has no effect under SOFA master's Gauss–Seidel family of constraint solvers "
                "(it turns a copy of H and a vector the correction does not read, since sofa PR #3894): "
                "reproduced here, the compliance is not rotated");
    }
  }
  const auto points = static_cast<std::size_t>(object.system.size());
  check_precomputed_compliance_size(c.where(), points);
  const std::string name = compliance_file_name(c.node->scene->name, 3 * points, simulation.dt);
  const std::string dir = data.text(c, "fileDir", "");
  const bool recompute = data.boolean(c, "recompute", false);
  const char* file_data = c.has("fileCompliance") ? "fileCompliance" : "filePrefix";
  const std::string given = data.text(c, file_data, "");
  const std::filesystem::path scene = c.object->location.file;
  // The file to read: fileDir/<name> (read whenever fileDir is set, recompute or not, as SOFA's
  // loadCompliance), else the given file, else SOFA's name on the data paths (unless recompute).
  // SOFA reports a named file it cannot load, then computes C.
  std::optional<std::filesystem::path> cached;
  if (!recompute || !dir.empty()) {
    const std::string wanted = given.empty() ? name : given;
    std::string missing;
    if (!dir.empty()) {
      const std::filesystem::path path = std::filesystem::path(dir) / wanted;
      if (std::filesystem::exists(path)) {
        cached = path;
      } else {
        missing = path.string() + " does not exist";
      }
    } else {
      try {
        cached = find_data_file(scene, wanted);
      } catch (const Error& error) {
        missing = error.what();
      }
    }
    if (!cached && !given.empty()) {
      data.warn(c.where() + ": " + file_data + " \"" + given + "\" cannot be loaded (" + missing + "): the compliance is computed, as SOFA does");
    }
  }
  std::shared_ptr<DenseMatrix<double>> compliance;
  if (cached) {
    compliance = std::make_shared<DenseMatrix<double>>(read_compliance_file<double>(*cached, 3 * points));
    info.push_back(c.where() + ": compliance read from " + cached->string());
  } else {
    compliance = std::make_shared<DenseMatrix<double>>(precompute_compliance(object, simulation.dt));
    const std::filesystem::path out = (dir.empty() ? scene.parent_path() : std::filesystem::path(dir)) / name;
    try {
      write_compliance_file(out, *compliance);
      info.push_back(c.where() + ": compliance computed and written to " + out.string() + " (read back at the next run unless recompute=\"1\")");
    } catch (const Error& error) {
      data.warn(c.where() + ": " + error.what() + ": the compliance is computed again at the next run");
    }
  }
  return std::make_unique<PrecomputedConstraintCorrection<double>>(c.where(), where.object, std::move(compliance), p);
}

}  // namespace fastcorot::scene_detail
