#include "run_command.h"

#include "contact_figures.h"
#include "default_scene.h"
#include "distributed_run.h"
#include "thread_count.h"
#include "json_io.h"
#include "picture_series.h"
#include "scene_source.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/render/drawing_vtu.h"
#include "fastcorot/io/checkpoint.h"
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/io/obj_writer.h"
#include "fastcorot/io/vtu_writer.h"
#include "fastcorot/topology/tetrahedron_faces.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/petsc_runtime.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>

namespace fastcorot::cli {

std::set<long> parse_step_list(const std::string& text) {
  std::set<long> steps;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    char* end = nullptr;
    const long step = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || step < 0) {
      throw make_error("--dump-steps \"", text, "\": expected a comma-separated list of step numbers >= 0");
    }
    steps.insert(step);
  }
  return steps;
}

std::string mesh_scene_text(const std::string& mesh_path) {
  const MeshData mesh = read_mesh_file(mesh_path);
  if (mesh.points.empty()) throw make_error(mesh_path, ": the mesh has no points");
  Vec3<double> lo = mesh.points.front(), hi = mesh.points.front();
  for (const auto& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = (hi - lo).maxCoeff();
  const double tolerance = 1e-6 * extent;
  const std::string extension = std::filesystem::path(mesh_path).extension().string();
  const std::string loader = extension == ".msh" ? "MeshGmshLoader" : "MeshVTKLoader";
  std::ostringstream scene;
  scene.precision(17);
  scene << "<Node name=\"root\" dt=\"0.01\" gravity=\"0 0 -9.81\">\n"
        << "  <Node name=\"" << std::filesystem::path(mesh_path).stem().string() << "\">\n"
        << "    <EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/>\n"
        << "    <EigenSimplicialLDLT/>\n"
        << "    <" << loader << " name=\"loader\" filename=\"" << std::filesystem::absolute(mesh_path).string() << "\"/>\n"
        << "    <TetrahedronSetTopologyContainer name=\"topology\" src=\"@loader\"/>\n"
        << "    <MechanicalObject name=\"state\"/>\n"
        << "    <DiagonalMass massDensity=\"1000\"/>\n"
        << "    <FastTetrahedralCorotationalForceField youngModulus=\"100000\" poissonRatio=\"0.3\" method=\"large\"/>\n"
        << "    <BoxROI name=\"bottom\" box=\"" << lo.x() - tolerance << " " << lo.y() - tolerance << " "
        << lo.z() - tolerance << " " << hi.x() + tolerance << " " << hi.y() + tolerance << " " << lo.z() + tolerance
        << "\"/>\n"
        << "    <FixedProjectiveConstraint indices=\"@bottom.indices\"/>\n"
        << "  </Node>\n</Node>\n";
  return scene.str();
}

LoadedScene load_scene_argument(const std::string& scene, bool strict) {
  if (is_script(scene)) {
    throw make_error(scene, ": a Python script: `fastcorot run` and `fastcorot view` run scripts; this command takes "
                     "scene and mesh files");
  }
  const SceneOptions options{strict};
  if (scene.empty()) return build_scene(parse_scene_text(kDefaultScene, "<built-in cantilever beam>"), options);
  std::string extension = std::filesystem::path(scene).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".msh" || extension == ".vtk" || extension == ".vtu") {
    return build_scene(parse_scene_text(mesh_scene_text(scene), scene + " (default mesh scene)"), options);
  }
  return load_scene_file(scene, options);
}

void make_output_folder(const std::string& dir, const std::string& option) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw make_error(option, " ", dir, ": cannot create the folder: ", error.message());
  if (!std::filesystem::is_directory(dir)) throw make_error(option, " ", dir, ": not a folder");
  if (access(dir.c_str(), W_OK) != 0) throw make_error(option, " ", dir, ": the folder is not writable");
}

namespace {

std::string file_stem(const std::string& path) {
  std::string stem = path;
  std::replace(stem.begin(), stem.end(), '/', '_');
  return stem;
}

// TetrahedronFEMForceField's von Mises stress (computeVonMisesStress 1 or 2) of the object's mesh:
// per point and per tetrahedron, as SOFA's vonMisesPerNode and vonMisesPerElement.
void add_von_mises_fields(const SimulatedObject<double>& object, std::vector<VtuField>& point_fields,
                          std::vector<VtuField>& cell_fields) {
  for (const auto& field : object.system.force_fields) {
    const auto* fem = dynamic_cast<const TetrahedronFEMForceField<double>*>(field.get());
    if (!fem || !object.mesh || &fem->mesh() != object.mesh.get() || fem->von_mises_per_node().empty()) continue;
    const auto per_node = fem->von_mises_per_node();
    const auto per_element = fem->von_mises_per_element();
    point_fields.push_back({"vonMisesPerNode", 1, {per_node.begin(), per_node.end()}});
    cell_fields.push_back({"vonMisesPerElement", 1, {per_element.begin(), per_element.end()}});
    return;
  }
}

class VtuSeries {
 public:
  VtuSeries(const std::string& dir, const Simulation<double>& simulation, TetrahedronDrawing drawing)
      : dir_(dir), drawing_(drawing) {
    make_output_folder(dir_, "--out");
    for (const auto& object : simulation.objects) names_.push_back(file_stem(object.path));
    frames_.resize(simulation.objects.size());
    drawing_frames_.resize(simulation.objects.size());
    rigid_frames_.resize(simulation.objects.size());
    for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
      const auto& object = simulation.objects[o];
      surface_stems_.emplace_back();
      for (const VisualSurface& surface : object.visual_surfaces) {
        surface_stems_[o].push_back(names_[o] + "_" + file_stem(surface.path.substr(object.path.size() + 1)));
      }
      surface_frames_.emplace_back(object.visual_surfaces.size());
    }
  }

  // `forces`: each object's forces, when the caller has them (a distributed run gathers them);
  // computed here otherwise.
  void write(Simulation<double>& simulation, const std::vector<std::vector<Vec3<double>>>* forces = nullptr) {
    for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
      auto& object = simulation.objects[o];
      auto& system = object.system;
      const auto& x = system.state.position;
      const std::size_t n = x.size();
      std::vector<Vec3<double>> force(n, Vec3<double>::Zero());
      if (forces) force = (*forces)[o];
      else system.compute_force(x, force);
      VtuField displacement{"displacement", 3, {}}, velocity{"velocity", 3, {}}, force_field{"force", 3, {}};
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3<double> u = x[i] - system.state.rest_position[i];
        displacement.values.insert(displacement.values.end(), {u.x(), u.y(), u.z()});
        const Vec3<double>& v = system.state.velocity[i];
        velocity.values.insert(velocity.values.end(), {v.x(), v.y(), v.z()});
        force_field.values.insert(force_field.values.end(), {force[i].x(), force[i].y(), force[i].z()});
      }
      std::vector<VtuCellBlock> cells;
      if (object.mesh) cells.push_back(tetrahedron_cells(object.mesh->tetrahedra()));
      std::vector<VtuField> point_fields{displacement, velocity, force_field}, cell_fields;
      add_von_mises_fields(object, point_fields, cell_fields);
      const std::string file = names_[o] + "_" + std::to_string(simulation.steps_done()) + ".vtu";
      write_vtu(std::filesystem::path(dir_) / file, x, cells, point_fields, cell_fields);
      frames_[o].push_back({simulation.time(), file});
      write_pvd(std::filesystem::path(dir_) / (names_[o] + ".pvd"), frames_[o]);
      if (system.rigids) {
        // The rigid bodies' frames go to a series of their own (their angular blocks, in the file
        // above, are rotation offsets: zero between steps).
        const std::string frames_file = names_[o] + "_frames_" + std::to_string(simulation.steps_done()) + ".vtu";
        write_rigid_frames_vtu(std::filesystem::path(dir_) / frames_file, *system.rigids, x, system.state.velocity, force);
        rigid_frames_[o].push_back({simulation.time(), frames_file});
        write_pvd(std::filesystem::path(dir_) / (names_[o] + "_frames.pvd"), rigid_frames_[o]);
      }
      // Each visual surface (an OglModel mapped onto the object) goes to a series of its own.
      auto& surface_frames = surface_frames_[o];
      for (std::size_t s = 0; s < object.visual_surfaces.size(); ++s) {
        const VisualSurface& surface = object.visual_surfaces[s];
        const std::string& stem = surface_stems_[o][s];
        const std::string surface_file = stem + "_" + std::to_string(simulation.steps_done()) + ".vtu";
        VtuCellBlock triangles{5, 3, {}};
        for (const Triangle& t : surface.triangles) triangles.connectivity.insert(triangles.connectivity.end(), t.begin(), t.end());
        write_vtu(std::filesystem::path(dir_) / surface_file, surface.points(x), {triangles}, {});
        surface_frames[s].push_back({simulation.time(), surface_file});
        write_pvd(std::filesystem::path(dir_) / (stem + ".pvd"), surface_frames[s]);
      }
      // The drawn tetrahedra go to a series of their own: their points are not the mesh's.
      const DrawnTetrahedraGrid grid = drawn_tetrahedra_grid(object, drawing_);
      if (grid.empty()) continue;
      const std::string drawing_file = names_[o] + "_drawing_" + std::to_string(simulation.steps_done()) + ".vtu";
      write_drawn_tetrahedra_vtu(std::filesystem::path(dir_) / drawing_file, grid);
      drawing_frames_[o].push_back({simulation.time(), drawing_file});
      write_pvd(std::filesystem::path(dir_) / (names_[o] + "_drawing.pvd"), drawing_frames_[o]);
    }
  }

  // For a run resumed at `simulation`'s step: lists in the collections the frames an uninterrupted
  // run would have written up to that step (step 0 and every K-th) that are in the folder, so that
  // the .pvd files come out as an uninterrupted run writes them.
  void adopt_earlier_frames(const Simulation<double>& simulation, long every) {
    for (long step = 0; step <= simulation.steps_done(); step += every) {
      const double time = static_cast<double>(step) * simulation.dt;  // as Simulation::time()
      for (std::size_t o = 0; o < names_.size(); ++o) {
        const std::string file = names_[o] + "_" + std::to_string(step) + ".vtu";
        if (std::filesystem::exists(std::filesystem::path(dir_) / file))
          frames_[o].push_back({time, file});
        const std::string drawing_file = names_[o] + "_drawing_" + std::to_string(step) + ".vtu";
        if (std::filesystem::exists(std::filesystem::path(dir_) / drawing_file)) {
          drawing_frames_[o].push_back({time, drawing_file});
        }
        const std::string frames_file = names_[o] + "_frames_" + std::to_string(step) + ".vtu";
        if (std::filesystem::exists(std::filesystem::path(dir_) / frames_file)) rigid_frames_[o].push_back({time, frames_file});
        for (std::size_t s = 0; s < surface_stems_[o].size(); ++s) {
          const std::string surface_file = surface_stems_[o][s] + "_" + std::to_string(step) + ".vtu";
          if (std::filesystem::exists(std::filesystem::path(dir_) / surface_file)) {
            surface_frames_[o][s].push_back({time, surface_file});
          }
        }
      }
    }
  }

 private:
  std::string dir_;
  TetrahedronDrawing drawing_;
  std::vector<std::string> names_;
  std::vector<std::vector<std::pair<double, std::string>>> frames_;
  std::vector<std::vector<std::pair<double, std::string>>> drawing_frames_;
  std::vector<std::vector<std::pair<double, std::string>>> rigid_frames_;  // objects with rigid bodies
  // Per object and visual surface: the file stem and the frames written.
  std::vector<std::vector<std::string>> surface_stems_;
  std::vector<std::vector<std::vector<std::pair<double, std::string>>>> surface_frames_;
};

// The surfaces as OBJ files, one per frame: each visual surface (an OglModel mapped onto its
// object) as `<object>_<model>_<step>.obj`, and an object without one as its boundary triangles,
// `<object>_<step>.obj` (SOFA's VisualModelOBJExporter writes the visual models the same way).
class ObjSeries {
 public:
  ObjSeries(const std::string& dir, const Simulation<double>& simulation) : dir_(dir) {
    make_output_folder(dir_, "--out");
    for (const auto& object : simulation.objects) {
      const std::string name = file_stem(object.path);
      std::vector<std::string> stems;
      for (const VisualSurface& surface : object.visual_surfaces) {
        stems.push_back(name + "_" + file_stem(surface.path.substr(object.path.size() + 1)));
      }
      if (stems.empty()) stems.push_back(name);
      stems_.push_back(std::move(stems));
      boundaries_.push_back(object.visual_surfaces.empty() && object.mesh
                                ? boundary_triangles(object.mesh->tetrahedra())
                                : std::vector<Triangle>{});
    }
  }

  void write(const Simulation<double>& simulation) const {
    const std::string step = "_" + std::to_string(simulation.steps_done()) + ".obj";
    for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
      const auto& object = simulation.objects[o];
      const auto& x = object.system.state.position;
      for (std::size_t s = 0; s < object.visual_surfaces.size(); ++s) {
        const VisualSurface& surface = object.visual_surfaces[s];
        write_obj(std::filesystem::path(dir_) / (stems_[o][s] + step), surface.points(x), surface.triangles, surface.path);
      }
      if (object.visual_surfaces.empty()) {
        write_obj(std::filesystem::path(dir_) / (stems_[o][0] + step), x, boundaries_[o], object.path + " (boundary)");
      }
    }
  }

 private:
  std::string dir_;
  std::vector<std::vector<std::string>> stems_;
  std::vector<std::vector<Triangle>> boundaries_;
};

// The constraint stage's figures over a run: rows, solver iterations, the time in W and in the
// solve, and the steps whose solve ended at its iteration limit above its tolerance (the first
// such step is warned about as it happens; SOFA says nothing).
struct ConstraintTally {
  long rows = 0, iterations = 0, unconverged = 0, max_rows = 0;
  double compliance_seconds = 0, solve_seconds = 0, worst_error = 0;

  void add(const Simulation<double>& simulation, long step, std::ostream* warn) {
    const ConstraintReport& r = simulation.constraint_report();
    rows += r.rows;
    max_rows = std::max<long>(max_rows, r.rows);
    iterations += r.iterations;
    compliance_seconds += r.compliance_seconds;
    solve_seconds += r.solve_seconds;
    if (r.converged) return;
    if (unconverged++ == 0 && warn) {
      *warn << "warning: step " << step << ": " << simulation.constraints->solver_name() << " stopped at its iteration limit ("
            << r.iterations << ") with error " << r.error << " above its tolerance " << r.tolerance
            << " (the summary counts such steps)\n";
    }
    worst_error = std::max(worst_error, r.error);
  }

  void summarise(std::ostream& out, long steps, const char* solver) const {
    const double n = static_cast<double>(std::max<long>(steps, 1));
    out << "constraints: " << std::setprecision(1) << static_cast<double>(rows) / n << " rows per step (at most " << max_rows
        << "), " << solver << " " << static_cast<double>(iterations) / n << " iterations per step, W " << std::setprecision(3)
        << compliance_seconds << " s, solve " << solve_seconds << " s";
    if (unconverged > 0) {
      out << "; " << unconverged << " step(s) unconverged (largest error " << std::scientific << std::setprecision(2) << worst_error
          << std::fixed << ")";
    }
    out << '\n';
  }

  // As `bench --json` gives them, with the run's time `seconds`.
  json to_json(long steps, const char* solver, double seconds) const {
    const double n = static_cast<double>(std::max<long>(steps, 1));
    return {{"solver", solver},
            {"rows_per_step", static_cast<double>(rows) / n},
            {"max_rows", max_rows},
            {"iterations_per_step", static_cast<double>(iterations) / n},
            {"unconverged_steps", unconverged},
            {"largest_error", worst_error},
            {"compliance_share", seconds > 0 ? compliance_seconds / seconds : 0.0},
            {"solve_share", seconds > 0 ? solve_seconds / seconds : 0.0}};
  }
};

// A dumped step: `steps` the positions of each simulated object under its path (the first format,
// kept for the files written before velocities were dumped), `states` every MechanicalObject,
// mapped ones included, under "node path/object name" in scene order (docs/cli.md); under
// FreeMotionAnimationLoop, `impulses` the constraint impulses λ of the step (one per row); with a
// collision pipeline, `contacts` the step's contacts (null: none known, the step resumed from).
void record(json& steps, nlohmann::ordered_json& states, json& impulses, json* contacts,
            const Simulation<double>& simulation) {
  json frame = json::object();
  nlohmann::ordered_json all = nlohmann::ordered_json::object();
  for (const auto& object : simulation.objects) {
    frame[object.path] = points_to_json(object.system.state.position);
    for (const StateSnapshot& state : state_snapshots(object)) {
      all[state.key()] = {{"node", state.node},
                          {"object", state.name},
                          {"mapped", state.mapped},
                          {"position", state.rigid ? rows_to_json(state.rigid_position, 7) : points_to_json(state.position, state.coordinates)},
                          {"velocity", state.rigid ? rows_to_json(state.rigid_velocity, 6) : points_to_json(state.velocity, state.coordinates)}};
      if (state.rigid) all[state.key()]["template"] = "Rigid3d";
      if (state.coordinates == 1) all[state.key()]["template"] = "Vec1d";
    }
  }
  if (simulation.constraints) {
    const auto forces = simulation.constraints->constraint_forces();
    impulses[std::to_string(simulation.steps_done())] = std::vector<double>(forces.begin(), forces.end());
  }
  if (simulation.collisions && contacts) (*contacts)[std::to_string(simulation.steps_done())] = contacts_to_json(*simulation.collisions);
  steps[std::to_string(simulation.steps_done())] = std::move(frame);
  states[std::to_string(simulation.steps_done())] = std::move(all);
}

void progress(std::ostream& err, long done, long total, double seconds) {
  const int width = 30;
  const int filled = total > 0 ? static_cast<int>(width * done / total) : width;
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  const double remaining = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  err << "\r[" << std::string(static_cast<std::size_t>(filled), '#') << std::string(static_cast<std::size_t>(width - filled), ' ')
      << "] " << done << "/" << total << " steps  " << std::fixed << std::setprecision(1) << rate << " steps/s  "
      << remaining << " s left " << std::flush;
}

// A script's controller changed the scene's tree while it runs (Sofa/_script.py builds it again):
// the outputs set up per object at the start cannot follow another set of objects.
void refuse_rebuilt(SceneSource& source, const RunOptions& options) {
  if (!source.take_rebuilt()) return;
  if (options.vtu || options.obj || options.checkpoint_every > 0) {
    throw make_error(options.scene, ": a controller added or removed nodes while the scene runs; --vtu, --obj and "
                     "--checkpoint-every follow the objects the scene started with, so they cannot be used with it");
  }
}

}  // namespace

void run(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (options.steps < 0) throw make_error("--steps ", options.steps, ": must be >= 0");
  if (options.every < 1) throw make_error("--every ", options.every, ": must be >= 1");
  check_threads_option(options.threads);
  if (options.checkpoint_every < 0)
    throw make_error("--checkpoint-every ", options.checkpoint_every, ": must be >= 1");
  if (!(options.divergence_factor >= 0)) {
    throw make_error("--divergence-factor ", options.divergence_factor,
                     ": must be >= 0 (0: no bound)");
  }
  const TetrahedronDrawing drawing = parse_tetrahedron_drawing(options.picture.drawing);
  // With several ranks (mpirun), every rank loads the scene and steps its part; rank 0 writes.
  const bool writer = process_rank() == 0;
  if (process_count() > 1) {
    if (!options.png_dir.empty()) throw make_error("--png: not in a distributed run (write --vtu frames and draw them)");
  }
  std::unique_ptr<SceneSource> source;
  std::unique_ptr<DistributedRun> distributed;
  on_every_rank([&] {
    source = open_scene(options.scene, options.strict);
    distributed = std::make_unique<DistributedRun>(source->scene().simulation);
  });
  LoadedScene& scene = source->scene();
  Simulation<double>& simulation = scene.simulation;
  if (options.dt) {
    if (!(*options.dt > 0)) throw make_error("--dt ", *options.dt, ": must be > 0");
    simulation.dt = *options.dt;
  }
  simulation.threads = threads_to_run(options.threads, process_count() > 1, simulated_points(simulation));
  simulation.divergence_factor = options.divergence_factor;
  const std::string checkpoint_file =
      options.checkpoint_file.empty()
          ? (std::filesystem::path(options.out_dir) / "checkpoint.ckpt").string()
          : options.checkpoint_file;
  if (options.checkpoint_every > 0) {
    const auto folder = std::filesystem::path(checkpoint_file).parent_path();
    if (!folder.empty()) make_output_folder(folder.string(), "--checkpoint");
  }
  // Warnings are printed even with --quiet: they name settings of the scene that are ignored.
  if (writer) {
    for (const auto& line : scene.warnings) err << "warning: " << line << '\n';
  }
  if (!options.quiet && writer) {
    for (const auto& line : scene.info) err << "info: " << line << '\n';
  }
  json steps = json::object();
  nlohmann::ordered_json states = nlohmann::ordered_json::object();
  json impulses = json::object();
  json contacts_dumped = json::object();
  auto write_dump = [&] {
    if (options.dump_state.empty()) return;
    nlohmann::ordered_json dump = {{"dt", simulation.dt}, {"steps", steps}, {"states", states}};
    if (simulation.constraints) dump["constraintForces"] = impulses;
    if (simulation.collisions) dump["contacts"] = contacts_dumped;
    write_text(dump.dump(), options.dump_state);
  };
  // Outputs are set up on the scene as built (the pictures' camera is framed on it), also when
  // resuming, so that a resumed run writes what the uninterrupted one would have.
  std::optional<VtuSeries> vtu;
  std::optional<ObjSeries> obj;
  on_every_rank([&] {
    if (options.vtu && writer) vtu.emplace(options.out_dir, simulation, drawing);
    if (options.obj && writer) obj.emplace(options.out_dir, simulation);
  });
  std::optional<PictureSeries> pictures;
  if (!options.png_dir.empty()) pictures.emplace(options.png_dir, options.picture, simulation, options.steps);
  const bool dump_last = !options.dump_state.empty();
  if (!options.resume.empty()) {
    if (source->has_controllers()) {
      throw make_error("--resume ", options.resume, ": ", options.scene, " has Python controllers, whose own state "
                       "a checkpoint does not hold: a resumed run could differ; run it from the start");
    }
    // Every rank reads the checkpoint (on a cluster it must be on a folder every node sees).
    on_every_rank([&] { restore_checkpoint(options.resume, simulation, distributed->fingerprints()); });
    if (simulation.steps_done() > options.steps) {
      throw make_error("--resume ", options.resume, ": the checkpoint is at step ",
                       simulation.steps_done(), ", past --steps ", options.steps,
                       " (--steps is the last step number, not a count)");
    }
    if (vtu) vtu->adopt_earlier_frames(simulation, options.every);
    if (options.dump_steps.count(simulation.steps_done()) ||
        (dump_last && options.steps == simulation.steps_done())) {
      // No detection has run in this process: the step's contacts are not known (left out).
      record(steps, states, impulses, nullptr, simulation);
    }
  }
  // Frames and dumps of the step just done: a distributed run first gathers the state on rank 0
  // (collectively), then rank 0 writes.
  auto write_outputs = [&](bool dump, bool frame) {
    std::vector<std::vector<Vec3<double>>> forces;
    if (distributed->active() && (dump || frame)) {
      distributed->gather_state(simulation);
      if (options.vtu && frame) forces = distributed->gather_forces(simulation);
    }
    on_every_rank([&] {
      if (!writer) return;
      if (dump) record(steps, states, impulses, &contacts_dumped, simulation);
      if (vtu && frame) vtu->write(simulation, distributed->active() ? &forces : nullptr);
      if (obj && frame) obj->write(simulation);
      if (pictures && frame) pictures->write(simulation);
    });
  };
  if (options.resume.empty()) {
    write_outputs(options.dump_steps.count(0) || (dump_last && options.steps == 0),
                  options.vtu || options.obj || !options.png_dir.empty());
  }
  const long first_step = simulation.steps_done() + 1;

  const bool show_progress = !options.quiet && writer && isatty(fileno(stderr));
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  long solves = 0, iterations = 0;
  ConstraintTally constraints;
  ContactTally contacts;
  double last_draw = -1;
  try {
    for (long step = first_step; step <= options.steps; ++step) {
      StepReport report;
      on_every_rank([&] {
        source->begin_step();
        refuse_rebuilt(*source, options);
        report = simulation.step();
        source->end_step();
        refuse_rebuilt(*source, options);
      });
      solves += report.linear_solves;
      iterations += report.linear_iterations;
      if (simulation.constraints) constraints.add(simulation, step, writer && !options.quiet ? &err : nullptr);
      if (simulation.collisions) {
        const std::string crossing = contacts.add(simulation.collision_report());
        if (!crossing.empty() && writer) err << "warning: " << crossing << '\n';
      }
      const bool frame = (options.vtu || options.obj || !options.png_dir.empty()) &&
                         (step % options.every == 0 || step == options.steps);
      write_outputs(options.dump_steps.count(step) || (dump_last && step == options.steps), frame);
      // After the frames, so that a run resumed here finds them in the folder.
      if (options.checkpoint_every > 0 && step % options.checkpoint_every == 0) {
        if (distributed->active()) distributed->gather_state(simulation);
        on_every_rank([&] {
          if (!writer) return;
          write_checkpoint(checkpoint_file, simulation,
                           options.scene.empty() ? "<built-in cantilever beam>" : options.scene,
                           distributed->fingerprints());
        });
      }
      if (show_progress && (elapsed() - last_draw > 0.1 || step == options.steps)) {
        last_draw = elapsed();
        progress(err, step - first_step + 1, options.steps - first_step + 1, last_draw);
      }
    }
  } catch (const Error&) {
    if (show_progress) err << '\n';
    if (writer) write_dump();  // keep what was computed before the failure
    throw;
  }
  if (show_progress) err << '\n';
  on_every_rank([&] {
    if (writer) write_dump();
  });
  const double seconds = elapsed();
  const long steps_run = options.steps - first_step + 1;
  if (options.json && writer) {
    json summary = {{"steps", steps_run},
                    {"seconds", seconds},
                    {"steps_per_second", seconds > 0 ? static_cast<double>(steps_run) / seconds : 0.0},
                    {"objects", simulation.objects.size()},
                    {"linear_solves", solves},
                    {"linear_iterations_per_solve", solves > 0 ? static_cast<double>(iterations) / static_cast<double>(solves) : 0.0},
                    {"ranks", process_count()}};
    if (simulation.constraints) summary["constraints"] = constraints.to_json(steps_run, simulation.constraints->solver_name(), seconds);
    if (simulation.collisions) summary["contacts"] = contacts.to_json(seconds);
    out << summary.dump(2) << '\n';
  } else if (!options.quiet && writer) {
    out << "fastcorot run: " << steps_run << " steps in " << std::fixed << std::setprecision(3)
        << seconds << " s (" << std::setprecision(1)
        << (seconds > 0 ? static_cast<double>(steps_run) / seconds : 0.0) << " steps/s), "
        << simulation.objects.size() << " object(s), " << solves << " linear solves";
    if (iterations > 0) {
      out << ", mean linear-solver iterations " << std::setprecision(2)
          << static_cast<double>(iterations) / static_cast<double>(solves);
    }
    if (distributed->active()) out << ", " << process_count() << " ranks";
    out << '\n';
    if (simulation.constraints) constraints.summarise(out, steps_run, simulation.constraints->solver_name());
    if (simulation.collisions) contacts.summarise(out);
  }
}

}  // namespace fastcorot::cli
