// Constraint-based animation: FreeMotionAnimationLoop, constraint solvers, constraint corrections
// and Lagrangian constraints (built by lagrangian_builder.cpp; docs/constraints.md).
#include "component_families.h"

namespace fastcorot::scene_detail {

namespace {

std::vector<AttributeSpec> solver_attributes() {
  return {{"maxIterations", "int", "1000", "iterations at most"},
          {"maxIt", "int", "1000", "SOFA's alias of maxIterations"},
          {"tolerance", "real", "0.001", "stop when the summed block errors fall below it (times the row count when scaleTolerance)"},
          {"sor", "real", "1", "successive over-relaxation, in (0, 2)"},
          {"regularizationTerm", "real", "0", "added to W's diagonal"},
          {"scaleTolerance", "bool", "true", "scale the tolerance by the number of rows"},
          {"allVerified", "bool", "false", "stop only when every block's error is below the tolerance"},
          {"useSVDForRegularization", "bool", "false", "regularizationTerm only on the rows in W's near-null space (singular value decomposition of W)"},
          {"svdSingularValueNullSpaceCriteriaFactor", "real", "0.01", "singular values below this × the largest span the near-null space"},
          {"svdSingularVectorNullSpaceCriteriaFactor", "real", "0.001", "rows whose entry in a near-null vector exceeds this get the regularisation"},
          {"computeConstraintForces", "bool", "false", "accepted: the impulses λ are always kept (dumps, --json, Python)"},
          {"computeGraphs", "bool", "false", "accepted (SOFA's GUI graphs)"},
          {"multithreading", "bool", "false", "accepted (W is built on the run's threads)"},
          {"constraintForces", "reals", "", "output: the last step's impulses λ, one per row (force × dt)"},
          {"currentIterations", "int", "0", "output: the last solve's iterations"},
          {"currentError", "real", "0", "output: the last solve's error"},
          {"currentNumConstraints", "int", "0", "output: the last step's rows"}};
}

std::vector<AttributeSpec> correction_link_attributes() {
  return {{"linearSolver", "link", "", "accepted: the object's own linear solver is used"},
          {"ODESolver", "link", "", "accepted: the object's own ODE solver is used"},
          {"solverName", "string", "", "accepted (older name of linearSolver)"},
          {"regularizationTerm", "real", "0", "added to W's diagonal on the rows that reach the object"},
          {"wire_optimization", "bool", "false", "accepted (only reorders SOFA's unbuilt solve)"}};
}

}  // namespace

std::vector<ComponentSpec> lagrangian_components() {
  auto generic_solver = solver_attributes();
  generic_solver.push_back({"resolutionMethod", "string", "ProjectedGaussSeidel",
                            "ProjectedGaussSeidel (run as BlockGaussSeidelConstraintSolver), UnbuiltGaussSeidel or NonsmoothNonlinearConjugateGradient (NNCGConstraintSolver)"});
  generic_solver.push_back({"newtonIterations", "int", "100", "NNCG's iteration count (SOFA's change list maps it to maxIterations)"});
  auto jacobi = solver_attributes();
  jacobi.push_back({"useSpectralCorrection", "bool", "false", "scale the violations by spectralCorrectionFactor × min(1, 1.8 / r), r SOFA's spectral measure of W"});
  jacobi.push_back({"spectralCorrectionFactor", "real", "1", "see useSpectralCorrection"});
  jacobi.push_back({"useConjugateResidue", "bool", "false", "after each iteration λ += β Δλ_previous, β = min(1, (i / maxIterations)^conjugateResidueSpeedFactor)"});
  jacobi.push_back({"conjugateResidueSpeedFactor", "real", "10", "see useConjugateResidue"});
  auto generic_correction = correction_link_attributes();
  generic_correction.push_back({"complianceFactor", "real", "1", "scales the compliance and the correction"});
  return {
      {"FreeMotionAnimationLoop", "animationloop",
       "SOFA's constraint-based step: each object's free motion, then the Lagrangian constraints solved on the free positions (W = H A⁻¹ Hᵀ from the corrections) and the objects corrected; without constraints, the default loop's trajectory.",
       {{"solveVelocityConstraintFirst", "bool", "false", "solve on velocities (x = x_start + dt v after the correction)"},
        {"parallelODESolving", "bool", "false", "accepted: objects are integrated on the run's threads"},
        {"parallelCollisionDetectionAndFreeMotion", "bool", "false", "accepted (same results)"},
        {"threadSafeVisitor", "bool", "false", "accepted (no numerical effect)"},
        {"computeBoundingBox", "bool", "true", "accepted (display)"}}},
      {"BlockGaussSeidelConstraintSolver", "constraintsolver",
       "Projected block Gauss–Seidel on the built compliance W, blocks warm-started by their constraints, SOFA's stopping rule.",
       solver_attributes()},
      {"UnbuiltGaussSeidelConstraintSolver", "constraintsolver",
       "The same sweep with λ from zero every step (SOFA's unbuilt variant; W λ is computed from the built W, which gives the same values).",
       solver_attributes()},
      {"NNCGConstraintSolver", "constraintsolver",
       "Nonsmooth nonlinear conjugate gradient: Gauss–Seidel sweeps with a conjugate step after each (β = |Δλ_new|² / |Δλ_old|², reset when above 1); also stops when λ no longer moves.",
       solver_attributes()},
      {"PreconditionedConjugateResidual", "constraintsolver",
       "Conjugate residuals on the Jacobi-scaled W, every row treated as bilateral, at most min(maxIterations, rows) iterations, SOFA's stopping measure.",
       solver_attributes()},
      {"ImprovedJacobiConstraintSolver", "constraintsolver",
       "Projected block Jacobi: every block resolved against the previous iteration's violations, λ from zero (or the constraint's warm start), optional spectral scaling and momentum; never stops after its first iteration.",
       jacobi},
      {"LCPConstraintSolver", "constraintsolver",
       "Projected Gauss–Seidel that solves every three rows as a frictional contact (normal, two tangents; Coulomb's disk with one mu) or, with mu = 0, every row as a frictionless contact; ignores the constraints' own resolutions, as SOFA; λ from zero.",
       {{"maxIt", "int", "1000", "iterations at most"},
        {"tolerance", "real", "0.001", "stop when the summed changes of the violations fall below it × (contacts + 1) (mu > 0) or below it (mu = 0)"},
        {"mu", "real", "0.6", "friction coefficient of every contact; 0: frictionless, one row per contact"},
        {"minW", "real", "0", "contacts whose normal compliance is at most this carry no force (0: off)"},
        {"maxF", "real", "0", "contacts whose normal λ reaches this are dropped (0: off)"},
        {"regularizationTerm", "real", "0", "added to W's diagonal"},
        {"initial_guess", "bool", "true", "accepted: only contacts keep their λ between steps in SOFA (none yet here), so λ starts from zero"},
        {"build_lcp", "bool", "true", "accepted: false (SOFA's unbuilt variant) solves the same problem on the built W"},
        {"computeConstraintForces", "bool", "false", "accepted: the impulses λ are always kept"},
        {"displayDebug", "bool", "false", "accepted"},
        {"group", "indices", "0", "accepted"},
        {"constraintForces", "reals", "", "output: the last step's impulses λ, one per row (force × dt)"},
        {"currentIterations", "int", "0", "output: the last solve's iterations"},
        {"currentError", "real", "0", "output: the last solve's error"},
        {"currentNumConstraints", "int", "0", "output: the last step's rows"}}},
      {"GenericConstraintSolver", "constraintsolver",
       "Gone from SOFA master (v25.12): run as BlockGaussSeidelConstraintSolver or UnbuiltGaussSeidelConstraintSolver according to resolutionMethod, with a warning.",
       generic_solver},
      {"LinearSolverConstraintCorrection", "constraintcorrection",
       "W through the object's own factorised system (sparse triangular solves on the rows of H with a direct solver, one solve per row with an iterative one); corrects x = x_free + h A⁻¹Hᵀλ, v = v_free + A⁻¹Hᵀλ.",
       correction_link_attributes()},
      {"GenericConstraintCorrection", "constraintcorrection",
       "As LinearSolverConstraintCorrection (rows always reach the solver's points through the mappings here), scaled by complianceFactor.",
       generic_correction},
      {"UncoupledConstraintCorrection", "constraintcorrection",
       "A fixed compliance per point (or per rigid body: 1/m and the inverse inertia), no coupling between points.",
       {{"compliance", "reals", "", "one per point (rigid bodies: 7 numbers, 1/m then the rotation's upper triangle)"},
        {"defaultCompliance", "real", "1e-5", "for every point when compliance is not given"},
        {"useOdeSolverIntegrationFactors", "bool", "true", "W and the correction scaled by the ODE solver's factors (h, 1)"},
        {"correctionPositionFactor", "real", "1", "without the ODE factors: x += factor dx"},
        {"correctionVelocityFactor", "real", "1", "without the ODE factors: v += factor / dt dx"},
        {"verbose", "bool", "false", "accepted"},
        {"topology", "link", "", "accepted"}}},
      {"PrecomputedConstraintCorrection", "constraintcorrection",
       "The object's dense compliance C = h P A₀⁻¹ P, computed once at the start (A₀ factorised, exact to round-off; SOFA's CG at 1e-20) "
       "or read from SOFA's cache file <node name>-<3 × points>-<dt>.comp (raw doubles, row after row); W += H C Hᵀ (1/dt in "
       "velocity order), correction x = x_free + C Hᵀλ, v = v_free + C Hᵀλ / dt. Points (Vec3) only, C at most 4 GiB.",
       {{"rotations", "bool", "false", "as SOFA master: under LCPConstraintSolver the response is turned by the point rotations of a "
                                      "TetrahedronFEMForceField or HexahedronFEMForceField (dx = R C Hᵀλ); under the other solvers no effect (warned)"},
        {"restDeformations", "bool", "false", "accepted (SOFA reads it nowhere)"},
        {"recompute", "bool", "false", "compute C rather than search the data paths for a cache file (fileDir's is still read, as SOFA); written either way"},
        {"regularizationTerm", "real", "0", "added to W's diagonal, once per point each row touches (as SOFA's loop adds it)"},
        {"debugViewFrameScale", "real", "1", "accepted (display of the rotations)"},
        {"fileCompliance", "file", "", "the cache file to read (found as mesh files are); default: SOFA's name on the data paths"},
        {"filePrefix", "file", "", "SOFA's alias of fileCompliance"},
        {"fileDir", "string", "", "folder the cache file is read from and written to (default: written beside the scene)"}}},
      {"FixedLagrangianConstraint", "lagrangian",
       "Holds points at their rest positions by Lagrange multipliers: 3 rows per point, violation x_free - x_rest. On Rigid3 states: 6 rows per rigid (centre, rotation), the rotation's violation SOFA's Euler vector of q_free q_rest⁻¹.",
       {{"indices", "indices", "", "the points"}, {"fixAll", "bool", "false", "every point"}}},
      {"BilateralLagrangianConstraint", "lagrangian",
       "Ties point first_point[k] of object1 to second_point[k] of object2 (x2 - x1 = rest_vector[k]) by Lagrange multipliers: 3 rows per pair. On Rigid3 states: 6 rows per pair (centres, rotations), no warm start, activate and load unused (as SOFA).",
       {{"object1", "link", "", "the first state (a node or its MechanicalObject); default: the node's"},
        {"object2", "link", "", "the second state"},
        {"first_point", "indices", "", "points of object1"},
        {"second_point", "indices", "", "points of object2"},
        {"rest_vector", "vec3s", "", "x2 - x1 to keep, per pair (zero when missing); on Rigid3 6 numbers per pair (linear, angular)"},
        {"activate", "bool", "true", "false: no rows"},
        {"load", "real", "1", "scales each update of λ, in [0, 1]"},
        {"keepOrientationDifference", "bool", "false", "Rigid3: keep the frames' difference when the scene is built (rest_vector ignored)"},
        {"numericalTolerance", "real", "0.0001", "accepted"},
        {"topology1", "link", "", "accepted"},
        {"topology2", "link", "", "accepted"}}},
      {"SlidingLagrangianConstraint", "lagrangian",
       "Point sliding_point of object1 slides without friction on the segment axis_1–axis_2 of object2: two bilateral rows across the axis and one unilateral row at each end (3 bilateral rows when the ends coincide); object1 or object2 may be a MechanicalObject no solver integrates (it stays put).",
       {{"object1", "link", "", "the state of the sliding point (a node or its MechanicalObject); default: the node's"},
        {"object2", "link", "", "the state of the segment's ends"},
        {"sliding_point", "int", "0", "the point of object1"},
        {"axis_1", "int", "0", "one end of the segment, in object2"},
        {"axis_2", "int", "0", "the other end, in object2"},
        {"force", "vec3", "", "output in SOFA (Σ row direction × λ): accepted, not kept"}}},
      {"UniformLagrangianConstraint", "lagrangian",
       "Holds every value of a Vec1 state (a DistanceMapping's edge extensions: inextensible edges) at zero, or at its rest value, by Lagrange multipliers: one row per value; violation x_free (velocity order: v_free + x / dt), minus the rest value with constrainToRestPos.",
       {{"iterative", "bool", "true", "one bilateral row at a time; false: all rows as one block, solved by an LDLᵀ of its part of W"},
        {"constrainToRestPos", "bool", "false", "hold the values at the state's rest values rather than at zero"}}},
      {"StopperLagrangianConstraint", "lagrangian",
       "Keeps value `index` of a Vec1 state (a DistanceMapping's edge extension) within [min, max] by one Lagrange multiplier; violation the free value, in either constraint order (as SOFA).",
       {{"index", "int", "0", "the value kept within bounds"},
        {"min", "real", "-100", "lower bound"},
        {"max", "real", "100", "upper bound"}}},
  };
}

}  // namespace fastcorot::scene_detail
