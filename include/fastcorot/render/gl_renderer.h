// Draws a DrawGeometry with OpenGL 2.1 (GLSL 1.20) into whatever framebuffer is current: an
// OSMesa buffer for pictures (offscreen_renderer.h) or the viewer's window. Triangles are lit by a
// key light above the camera and a headlight, on both sides (SOFA's tetrahedra have no consistent
// winding); lines and points are unlit and win over the surfaces they lie on; the background is
// a vertical gradient. GL entry points come from the context's loader rather than from libGL, so
// OSMesa and a windowing GL can live in one program. Same input, same driver: same pixels.
#pragma once

#include "fastcorot/render/camera.h"
#include "fastcorot/render/draw_geometry.h"
#include "fastcorot/render/image.h"

#include <memory>

namespace fastcorot {

using GlProc = void (*)();
using GlLoader = GlProc (*)(const char* name);  // OSMesaGetProcAddress, glfwGetProcAddress

struct RenderStyle {
  Rgba background_top{0.25f, 0.27f, 0.32f, 1.0f};
  Rgba background_bottom{0.08f, 0.09f, 0.11f, 1.0f};
  bool lighting = true;  // off: every triangle in its flat colour (tests compare exact colours)
  float point_size = 5;  // fixed points, in pixels of the final picture
  float marker_size = 10;  // constraint points (SOFA draws its bilateral points 10 pixels wide)
  float line_width = 1.5f;
};

class GlRenderer {
 public:
  // Needs a current OpenGL >= 2.1 context; compiles the shaders. Throws fastcorot::Error naming a
  // missing entry point or a shader that does not compile.
  explicit GlRenderer(GlLoader load);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Clears and draws into the viewport (0, 0, width, height). `pixel_scale` multiplies point sizes
  // and line widths (for supersampled pictures). Throws fastcorot::Error on an OpenGL error.
  void draw(const DrawGeometry& geometry, const Camera& camera, int width, int height,
            const RenderStyle& style, float pixel_scale = 1);

  // The current read buffer's pixels (0, 0, width, height), top row first.
  Image read_pixels(int width, int height) const;

  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Compatibility Profile)
  // Mesa 22.3.6".
  std::string driver() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fastcorot
