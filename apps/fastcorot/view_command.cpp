#include "view_command.h"

#include "viewer_panel.h"
#include "viewer_session.h"

#include "fastcorot/core/error.h"
#include "fastcorot/render/gl_renderer.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>

namespace fastcorot::cli {

namespace {

// GLFW reports errors through a C callback; keep the last message for ours.
std::string& last_glfw_error() {
  static std::string message;
  return message;
}

void record_glfw_error(int, const char* description) {
  last_glfw_error() = description ? description : "unknown";
}

// Owns GLFW and ImGui in the order they must be torn down.
struct Window {
  GLFWwindow* handle = nullptr;
  bool imgui = false;

  Window(int width, int height, const std::string& title) {
    glfwSetErrorCallback(record_glfw_error);
    if (!glfwInit()) {
      throw make_error(
          "view: cannot start GLFW: ", last_glfw_error(),
          " (no display? run it under xvfb-run, or make pictures with fastcorot run --png)");
    }
    glfwWindowHint(GLFW_SAMPLES, 4);  // a request: servers without multisampling give less
    handle = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!handle) {
      glfwTerminate();
      throw make_error("view: cannot open a ", width, "x", height,
                       " OpenGL window: ", last_glfw_error());
    }
    glfwMakeContextCurrent(handle);
  }

  void start_imgui() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // leave no imgui.ini behind in the user's folder
    ImGui::StyleColorsDark();
    // Installs ImGui's callbacks, which call the ones set before (ours) afterwards.
    ImGui_ImplGlfw_InitForOpenGL(handle, true);
    ImGui_ImplOpenGL3_Init("#version 120");
    imgui = true;
  }

  ~Window() {
    if (imgui) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

GlProc glfw_loader(const char* name) {
  return glfwGetProcAddress(name);
}

// Mouse and keyboard state, reached from GLFW's callbacks through the window's user pointer.
struct Controls {
  ViewerSession* session = nullptr;
  Camera* camera = nullptr;
  bool reframe = false;
  bool orbiting = false, panning = false, cutting = false;
  double x = 0, y = 0;
};

// Cuts under the cursor at window position (x, y). Cursor positions are in window coordinates,
// which on high-density displays differ from framebuffer pixels; the camera only needs the aspect
// ratio, so the window's size is the picture the pixel belongs to.
void cut_under(GLFWwindow* window, Controls& c, double x, double y) {
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  c.session->cut_at(*c.camera, width, height, {x, y});
}

// A drag reports the cursor every few pixels or farther apart when fast: cut along the segment
// from the last position so that the cut has no gaps, every 3 pixels, at most 16 cuts per event
// since each one looks at every tetrahedron (2 ms for the built-in beam).
void cut_along(GLFWwindow* window, Controls& c, double x0, double y0, double x1, double y1) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const int samples = std::clamp(static_cast<int>(std::ceil(length / 3)), 1, 16);
  for (int k = 1; k <= samples; ++k) {
    const double s = static_cast<double>(k) / samples;
    cut_under(window, c, x0 + s * (x1 - x0), y0 + s * (y1 - y0));
  }
}

Controls& controls_of(GLFWwindow* window) {
  return *static_cast<Controls*>(glfwGetWindowUserPointer(window));
}

void on_mouse_button(GLFWwindow* window, int button, int action, int mods) {
  Controls& c = controls_of(window);
  if (action == GLFW_PRESS && ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  const bool pressed = action == GLFW_PRESS;
  glfwGetCursorPos(window, &c.x, &c.y);
  // Left drag cuts in cut mode or with Ctrl held; shift + left still pans in either.
  const bool left = button == GLFW_MOUSE_BUTTON_LEFT;
  const bool cut =
      left && !(mods & GLFW_MOD_SHIFT) && (c.session->cut_mode || (mods & GLFW_MOD_CONTROL));
  if (cut) {
    c.cutting = pressed;
    if (pressed) cut_under(window, c, c.x, c.y);
  } else if (left && !(mods & GLFW_MOD_SHIFT)) {
    c.orbiting = pressed;
  }
  if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE ||
      (left && (mods & GLFW_MOD_SHIFT))) {
    c.panning = pressed;
  }
  if (!pressed) c.orbiting = c.panning = c.cutting = false;
}

void on_cursor(GLFWwindow* window, double x, double y) {
  Controls& c = controls_of(window);
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  const double dx = x - c.x, dy = y - c.y;
  const double from_x = c.x, from_y = c.y;
  c.x = x;
  c.y = y;
  if (height <= 0) return;
  if (c.cutting) cut_along(window, c, from_x, from_y, x, y);
  if (c.orbiting) c.camera->orbit(-dx * 0.008, dy * 0.008);
  if (c.panning) c.camera->pan(-dx / height, dy / height);
}

void on_scroll(GLFWwindow* window, double, double offset) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  controls_of(window).camera->zoom(std::pow(0.9, offset));
}

void on_key(GLFWwindow* window, int key, int, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  Controls& c = controls_of(window);
  ViewerSession& s = *c.session;
  // As in runSofa, keys pressed with Ctrl go to the scene's controllers (letters as capitals; the
  // arrows as SOFA's codes 18 left, 19 up, 20 right, 21 down).
  if (mods & GLFW_MOD_CONTROL) {
    if (key >= GLFW_KEY_SPACE && key <= GLFW_KEY_GRAVE_ACCENT) {
      s.key_pressed(static_cast<char>(key));
      return;
    }
    const int arrow = key == GLFW_KEY_LEFT ? 18 : key == GLFW_KEY_UP ? 19 : key == GLFW_KEY_RIGHT ? 20 : key == GLFW_KEY_DOWN ? 21 : 0;
    if (arrow != 0) {
      s.key_pressed(static_cast<char>(arrow));
      return;
    }
  }
  switch (key) {
    case GLFW_KEY_SPACE:
      s.playing = !s.playing;
      break;
    case GLFW_KEY_N:
    case GLFW_KEY_RIGHT:
      s.step();
      break;
    case GLFW_KEY_D:
      s.draw.tetrahedra =
          static_cast<TetrahedronDrawing>((static_cast<int>(s.draw.tetrahedra) + 1) % 3);
      break;
    case GLFW_KEY_E:
      s.draw.surface_edges = !s.draw.surface_edges;
      break;
    case GLFW_KEY_L:
      s.draw.constraints = !s.draw.constraints;
      break;
    case GLFW_KEY_K:
      s.draw.contacts = !s.draw.contacts;
      break;
    case GLFW_KEY_F:
      c.reframe = true;
      break;
    case GLFW_KEY_C:
      s.cut_mode = !s.cut_mode;
      break;
    case GLFW_KEY_R:
      s.reload();
      break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      glfwSetWindowShouldClose(window, GLFW_TRUE);
      break;
    default:
      break;
  }
}

}  // namespace

void view(const ViewOptions& options, std::ostream& out, std::ostream& err) {
  const ImageSize size = parse_image_size(options.picture.size);
  const CameraOptions camera_choices = camera_options(options.picture);
  if (options.frames < 0) throw make_error("--frames ", options.frames, ": must be >= 0");
  ViewerSession session(options);
  for (const auto& line : session.warnings) err << "warning: " << line << '\n';

  Window window(size.width, size.height, "fastcorot view: " + session.title());
  GlRenderer renderer(glfw_loader);
  glfwSwapInterval(options.frames > 0 ? 0 : 1);  // scripted runs need not wait for the display

  SceneDrawer drawer;
  auto frame = [&] {
    return frame_camera(drawer.draw(session.simulation(), session.draw).framing_bounds(),
                        session.simulation().gravity, static_cast<double>(size.width) / size.height,
                        camera_choices);
  };
  Camera camera = frame();
  Controls controls{&session, &camera};
  glfwSetWindowUserPointer(window.handle, &controls);
  glfwSetMouseButtonCallback(window.handle, on_mouse_button);
  glfwSetCursorPosCallback(window.handle, on_cursor);
  glfwSetScrollCallback(window.handle, on_scroll);
  glfwSetKeyCallback(window.handle, on_key);
  window.start_imgui();  // after our callbacks: ImGui chains to them

  PanelState panel;
  RenderStyle style;
  long frames = 0;
  double fps = 0;
  auto last = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(window.handle)) {
    glfwPollEvents();
    session.advance();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (draw_viewer_panel(session, panel, fps).reframe) controls.reframe = true;
    if (controls.reframe) {
      // Cutting or a scene of fixed points only can leave nothing to frame: keep the camera.
      try {
        camera = frame();
      } catch (const Error& error) {
        session.message = std::string("reframe: ") + error.what();
      }
      controls.reframe = false;
    }
    ImGui::Render();

    int width = 0, height = 0;
    glfwGetFramebufferSize(window.handle, &width, &height);
    if (width > 0 && height > 0) {
      // The camera's aspect follows the window when it is resized.
      renderer.draw(drawer.draw(session.simulation(), session.draw), camera, width, height, style);
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ++frames;
    const bool last_frame = options.frames > 0 && frames >= options.frames;
    if ((last_frame || glfwWindowShouldClose(window.handle)) && !options.screenshot.empty() &&
        width > 0) {
      write_png(options.screenshot, renderer.read_pixels(width, height));
    }
    glfwSwapBuffers(window.handle);

    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    if (seconds > 0) fps = fps == 0 ? 1 / seconds : 0.9 * fps + 0.1 / seconds;
    std::ostringstream title;
    title << "fastcorot view: " << session.title() << "  t = " << std::fixed << std::setprecision(3)
          << session.simulation().time() << " s  " << std::setprecision(1)
          << session.steps_per_second() << " steps/s";
    glfwSetWindowTitle(window.handle, title.str().c_str());
    if (last_frame) break;
  }
  if (!session.message.empty()) err << "fastcorot view: " << session.message << '\n';
  out << "fastcorot view: " << session.simulation().steps_done() << " steps, " << frames
      << " frames\n";
}

}  // namespace fastcorot::cli
