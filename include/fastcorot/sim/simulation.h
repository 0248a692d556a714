// Simulation<Real>: the objects of a scene, each with its ODE solver and linear solver (one SOFA
// solver node each), advanced together one time step at a time as SOFA's DefaultAnimationLoop
// does: each object is integrated in scene order, then time advances by dt. A step that leaves a
// diverged state (a non-finite position or velocity, or a point thrown absurdly far: see
// divergence_factor) stops the simulation with an error naming the step, the time, the object and
// the vertex.
#pragma once

#include "fastcorot/sim/collision_stage.h"
#include "fastcorot/sim/constraint_stage.h"
#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/mapped_state.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/topology_script.h"
#include "fastcorot/sim/visual_surface.h"
#include "fastcorot/topology/tet_mesh.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace fastcorot {

// An RGBA colour, each component in [0, 1] (SOFA's RGBAColor).
using Rgba = std::array<float, 4>;

// How the scene asks one force field to be drawn: SOFA's `drawing` and `drawColor1..4` of
// FastTetrahedralCorotationalForceField (defaults from SPEC.md). Display only: the physics never
// reads it; the render layer does (include/fastcorot/render/).
struct ForceFieldDrawing {
  bool drawing = false;
  std::array<Rgba, 4> colors{{{0.0f, 0.0f, 1.0f, 1.0f}, {0.0f, 0.5f, 1.0f, 1.0f}, {0.0f, 1.0f, 1.0f, 1.0f},
                              {0.5f, 1.0f, 1.0f, 1.0f}}};  // drawColor1..4
};

// An axis-aligned box of a BoxROI, in the coordinates of the points it selects from.
struct DrawnBox {
  Vec3<double> min;
  Vec3<double> max;
};

template <class Real>
struct SimulatedObject {
  std::string path;               // node path from the root, names joined by '/'
  std::shared_ptr<TetMesh> mesh;  // the elements (for output), may be null
  MechanicalSystem<Real> system;
  std::unique_ptr<OdeSolver<Real>> ode_solver;
  std::unique_ptr<LinearSolver<Real>> linear_solver;
  // Display information, never read by the physics: one entry per system.force_fields (same
  // order), and the BoxROI boxes of the object's nodes (fixed points are system.fixed).
  std::vector<ForceFieldDrawing> force_field_drawing;
  std::vector<DrawnBox> boxes;
  // Visual models mapped onto the object's points (OglModel with a BarycentricMapping or
  // IdentityMapping in a child node); display and output only.
  std::vector<VisualSurface> visual_surfaces;
  // The MechanicalObjects the state is made of (one, or several under one solver), and those of
  // mapped child nodes that follow it (outputs only: sim/mapped_state.h).
  std::vector<StateRange> states;
  std::vector<MappedState> mapped_states;
  // Scripted topological changes (TopologicalChangeProcessor), applied at the start of each step.
  std::vector<TopologyScript> topology_scripts;
};

template <class Real>
class Simulation {
 public:
  Real dt = Real(0.01);
  Vec3<Real> gravity{Real(0), Real(-9.81), Real(0)};
  std::vector<SimulatedObject<Real>> objects;
  // Objects are independent; with threads > 1 they are integrated concurrently (like SOFA's
  // parallelODESolving), and threads beyond one per object go to each object's kernels (force
  // field, products, solver vectors). Each object's result is bitwise the same whatever the count.
  int threads = 1;
  // A point has "exploded" when it is farther from its rest position than divergence_factor times
  // the scene's size (scene_size()), or when its velocity would carry it that far in one step.
  // Elastic bodies never get there: 1e6 sizes is a kilometre for a millimetre part, and a free
  // fall takes about sqrt(2e6 L / g) seconds (450 s for L = 1 m) to cover it. Explosions grow
  // geometrically, so the test catches them a few steps before they overflow, with finite values
  // to report. 0 (or infinity) turns the test off; non-finite values are always divergence.
  Real divergence_factor = Real(1e6);
  // SOFA's FreeMotionAnimationLoop (null: its DefaultAnimationLoop): after every object's free
  // motion, the Lagrangian constraints are solved and the objects corrected (sim/constraint_stage.h).
  std::shared_ptr<ConstraintStage<Real>> constraints;
  // SOFA's collision pipeline (null: none): contacts found at each step's start, their responses
  // felt during it (sim/collision_stage.h).
  std::shared_ptr<CollisionStage<Real>> collisions;

  // Advances every object by dt: first the scripted topological changes due at the current time,
  // then the integration. Throws fastcorot::Error "diverged at step N (t = T): OBJECT vertex V
  // ..." when a state diverges (the state before the step is lost for that object; others are
  // advanced; steps_done() stays at N - 1), or "at step N (t = T): ..." for a failed change.
  StepReport step();

  // Applies the scripted topological changes of steps_done() + 1 .. `steps` without integrating:
  // what a run resumed at step `steps` must do to its freshly built scene before taking the
  // checkpoint's state. Does not change steps_done().
  void replay_topology_changes(long steps);

  long steps_done() const { return steps_done_; }
  // What the constraint stage did in the last step (all zero without one).
  const ConstraintReport& constraint_report() const { return constraint_report_; }
  // What the collision stage did in the last step (all zero without one).
  const CollisionReport& collision_report() const { return collision_report_; }
  Real time() const { return static_cast<Real>(steps_done_) * dt; }
  // Sets the step counter (and so the time): for resuming from a checkpoint. Throws for steps < 0.
  void set_steps_done(long steps);

  // The diagonal of the bounding box of every object's rest positions (1 when that is zero, as for
  // a single point or an empty scene): the length divergence_factor is measured in.
  Real scene_size() const;

 private:
  void apply_topology_changes(long step_number, double clock);

  long steps_done_ = 0;
  ConstraintReport constraint_report_;
  CollisionReport collision_report_;
  // SOFA's context time: dt added once per step, rounding included (0.01 ten times is
  // 0.09999999999999999). Scripted topological changes compare their times with it, as SOFA's
  // TopologicalChangeProcessor does, so that they fire at the very step they fire in SOFA.
  double clock_ = 0;
};

}  // namespace fastcorot
