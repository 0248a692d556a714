#include "fastcorot/io/checkpoint.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/io/atomic_file.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string_view>
#include <typeinfo>
#include <vector>

namespace fastcorot {

namespace {

constexpr std::string_view kMagic = "FCOROTCK";
constexpr std::size_t kHeaderSize = 24;  // magic, version, bytes per real, file size
constexpr std::size_t kChecksumSize = 8;

class ByteWriter {
 public:
  void u32(std::uint32_t value) { little_endian(value, 4); }
  void u64(std::uint64_t value) { little_endian(value, 8); }
  void i64(std::int64_t value) { u64(static_cast<std::uint64_t>(value)); }
  void f64(double value) { u64(std::bit_cast<std::uint64_t>(value)); }
  void string(std::string_view text) {
    u32(static_cast<std::uint32_t>(text.size()));
    bytes.append(text);
  }
  void points(const std::vector<Vec3<double>>& points) {
    for (const auto& p : points) {
      for (int c = 0; c < 3; ++c) f64(p[c]);
    }
  }
  void integers(const std::vector<std::int64_t>& values) {
    u32(static_cast<std::uint32_t>(values.size()));
    for (const std::int64_t v : values) i64(v);
  }
  std::string bytes;

 private:
  void little_endian(std::uint64_t value, int count) {
    for (int i = 0; i < count; ++i) bytes.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
  }
};

// Reads what ByteWriter wrote; every read is bounds-checked against the payload's end.
class ByteReader {
 public:
  ByteReader(const std::string& bytes, std::size_t begin, std::size_t end, std::string file)
      : bytes_(bytes), at_(begin), end_(end), file_(std::move(file)) {}
  std::uint64_t unsigned_value(int count, const char* what) {
    need(static_cast<std::size_t>(count), what);
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i)
      value |= std::uint64_t(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    at_ += static_cast<std::size_t>(count);
    return value;
  }
  std::uint32_t u32(const char* what) {
    return static_cast<std::uint32_t>(unsigned_value(4, what));
  }
  std::uint64_t u64(const char* what) { return unsigned_value(8, what); }
  std::int64_t i64(const char* what) { return static_cast<std::int64_t>(u64(what)); }
  double f64(const char* what) { return std::bit_cast<double>(u64(what)); }
  std::string string(const char* what) {
    const std::size_t size = u32(what);
    need(size, what);
    std::string text = bytes_.substr(at_, size);
    at_ += size;
    return text;
  }
  std::vector<Vec3<double>> points(std::size_t count, const char* what) {
    if (count > (end_ - at_) / 24) need(end_ - at_ + 1, what);
    std::vector<Vec3<double>> points(count);
    for (auto& p : points) {
      for (int c = 0; c < 3; ++c) p[c] = f64(what);
    }
    return points;
  }
  std::vector<std::int64_t> integers(const char* what) {
    const std::size_t count = u32(what);
    if (count > (end_ - at_) / 8) need(end_ - at_ + 1, what);
    std::vector<std::int64_t> values(count);
    for (auto& v : values) v = i64(what);
    return values;
  }
  bool at_end() const { return at_ == end_; }

 private:
  void need(std::size_t count, const char* what) const {
    if (count > end_ - at_) {
      throw make_error(file_, ": malformed checkpoint: ", what,
                       " runs past the end of the data at byte ", at_);
    }
  }
  const std::string& bytes_;
  std::size_t at_, end_;
  std::string file_;
};

template <class T>
std::uint64_t hash_values(const std::vector<T>& values, std::uint64_t hash) {
  ByteWriter bytes;
  for (const T& v : values) {
    if constexpr (std::is_floating_point_v<T>) {
      bytes.f64(static_cast<double>(v));
    } else {
      bytes.i64(static_cast<std::int64_t>(v));
    }
  }
  return fnv1a64(bytes.bytes.data(), bytes.bytes.size(), hash);
}

std::uint64_t hash_points(const std::vector<Vec3<double>>& points) {
  ByteWriter bytes;
  bytes.points(points);
  return fnv1a64(bytes.bytes.data(), bytes.bytes.size());
}

std::uint64_t hash_text(std::string_view text, std::uint64_t hash) {
  return fnv1a64(text.data(), text.size(), hash ^ text.size());
}

ObjectFingerprint fingerprint(const SimulatedObject<double>& object) {
  const MechanicalSystem<double>& system = object.system;
  ObjectFingerprint print;
  print.vertices = static_cast<std::uint64_t>(system.size());
  print.rest = hash_points(system.state.rest_position);
  std::vector<Index> tetrahedra;
  if (object.mesh) {
    for (const auto& t : object.mesh->tetrahedra())
      tetrahedra.insert(tetrahedra.end(), t.begin(), t.end());
  }
  print.tetrahedra = tetrahedra.size() / 4;
  print.elements = hash_values(tetrahedra, fnv1a64(nullptr, 0));
  std::uint64_t model = fnv1a64(nullptr, 0);
  model = hash_values(
      std::vector<double>(system.mass.vertex_masses().begin(), system.mass.vertex_masses().end()),
      model);
  model = hash_values(std::vector<int>{system.mass.is_lumped() ? 1 : 0}, model);
  model = hash_values(system.fixed, model);
  model = hash_values(system.zero_velocity, model);
  for (const auto& constant : system.constant_forces) {
    model = hash_values(constant.indices, model);
    for (const auto& f : constant.forces)
      model = hash_values(std::vector<double>{f.x(), f.y(), f.z()}, model);
  }
  model = hash_values(
      std::vector<double>{system.gravity.x(), system.gravity.y(), system.gravity.z()}, model);
  for (const auto& field : system.force_fields) {
    if (const auto* corotational = dynamic_cast<const CorotationalForceField<double>*>(field.get())) {
      // Hashed as format version 1 always hashed it, so that earlier checkpoints still resume.
      const auto& p = corotational->parameters();
      model = hash_values(p.young_modulus, model);
      model = hash_values(p.poisson_ratio, model);
      model = hash_values(std::vector<double>{static_cast<double>(p.method), p.rayleigh_stiffness},
                          model);
    } else {
      model = hash_text(field->component(), model);
      model = hash_values(field->model_values(), model);
    }
  }
  model = hash_text(object.ode_solver ? typeid(*object.ode_solver).name() : "-", model);
  model = hash_text(object.linear_solver ? typeid(*object.linear_solver).name() : "-", model);
  print.model = model;
  return print;
}

struct SavedObject {
  std::string path;
  ObjectFingerprint print;
  std::vector<Vec3<double>> position, velocity;
  std::vector<std::int64_t> ode_state, linear_state;
  std::vector<Eigen::Quaterniond> orientation;  // version 2: the rigids'
};

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error(path.string(), ": cannot open the checkpoint: ", std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw make_error(path.string(), ": cannot read the checkpoint");
  return bytes;
}

std::uint64_t read_u64_at(const std::string& bytes, std::size_t at) {
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i)
    value |= std::uint64_t(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
  return value;
}

// Checks the frame of the file (magic, version, size, checksum) in the order that gives the most
// useful message: a file of another kind or version is named as such before any talk of damage.
std::uint32_t check_frame(const std::string& bytes, const std::string& file) {
  if (bytes.size() < kMagic.size() || std::string_view(bytes).substr(0, kMagic.size()) != kMagic) {
    if (bytes.size() < kMagic.size() && kMagic.substr(0, bytes.size()) == bytes) {
      throw make_error(file, ": truncated checkpoint: only ", bytes.size(), " bytes");
    }
    throw make_error(file, ": not a fastcorot checkpoint (it does not begin with \"", kMagic,
                     "\")");
  }
  if (bytes.size() < kHeaderSize)
    throw make_error(file, ": truncated checkpoint: only ", bytes.size(), " bytes");
  ByteReader header(bytes, kMagic.size(), kHeaderSize, file);
  const std::uint32_t version = header.u32("the format version");
  if (version != kCheckpointVersion && version != 1) {
    throw make_error(file, ": checkpoint format version ", version,
                     "; this fastcorot reads versions 1 and ", kCheckpointVersion, " only");
  }
  const std::uint32_t real_size = header.u32("the real size");
  if (real_size != sizeof(double)) {
    throw make_error(file, ": the checkpoint stores ", real_size, "-byte reals; this run uses ",
                     sizeof(double));
  }
  const std::uint64_t size = header.u64("the file size");
  if (size != bytes.size()) {
    throw make_error(file, ": ", size > bytes.size() ? "truncated" : "damaged",
                     " checkpoint: its header says ", size, " bytes, the file has ", bytes.size());
  }
  if (size < kHeaderSize + kChecksumSize)
    throw make_error(file, ": damaged checkpoint: impossible size ", size);
  const std::uint64_t stored = read_u64_at(bytes, bytes.size() - kChecksumSize);
  const std::uint64_t computed = fnv1a64(bytes.data(), bytes.size() - kChecksumSize);
  if (stored != computed) {
    throw make_error(
        file, ": corrupt checkpoint: the checksum of its content does not match the one stored (",
        "the file was changed or damaged after it was written)");
  }
  return version;
}

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t hash) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

ObjectFingerprint object_fingerprint(const SimulatedObject<double>& object) { return fingerprint(object); }

std::vector<ObjectFingerprint> scene_fingerprints(const Simulation<double>& simulation) {
  std::vector<ObjectFingerprint> prints;
  for (const auto& object : simulation.objects) prints.push_back(fingerprint(object));
  return prints;
}

void write_checkpoint(const std::filesystem::path& path, const Simulation<double>& simulation,
                      const std::string& scene_name, const std::vector<ObjectFingerprint>* fingerprints) {
  const std::vector<ObjectFingerprint> prints = fingerprints ? *fingerprints : scene_fingerprints(simulation);
  if (prints.size() != simulation.objects.size()) {
    throw make_error(path.string(), ": not written: ", prints.size(), " fingerprints for ", simulation.objects.size(),
                     " objects");
  }
  if (simulation.constraints) {
    // The constraints' warm starts (the last impulses) and what scripts changed in them are not
    // saved: a resumed run would not continue bitwise.
    throw make_error(path.string(), ": not written: the scene's Lagrangian constraints (FreeMotionAnimationLoop) carry "
                     "their last impulses from step to step, which checkpoints do not save");
  }
  for (const auto& object : simulation.objects) {
    for (const auto& field : object.system.force_fields) {
      if (const std::string unsaved = field->unsaved_state(); !unsaved.empty()) {
        throw make_error(path.string(), ": not written: ", object.path, "'s ", field->component(), " carries ", unsaved,
                         ", which checkpoints do not save");
      }
    }
  }
  ByteWriter out;
  out.bytes.append(kMagic);
  out.u32(kCheckpointVersion);
  out.u32(sizeof(double));
  out.u64(0);  // the file size, filled in below
  out.string(scene_name);
  out.f64(simulation.dt);
  out.i64(simulation.steps_done());
  out.u32(static_cast<std::uint32_t>(simulation.objects.size()));
  for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
    const SimulatedObject<double>& object = simulation.objects[o];
    const ObjectFingerprint& print = prints[o];
    out.string(object.path);
    out.u64(print.vertices);
    out.u64(print.tetrahedra);
    out.u64(print.rest);
    out.u64(print.elements);
    out.u64(print.model);
    out.points(object.system.state.position);
    out.points(object.system.state.velocity);
    out.integers(object.ode_solver ? object.ode_solver->carried_state()
                                   : std::vector<std::int64_t>{});
    out.integers(object.linear_solver ? object.linear_solver->carried_state()
                                      : std::vector<std::int64_t>{});
    // Version 2: the rigid bodies' orientations (x y z w each; none for a deformable object).
    const auto& rigids = object.system.rigids;
    out.u64(rigids ? rigids->size() : 0);
    if (rigids) {
      for (const auto& q : rigids->orientation) {
        for (int c = 0; c < 4; ++c) out.f64(q.coeffs()[c]);
      }
    }
  }
  const std::uint64_t size = out.bytes.size() + kChecksumSize;
  for (int i = 0; i < 8; ++i)
    out.bytes[16 + static_cast<std::size_t>(i)] = static_cast<char>((size >> (8 * i)) & 0xff);
  out.u64(fnv1a64(out.bytes.data(), out.bytes.size()));
  write_stream_atomically(path, [&](std::ostream& stream) {
    stream.write(out.bytes.data(), static_cast<std::streamsize>(out.bytes.size()));
  });
}

void restore_checkpoint(const std::filesystem::path& path, Simulation<double>& simulation,
                        const std::vector<ObjectFingerprint>* fingerprints) {
  const std::string file = path.string();
  const std::string bytes = read_whole_file(path);
  const std::uint32_t version = check_frame(bytes, file);
  ByteReader in(bytes, kHeaderSize, bytes.size() - kChecksumSize, file);
  const std::string scene_name = in.string("the scene name");
  const std::string made_for = "the checkpoint was written for scene \"" + scene_name + "\"";
  const double dt = in.f64("dt");
  const std::int64_t step = in.i64("the step");
  if (step < 0) throw make_error(file, ": malformed checkpoint: step ", step);
  const std::size_t count = in.u32("the object count");
  if (count != simulation.objects.size()) {
    throw make_error(file, ": ", made_for, ", which has ", count, " object(s); this scene has ",
                     simulation.objects.size());
  }
  std::vector<SavedObject> saved(count);
  for (std::size_t o = 0; o < count; ++o) {
    SavedObject& s = saved[o];
    s.path = in.string("an object path");
    s.print.vertices = in.u64("a vertex count");
    s.print.tetrahedra = in.u64("a tetrahedron count");
    s.print.rest = in.u64("a fingerprint");
    s.print.elements = in.u64("a fingerprint");
    s.print.model = in.u64("a fingerprint");
    s.position = in.points(s.print.vertices, "the positions");
    s.velocity = in.points(s.print.vertices, "the velocities");
    s.ode_state = in.integers("the ODE solver state");
    s.linear_state = in.integers("the linear solver state");
    if (version >= 2) {
      const std::uint64_t rigids = in.u64("the rigid count");
      if (rigids > s.print.vertices) throw make_error(file, ": malformed checkpoint: ", rigids, " rigids in ", s.print.vertices, " blocks");
      for (std::uint64_t k = 0; k < rigids; ++k) {
        Eigen::Quaterniond q;
        for (int c = 0; c < 4; ++c) q.coeffs()[c] = in.f64("an orientation");
        s.orientation.push_back(q);
      }
    }
  }
  if (!in.at_end())
    throw make_error(file, ": malformed checkpoint: extra bytes after the last object");

  if (std::bit_cast<std::uint64_t>(dt) != std::bit_cast<std::uint64_t>(simulation.dt)) {
    throw make_error(file, ": ", made_for, " with dt = ", dt, "; this run has dt = ", simulation.dt,
                     " (a resumed run must keep the time step)");
  }
  // Scripted cuts of the steps before the checkpoint, so that the meshes, masses and force fields
  // are those the checkpoint's state belongs to.
  simulation.replay_topology_changes(static_cast<long>(step));
  const std::vector<ObjectFingerprint> prints = fingerprints ? *fingerprints : scene_fingerprints(simulation);
  if (prints.size() != count) {
    throw make_error(file, ": ", prints.size(), " fingerprints given for ", count, " objects");
  }

  // The scene must be the one the checkpoint was made for.
  for (std::size_t o = 0; o < count; ++o) {
    const SavedObject& s = saved[o];
    const SimulatedObject<double>& object = simulation.objects[o];
    const ObjectFingerprint& print = prints[o];
    const std::string where = file + ": " + made_for + ": object " + std::to_string(o) + " ";
    if (s.path != object.path)
      throw make_error(where, "is \"", s.path, "\"; in this scene it is \"", object.path, "\"");
    if (s.print.vertices != print.vertices) {
      throw make_error(where, s.path, " has ", s.print.vertices, " vertices; in this scene it has ",
                       print.vertices);
    }
    if (s.print.tetrahedra != print.tetrahedra) {
      throw make_error(where, s.path, " has ", s.print.tetrahedra,
                       " tetrahedra; in this scene it has ", print.tetrahedra);
    }
    if (s.print.rest != print.rest) throw make_error(where, s.path, " had other rest positions");
    if (s.print.elements != print.elements)
      throw make_error(where, s.path, " had other tetrahedra (same count)");
    if (s.print.model != print.model) {
      throw make_error(where, s.path,
                       " had another model (masses, fixed points, constant forces, gravity, ",
                       "force-field parameters or kinds of solver differ)");
    }
    const std::size_t rigids = object.system.rigids ? object.system.rigids->size() : 0;
    if (s.orientation.size() != rigids) {
      throw make_error(where, s.path, " has ", s.orientation.size(), " rigid orientations; in this scene it has ", rigids, " rigids",
                       version == 1 ? " (a version-1 checkpoint holds none)" : "");
    }
    const std::size_t ode_size = object.ode_solver ? object.ode_solver->carried_state().size() : 0;
    if (s.ode_state.size() != ode_size) {
      throw make_error(where, s.path, ": its ODE solver state has ", s.ode_state.size(),
                       " values; this scene's ODE solver carries ", ode_size);
    }
    try {
      if (object.linear_solver) {
        object.linear_solver->check_carried_state(s.linear_state);
      } else if (!s.linear_state.empty()) {
        throw make_error("this scene's object has no linear solver");
      }
    } catch (const Error& error) {
      throw make_error(where, s.path, ": its linear solver state does not fit this scene's: ",
                       error.what());
    }
  }

  for (std::size_t o = 0; o < count; ++o) {
    SimulatedObject<double>& object = simulation.objects[o];
    if (object.ode_solver) object.ode_solver->restore_carried_state(saved[o].ode_state);
    if (object.linear_solver) object.linear_solver->restore_carried_state(saved[o].linear_state);
    object.system.state.position = std::move(saved[o].position);
    object.system.state.velocity = std::move(saved[o].velocity);
    if (auto& rigids = object.system.rigids) {
      rigids->orientation = saved[o].orientation;
      rigids->rebase(object.system.state.position);  // passes them on to the followers
    }
  }
  simulation.set_steps_done(static_cast<long>(step));
}

}  // namespace fastcorot
