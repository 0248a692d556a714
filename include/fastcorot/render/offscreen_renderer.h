// Pictures without a display: an OpenGL context in memory from Mesa's OSMesa (software rendering
// with llvmpipe, from Debian's libosmesa6), drawn by GlRenderer. The picture is rendered at
// `supersample` times its size in each direction and box-filtered down, which smooths edges (OSMesa
// has no multisampling). Rendering is deterministic: the same geometry, camera and style give the
// same pixels. The context is made current on the calling thread by each render call.
#pragma once

#include "fastcorot/render/gl_renderer.h"

#include <memory>

namespace fastcorot {

class OffscreenRenderer {
 public:
  // Throws fastcorot::Error when the size is outside [1, 8192] (after supersampling: larger
  // pictures drop to less supersampling) or OSMesa cannot create a context.
  OffscreenRenderer(int width, int height, int supersample = 2);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int supersample() const { return supersample_; }

  Image render(const DrawGeometry& geometry, const Camera& camera, const RenderStyle& style = {});

  // The OpenGL renderer and version strings of the context (for error reports and the docs).
  std::string driver() const;

 private:
  struct Context;
  int width_, height_, supersample_;
  std::unique_ptr<Context> context_;
  std::unique_ptr<GlRenderer> renderer_;
};

}  // namespace fastcorot
