#include "fastcorot/render/offscreen_renderer.h"

#include "fastcorot/core/error.h"

#include <GL/osmesa.h>

#include <algorithm>

namespace fastcorot {

namespace {

constexpr int kMaxSide = 8192;

GlProc osmesa_loader(const char* name) {
  return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
}

}  // namespace

struct OffscreenRenderer::Context {
  OSMesaContext context = nullptr;
  std::vector<std::uint8_t> buffer;  // RGBA, OSMesa's colour buffer
  int width = 0, height = 0;

  Context(int w, int h) : buffer(static_cast<std::size_t>(w) * h * 4), width(w), height(h) {
    // A compatibility context: the renderer uses OpenGL 2.1 with GLSL 1.20, wide lines and points.
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              2,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              1,
                              0};
    context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context)
      throw make_error("OSMesa: cannot create an OpenGL 2.1 context (is libosmesa6 installed?)");
    make_current();
  }
  ~Context() { OSMesaDestroyContext(context); }

  bool try_make_current() noexcept {
    return OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height) != 0;
  }
  void make_current() {
    if (!try_make_current()) {
      throw make_error("OSMesa: cannot make the ", width, "x", height, " context current");
    }
  }
};

OffscreenRenderer::OffscreenRenderer(int width, int height, int supersample)
    : width_(width), height_(height), supersample_(std::max(1, supersample)) {
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) {
    throw make_error("picture size ", width, "x", height, ": each side must be in [1, ", kMaxSide,
                     "]");
  }
  while (supersample_ > 1 && std::max(width, height) * supersample_ > kMaxSide) --supersample_;
  context_ = std::make_unique<Context>(width * supersample_, height * supersample_);
  renderer_ = std::make_unique<GlRenderer>(osmesa_loader);
}

OffscreenRenderer::~OffscreenRenderer() {
  // The renderer's GL objects go while the context is still alive and current.
  if (context_ && context_->try_make_current()) renderer_.reset();
}

std::string OffscreenRenderer::driver() const {
  context_->make_current();
  return renderer_->driver();
}

Image OffscreenRenderer::render(const DrawGeometry& geometry, const Camera& camera,
                                const RenderStyle& style) {
  context_->make_current();
  const int s = supersample_;
  renderer_->draw(geometry, camera, width_ * s, height_ * s, style, static_cast<float>(s));
  const Image big = renderer_->read_pixels(width_ * s, height_ * s);
  if (s == 1) return big;
  // Box filter, rounding to nearest: a region of one colour keeps that colour exactly.
  Image image(width_, height_);
  const int samples = s * s;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = 0; dy < s; ++dy) {
          const std::uint8_t* row =
              big.rgb.data() + (static_cast<std::size_t>(y * s + dy) * big.width + x * s) * 3;
          for (int dx = 0; dx < s; ++dx) sum += row[3 * dx + c];
        }
        image.rgb[(static_cast<std::size_t>(y) * width_ + x) * 3 + c] =
            static_cast<std::uint8_t>((sum + samples / 2) / samples);
      }
    }
  }
  return image;
}

}  // namespace fastcorot
