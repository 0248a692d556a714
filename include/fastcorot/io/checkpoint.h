// Checkpoints: the whole evolving state of a Simulation<double> in one binary file, so that a run
// can stop and later resume with a trajectory bitwise identical to an uninterrupted one
// (`fastcorot run --checkpoint-every K`, `--resume FILE`).
//
// What a resumed run needs beyond the scene itself: the step counter (time is steps × dt), every
// object's positions and velocities, and what its solvers carry from one step to the next
// (carried_state(): the CG's solve count, whose first solve stops differently). Everything else is
// rebuilt from the scene: rest data, masses, constraints, constant forces; the force field's
// rotations and edge stiffness are recomputed by add_force at the start of every step, and the
// direct solver's cached analysis depends only on the matrix pattern.
//
// Format, version 1. Integers and IEEE-754 doubles little-endian; a string is a u32 byte count
// and its bytes.
//   offset 0   8 bytes  magic "FCOROTCK"
//          8   u32      format version (1)
//         12   u32      bytes per real (8)
//         16   u64      size of the whole file in bytes
//         24   string   the scene as given on the command line (for messages only)
//              f64      dt
//              i64      step (steps done)
//              u32      object count, then per object, in scene order:
//                string   node path (root/beam)
//                u64      vertex count V, u64 tetrahedron count
//                u64 ×3   fingerprints of the rest positions, of the tetrahedra, and of the rest of
//                         the model (masses, fixed and velocity-projected points, constant forces,
//                         gravity, force-field parameters, the kinds of ODE and linear solver)
//                f64 ×3V  positions, then f64 ×3V velocities
//                u32 n, i64 ×n  the ODE solver's carried state; u32 n, i64 ×n  the linear solver's
//   last 8 bytes  u64   FNV-1a 64 of every byte before it
// Fingerprints are FNV-1a 64 of the little-endian bytes of the values. FNV-1a detects every single
// changed byte (each step of it is a bijection); solver settings (tolerances, Rayleigh
// coefficients) are not fingerprinted: changing them on resume is allowed and changes the run.
#pragma once

#include "fastcorot/sim/simulation.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fastcorot {

// Version 2 adds the rigid bodies' orientations after each object's solver states; version 1
// files (no rigid bodies) are still read.
inline constexpr std::uint32_t kCheckpointVersion = 2;

// What a checkpoint records of one object's scene, to check that a resumed run has the same one:
// counts, and the fingerprints described above.
struct ObjectFingerprint {
  std::uint64_t vertices = 0;
  std::uint64_t tetrahedra = 0;
  std::uint64_t rest = 0;
  std::uint64_t elements = 0;
  std::uint64_t model = 0;
  bool operator==(const ObjectFingerprint&) const = default;
};

// One object's fingerprint.
ObjectFingerprint object_fingerprint(const SimulatedObject<double>& object);

// Every object's fingerprint, in scene order. A distributed run (sim/distribution.h) takes them
// before its objects are shared out, since each rank then holds only part of the elements and
// masses; it passes them to write_checkpoint and restore_checkpoint below.
std::vector<ObjectFingerprint> scene_fingerprints(const Simulation<double>& simulation);

// Writes `simulation`'s state to `path` atomically (atomic_file.h). `scene_name` is recorded so
// that a refused checkpoint can say which scene it belongs to. `fingerprints`, when given, are
// recorded in place of those of `simulation` as it is now (a distributed run's rank 0, whose state
// was gathered from every rank).
void write_checkpoint(const std::filesystem::path& path, const Simulation<double>& simulation,
                      const std::string& scene_name,
                      const std::vector<ObjectFingerprint>* fingerprints = nullptr);

// Reads `path` and restores it into `simulation`, freshly built from the same scene: positions,
// velocities, solver states and the step counter. Refuses, with a fastcorot::Error naming the file
// and what is wrong, a file that is not a checkpoint, of another format version, truncated or
// corrupt (checksum), or made for another scene (object paths, vertex or tetrahedron counts, rest
// positions, elements, model) or another dt. The scene's scripted topological changes up to the
// checkpoint's step are replayed first (the meshes and masses they leave are part of what is
// checked); nothing else is changed unless everything checks. `fingerprints`, when given, are
// checked in place of those of `simulation` (a distributed run, which has no topological changes:
// they would be refused before).
void restore_checkpoint(const std::filesystem::path& path, Simulation<double>& simulation,
                        const std::vector<ObjectFingerprint>* fingerprints = nullptr);

// FNV-1a 64 of `size` bytes, continuing from `hash` (the checksum and fingerprints above).
std::uint64_t fnv1a64(const void* data, std::size_t size,
                      std::uint64_t hash = 14695981039346656037ull);

}  // namespace fastcorot
