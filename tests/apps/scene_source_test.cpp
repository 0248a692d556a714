// Scenes from scripts, as the command line sees them (scene_source.h), with a loader written here in
// place of the Python module's: run calls the controllers around every step (begin before the
// step, end after it), --resume is refused when the script has controllers, and a .py scene
// without a loader, or given to a command that takes files, is one clear error.
#include "scene_source.h"

#include "run_command.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_graph.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

namespace fastcorot::cli {
namespace {

const char* kScene = R"(<Node name="root" dt="0.01"><Node name="body"><EulerImplicitSolver/><EigenSimplicialLDLT/>
  <MechanicalObject position="0 0 0 1 0 0 0 1 0 0 0 1"/><TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass totalMass="1"/><TetrahedronFEMForceField youngModulus="100"/><FixedProjectiveConstraint indices="0"/>
  </Node></Node>)";

// What a script's controllers would see: the step count at each call, and the keys.
struct Calls {
  std::vector<std::string> events;
};

class RecordingSource final : public SceneSource {
 public:
  RecordingSource(Calls& calls, bool controllers) : calls_(calls), controllers_(controllers), scene_(build()) {}
  LoadedScene& scene() override { return scene_; }
  LoadedScene& reload() override {
    calls_.events.push_back("reload");
    scene_ = build();
    return scene_;
  }
  void begin_step() override { calls_.events.push_back("begin " + std::to_string(scene_.simulation.steps_done())); }
  void end_step() override { calls_.events.push_back("end " + std::to_string(scene_.simulation.steps_done())); }
  void key_pressed(char key) override { calls_.events.push_back(std::string("key ") + key); }
  bool has_controllers() const override { return controllers_; }

 private:
  static LoadedScene build() { return build_scene(parse_scene_text(kScene, "script.py")); }
  Calls& calls_;
  bool controllers_;
  LoadedScene scene_;
};

class ScriptScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    set_script_loader([this](const std::string& script, bool) -> std::unique_ptr<SceneSource> {
      calls.events.push_back("load " + std::filesystem::path(script).filename().string());
      return std::make_unique<RecordingSource>(calls, controllers);
    });
  }
  void TearDown() override { set_script_loader(nullptr); }

  Calls calls;
  bool controllers = true;
};

TEST_F(ScriptScenes, RunCallsTheControllersAroundEveryStep) {
  RunOptions options;
  options.scene = "script.py";
  options.steps = 2;
  options.quiet = true;
  std::ostringstream out, err;
  run(options, out, err);
  EXPECT_EQ(calls.events, (std::vector<std::string>{"load script.py", "begin 0", "end 1", "begin 1", "end 2"}));
}

TEST_F(ScriptScenes, ResumeIsRefusedWithControllers) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "script_resume";
  std::filesystem::create_directories(dir);
  RunOptions options;
  options.scene = "script.py";
  options.steps = 2;
  options.quiet = true;
  options.checkpoint_every = 1;
  options.checkpoint_file = (dir / "c.ckpt").string();
  std::ostringstream out, err;
  run(options, out, err);
  options.resume = options.checkpoint_file;
  options.steps = 3;
  try {
    run(options, out, err);
    FAIL() << "resumed";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("has Python controllers"), std::string::npos) << error.what();
  }
  controllers = false;  // without controllers the checkpoint is the whole state
  run(options, out, err);
}

TEST(ScriptScenesWithoutPython, AreOneClearError) {
  EXPECT_TRUE(is_script("a/b/liver.py"));
  EXPECT_TRUE(is_script("LIVER.PY"));
  EXPECT_FALSE(is_script("liver.scn"));
  try {
    open_scene("liver.py", false);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("a Python script runs through the Python module"), std::string::npos);
  }
  try {
    load_scene_argument("liver.py");
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("this command takes scene and mesh files"), std::string::npos);
  }
}

}  // namespace
}  // namespace fastcorot::cli
