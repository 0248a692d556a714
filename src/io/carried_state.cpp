#include "fastcorot/io/carried_state.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/checkpoint.h"

#include <map>

namespace fastcorot {

CarriedState carry_state(const Simulation<double>& from, Simulation<double>& to) {
  CarriedState result;
  std::map<std::string, const SimulatedObject<double>*> before;
  for (const auto& object : from.objects) before.emplace(object.path, &object);
  for (auto& object : to.objects) {
    const auto it = before.find(object.path);
    if (it == before.end()) {
      result.fresh.push_back(object.path);
      continue;
    }
    const SimulatedObject<double>& old = *it->second;
    const ObjectFingerprint a = object_fingerprint(old), b = object_fingerprint(object);
    if (a.vertices != b.vertices || a.tetrahedra != b.tetrahedra || a.rest != b.rest || a.elements != b.elements) {
      throw make_error(object.path, ": the scene was built again while running (a node added or removed), but this object's ",
                       "points, rest positions or elements differ from the running one's (changed by cutting?): its state ",
                       "cannot be carried over");
    }
    const std::size_t rigids = object.system.rigids ? object.system.rigids->size() : 0;
    const std::size_t old_rigids = old.system.rigids ? old.system.rigids->size() : 0;
    if (rigids != old_rigids) throw make_error(object.path, ": the rebuilt object has ", rigids, " rigid bodies, the running one ", old_rigids);
    // A solver of another kind (the script changed it) starts afresh.
    if (object.ode_solver && old.ode_solver && object.ode_solver->carried_state().size() == old.ode_solver->carried_state().size()) {
      object.ode_solver->restore_carried_state(old.ode_solver->carried_state());
    }
    if (object.linear_solver && old.linear_solver) {
      try {
        object.linear_solver->check_carried_state(old.linear_solver->carried_state());
        object.linear_solver->restore_carried_state(old.linear_solver->carried_state());
      } catch (const Error&) {
        result.notes.push_back(object.path + ": its linear solver starts afresh (another kind than the running one's)");
      }
    }
    for (const auto& field : old.system.force_fields) {
      if (const std::string unsaved = field->unsaved_state(); !unsaved.empty()) {
        result.notes.push_back(object.path + ": its " + field->component() + "'s " + unsaved + " start again");
      }
    }
    object.system.state.position = old.system.state.position;
    object.system.state.velocity = old.system.state.velocity;
    if (auto& frames = object.system.rigids) {
      frames->orientation = old.system.rigids->orientation;
      frames->rebase(object.system.state.position);  // passes them on to the followers
    }
    result.carried.push_back(object.path);
  }
  if (from.constraints) {
    result.notes.push_back("the FreeMotionAnimationLoop's last impulses (its constraint solver's warm start) start again from zero");
  }
  to.dt = from.dt;
  to.set_steps_done(from.steps_done());
  return result;
}

}  // namespace fastcorot
