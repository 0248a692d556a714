#include "solver_builder.h"

#include "linear_solver_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/explicit_solvers.h"
#include "fastcorot/sim/newmark_solver.h"
#include "fastcorot/sim/variational_symplectic_solver.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/petsc_linear_solver.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include <algorithm>
#include <limits>

namespace fastcorot::scene_detail {

namespace {

bool is_explicit(const Component& integrator) {
  return integrator.type() == "EulerExplicitSolver" || integrator.type() == "RungeKutta4Solver";
}

// An explicit solver's linear solver when its node has none: fine for a lumped mass, which is
// inverted point by point; a consistent mass needs a solve, which is refused naming the solver.
class MissingLinearSolver final : public LinearSolver<double> {
 public:
  explicit MissingLinearSolver(std::string integrator) : integrator_(std::move(integrator)) {}
  LinearSolveReport solve(const MechanicalSystem<double>&, const MatrixFactors<double>&, std::span<const Vec3<double>>,
                          std::span<Vec3<double>>) override {
    throw make_error(integrator_, ": the mass is not diagonal (MeshMatrixMass without lumping), so it needs a linear "
                     "solver to invert it, and its node has none (add SparseLDLSolver or CGLinearSolver)");
  }

 private:
  std::string integrator_;
};

class SolverBuilder {
 public:
  SolverBuilder(SceneData& data, std::vector<std::string>& info) : data(data), info(info) {}

  std::unique_ptr<OdeSolver<double>> build_integrator(Component& c, const std::vector<GraphNode*>& nodes, Index points) {
    try {
      if (c.type() == "NewmarkImplicitSolver") {
        NewmarkSolver<double>::Parameters p;
        p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
        p.rayleigh_mass = data.real(c, "rayleighMass", 0);
        p.velocity_damping = data.real(c, "vdamping", 0);
        p.gamma = data.real(c, "gamma", 0.5);
        p.beta = data.real(c, "beta", 0.25);
        return std::make_unique<NewmarkSolver<double>>(p, points);
      }
      if (c.type() == "EulerImplicitSolver") {
        ImplicitEulerSolver<double>::Parameters p;
        p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
        p.rayleigh_mass = data.real(c, "rayleighMass", 0);
        p.velocity_damping = data.real(c, "vdamping", 0);
        p.first_order = data.boolean(c, "firstOrder", false);
        p.trapezoidal = data.boolean(c, "trapezoidalScheme", false);
        return std::make_unique<ImplicitEulerSolver<double>>(p);
      }
      if (c.type() == "VariationalSymplecticSolver") {
        VariationalSymplecticSolver<double>::Parameters p;
        p.newton_error = data.real(c, "newtonError", 0.01);
        p.newton_steps = data.whole_number(c, "steps", 5);
        p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
        p.rayleigh_mass = data.real(c, "rayleighMass", 0);
        p.explicit_integration = data.boolean(c, "explicitIntegration", false);
        if (data.boolean(c, "saveEnergyInFile", false)) {
          info.push_back(c.where() + ": saveEnergyInFile: the energies file is not written by fastcorot");
        }
        return std::make_unique<VariationalSymplecticSolver<double>>(p, points);
      }
      if (c.type() == "EulerExplicitSolver") return std::make_unique<ExplicitEulerSolver<double>>(data.boolean(c, "symplectic", true));
      if (c.type() == "RungeKutta4Solver") return std::make_unique<RungeKutta4Solver<double>>();
      StaticSolver<double>::NewtonParameters p;
      Component* newton = newton_of(c, nodes);
      if (newton) {
        p.max_iterations = data.whole_number(*newton, "maxNbIterationsNewton", 1);
        p.max_line_search_iterations = data.whole_number(*newton, "maxNbIterationsLineSearch", 5);
        p.line_search_coefficient = data.real(*newton, "lineSearchCoefficient", 0.5);
        p.relative_successive_threshold =
            data.real(*newton, "relativeSuccessiveStoppingThreshold", 1e-5);
        p.relative_initial_threshold = data.real(*newton, "relativeInitialStoppingThreshold", 1e-5);
        p.absolute_residual_threshold =
            data.real(*newton, "absoluteResidualStoppingThreshold", 1e-5);
        p.relative_estimate_difference_threshold =
            data.real(*newton, "relativeEstimateDifferenceThreshold", 0);
        p.absolute_estimate_difference_threshold =
            data.real(*newton, "absoluteEstimateDifferenceThreshold", 0);
      } else {
        // SOFA creates a NewtonRaphsonSolver and copies the older StaticSolver attributes onto it,
        // including its mapping of the relative residual threshold onto the estimate difference.
        p.max_iterations = data.whole_number(c, "newton_iterations", 1);
        p.absolute_estimate_difference_threshold =
            data.real(c, "absolute_correction_tolerance_threshold", 0);
        p.relative_estimate_difference_threshold =
            data.real(c, "relative_correction_tolerance_threshold", 0);
        p.absolute_residual_threshold = data.real(c, "absolute_residual_tolerance_threshold", 1e-5);
        if (c.has("relative_residual_tolerance_threshold")) {
          p.relative_estimate_difference_threshold =
              data.real(c, "relative_residual_tolerance_threshold", 0);
        }
      }
      return std::make_unique<StaticSolver<double>>(p);
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  // A StaticSolver's NewtonRaphsonSolver: the linked one, else the first in its nodes; nullptr when
  // there is none (SOFA then makes one with default settings). Called first by build_integrator,
  // whose errors name the StaticSolver.
  Component* newton_of(Component& static_solver, const std::vector<GraphNode*>& nodes) {
    if (static_solver.has("newtonSolver")) {
      Component& newton = data.resolve_object(
          *static_solver.node, static_solver.object->attributes.at("newtonSolver"), static_solver);
      if (newton.type() != "NewtonRaphsonSolver") {
        throw make_error("newtonSolver must link a NewtonRaphsonSolver, not ", newton.type());
      }
      return &newton;
    }
    for (GraphNode* node : nodes) {
      for (auto& other : node->components) {
        if (other->type() == "NewtonRaphsonSolver") return other.get();
      }
    }
    return nullptr;
  }

  // The linear solver of an ODE solver, as SOFA's LinearSolverAccessor finds it: its linearSolver
  // link (on a StaticSolver, or on the NewtonRaphsonSolver it drives), else the first linear solver
  // of its nodes.
  Component& linear_solver_of(Component& integrator, const std::vector<GraphNode*>& nodes,
                              const std::vector<Component*>& linear_solvers) {
    Component* holder = &integrator;
    if (!integrator.has("linearSolver") && integrator.type() == "StaticSolver") {
      if (Component* newton = newton_of(integrator, nodes); newton && newton->has("linearSolver"))
        holder = newton;
    }
    if (holder->has("linearSolver")) {
      Component& linked = data.resolve_object(
          *holder->node, holder->object->attributes.at("linearSolver"), *holder);
      if (!linked.spec || linked.spec->category != "linearsolver") {
        throw make_error(
            holder->where(),
            ": linearSolver must link a linear solver (CGLinearSolver, PCGLinearSolver, "
            "EigenSimplicialLDLT, ...), not ",
            linked.where());
      }
      return linked;
    }
    if (linear_solvers.empty()) {
      throw make_error(integrator.where(), ": no linear solver in node ", integrator.node->path,
                       " or below (add CGLinearSolver or EigenSimplicialLDLT)");
    }
    if (linear_solvers.size() > 1) {
      // Solvers that a preconditioner or another solver links to (a PCG's preconditioner, a warp
      // preconditioner's precomputation) are used, through that link.
      std::vector<const Component*> linked;
      for (GraphNode* node : nodes) {
        for (const auto& c : node->components) {
          for (const char* link : {"preconditioner", "linearSolver"}) {
            if (c->spec && c->has(link) && c->object->attributes.at(link).rfind('@', 0) == 0) {
              try {
                linked.push_back(&data.resolve_object(*c->node, c->object->attributes.at(link), *c));
              } catch (const Error&) {
                // a broken link is reported where it is used
              }
            }
          }
        }
      }
      std::string unused;
      for (std::size_t i = 1; i < linear_solvers.size(); ++i) {
        if (std::find(linked.begin(), linked.end(), linear_solvers[i]) != linked.end()) continue;
        unused += (unused.empty() ? "" : ", ") + linear_solvers[i]->where();
      }
      if (!unused.empty()) {
        info.push_back(integrator.where() + ": uses the first linear solver, " + linear_solvers.front()->where() +
                       "; not used: " + unused + " (choose one with linearSolver=\"@name\")");
      }
    }
    return *linear_solvers.front();
  }

  std::unique_ptr<LinearSolver<double>> build_linear_solver(Component& c, Index points,
                                                            const std::vector<GraphNode*>& nodes) {
    if (c.type() == "PCGLinearSolver") return build_pcg(c, points, nodes);
    if (c.type() == "PETScLinearSolver") return build_petsc(c);
    if (c.type() == "MinResLinearSolver") return build_minres(data, c, points);
    if (c.type() == "PrecomputedLinearSolver") return build_precomputed_linear_solver(data, info, c);
    if (c.type() == "EigenSimplicialLDLT") {
      link_to_matrix_system(c, "linearSystem");
      return std::make_unique<SparseDirectSolver<double>>();
    }
    if (data.boolean(c, "warmStart", false)) {
      throw make_error(c.where(),
                       ": warmStart=\"true\" is not supported (the solve starts from zero)");
    }
    ConjugateGradientSolver<double>::Parameters p;
    p.iterations = data.whole_number(c, "iterations", 25);
    p.tolerance = data.real(c, "tolerance", 1e-5);
    p.threshold = data.real(c, "threshold", 1e-5);
    try {
      return std::make_unique<ConjugateGradientSolver<double>>(p);
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  std::unique_ptr<LinearSolver<double>> build_petsc(Component& c) {
    PetscLinearSolver::Parameters p;
    p.ksp = data.text(c, "ksp", p.ksp);
    p.pc = data.text(c, "pc", p.pc);
    p.tolerance = data.real(c, "tolerance", p.tolerance);
    p.max_iterations = data.whole_number(c, "maxIterations", p.max_iterations);
    p.near_null_space = data.boolean(c, "nearNullSpace", p.near_null_space);
    p.rebuild_every = data.whole_number(c, "rebuildEvery", p.rebuild_every);
    p.rebuild_growth = data.real(c, "rebuildGrowth", p.rebuild_growth);
    p.matrix_free = data.boolean(c, "matrixFree", p.matrix_free);
    try {
      return std::make_unique<PetscLinearSolver>(p);
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  std::unique_ptr<LinearSolver<double>> build_pcg(Component& c, Index points,
                                                  const std::vector<GraphNode*>& nodes) {
    PreconditionedConjugateGradientSolver<double>::Parameters p;
    p.iterations = data.whole_number(c, "iterations", 25);
    p.tolerance = data.real(c, "tolerance", 1e-5);
    p.update_step = data.whole_number(c, "update_step", 1);
    // SOFA master keeps the rebuild period on the PCG's linear system, a
    // PreconditionedMatrixFreeSystem (assemblingRate, alias update_step): the linked one, else the
    // first in the solver's nodes.
    Component* system = nullptr;
    if (c.has("linearSystem")) {
      system = &data.resolve_object(*c.node, c.object->attributes.at("linearSystem"), c);
      if (system->type() != "PreconditionedMatrixFreeSystem") {
        throw make_error(c.where(),
                         ": linearSystem must link a PreconditionedMatrixFreeSystem, not ",
                         system->where());
      }
    } else {
      for (GraphNode* node : nodes) {
        for (Component* other : node->of_category("linearsystem")) {
          if (!system && other->type() == "PreconditionedMatrixFreeSystem") system = other;
        }
      }
    }
    if (system) {
      link_to_matrix_system(*system, "preconditionerSystem");
      const char* rate = system->has("assemblingRate") ? "assemblingRate" : "update_step";
      if (system->has("assemblingRate") && system->has("update_step")) {
        throw make_error(system->where(),
                         ": assemblingRate and update_step name the same value: give one");
      }
      const int system_rate = data.whole_number(*system, rate, 1);
      if (system_rate < 1)
        throw make_error(system->where(), ": ", rate, " = ", system_rate, ": must be >= 1");
      if (c.has("update_step") && system->has(rate) && system_rate != p.update_step) {
        throw make_error(c.where(), ": update_step = ", p.update_step, " disagrees with ",
                         system->where(), "'s ", rate, " = ", system_rate,
                         ": give the rebuild period once");
      }
      if (system->has(rate)) p.update_step = system_rate;
    }
    if (!data.boolean(c, "build_precond", true)) p.update_step = std::numeric_limits<int>::max();
    p.preconditioner = Preconditioner::none;
    Component* preconditioner = nullptr;
    if (c.has("preconditioner")) {
      preconditioner = &data.resolve_object(*c.node, c.object->attributes.at("preconditioner"), c);
    } else if (c.has("preconditioners")) {
      const std::string name = data.text(c, "preconditioners", "");
      preconditioner = &data.resolve_object(*c.node, "@" + name, c, name);
    }
    if (preconditioner) link_to_matrix_system(*preconditioner, "linearSystem");
    if (preconditioner && data.boolean(c, "use_precond", true)) {
      if (preconditioner->type() == "BlockJacobiPreconditioner") {
        p.preconditioner = Preconditioner::block_jacobi;
      } else if (preconditioner->type() == "JacobiPreconditioner") {
        p.preconditioner = Preconditioner::jacobi;
      } else if (preconditioner->type() == "PrecomputedWarpPreconditioner") {
        p.preconditioner = Preconditioner::precomputed_warp;
        p.warp_rotations = data.boolean(*preconditioner, "use_rotations", true);
        if (preconditioner->has("linearSolver")) {
          Component& direct = data.resolve_object(*preconditioner->node, preconditioner->object->attributes.at("linearSolver"), *preconditioner);
          if (direct.type() != "EigenSimplicialLDLT") {
            throw make_error(preconditioner->where(), ": linearSolver must link a sparse direct solver, not ", direct.where());
          }
          link_to_matrix_system(direct, "linearSystem");
        }
        if (p.warp_rotations && !has_component(nodes, "TetrahedronFEMForceField")) {
          info.push_back(preconditioner->where() + ": no TetrahedronFEMForceField reports rotations: R is the identity (as in SOFA)");
        }
      } else if (preconditioner->type() == "SSORPreconditioner" || preconditioner->type() == "WarpPreconditioner") {
        p.preconditioner = Preconditioner::solver;
        p.solver = build_preconditioning_solver(data, info, *preconditioner, nodes);
      } else if (preconditioner->type() == "EigenSimplicialLDLT") {
        // SparseLDLSolver, SparseCholeskySolver, ...: the factorisation of the assembled matrix.
        p.preconditioner = Preconditioner::sparse_ldlt;
      } else {
        throw make_error(c.where(), ": preconditioner ", preconditioner->where(),
                         " is not supported; supported: BlockJacobiPreconditioner, JacobiPreconditioner, "
                         "SSORPreconditioner, WarpPreconditioner, PrecomputedWarpPreconditioner, a sparse direct solver (SparseLDLSolver, EigenSimplicialLDLT, ...)");
      }
    }
    if (!preconditioner)
      info.push_back(c.where() + ": no preconditioner: plain conjugate gradient iterations");
    try {
      return std::make_unique<PreconditionedConjugateGradientSolver<double>>(p, points);
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  // A link to the MatrixLinearSystem a preconditioner assembles into in SOFA: checked, nothing more
  // (the preconditioners here take their blocks from the force fields and the mass directly).
  static bool has_component(const std::vector<GraphNode*>& nodes, std::string_view type) {
    for (const GraphNode* node : nodes) {
      for (const auto& c : node->components) {
        if (c->type() == type) return true;
      }
    }
    return false;
  }

  void link_to_matrix_system(Component& c, const std::string& attribute) {
    if (!c.has(attribute)) return;
    Component& target = data.resolve_object(*c.node, c.object->attributes.at(attribute), c);
    if (target.type() != "MatrixLinearSystem" && target.type() != "PrecomputedMatrixSystem" &&
        target.type() != "CompositeLinearSystem" && target.type() != "ConstantSparsityPatternSystem" &&
        target.type() != "RotationMatrixSystem") {
      throw make_error(c.where(), ": ", attribute, " must link a MatrixLinearSystem, not ",
                       target.where());
    }
  }

  SceneData& data;
  std::vector<std::string>& info;
};

}  // namespace

BuiltSolvers build_solvers(SceneData& data, std::vector<std::string>& info, Component& integrator,
                           const std::vector<GraphNode*>& nodes, Index points) {
  std::vector<Component*> linear_solvers;
  for (GraphNode* node : nodes) {
    for (Component* c : node->of_category("linearsolver")) linear_solvers.push_back(c);
  }
  SolverBuilder builder(data, info);
  BuiltSolvers solvers;
  solvers.ode = builder.build_integrator(integrator, nodes, points);
  report_matrix_images(nodes, info);
  if (is_explicit(integrator) && linear_solvers.empty() && !integrator.has("linearSolver")) {
    solvers.linear = std::make_unique<MissingLinearSolver>(integrator.where());
    return solvers;
  }
  solvers.linear = builder.build_linear_solver(
      builder.linear_solver_of(integrator, nodes, linear_solvers), points, nodes);
  return solvers;
}

}  // namespace fastcorot::scene_detail
