#include "fastcorot/render/gl_renderer.h"

#include "fastcorot/core/error.h"
#include "gl_functions.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fastcorot {

namespace render_detail {

GlFunctions::GlFunctions(GlLoader load) {
#define FASTCOROT_GL_LOAD(name)                              \
  name = reinterpret_cast<decltype(name)>(load("gl" #name)); \
  if (!name) throw make_error("OpenGL: the context does not provide gl" #name);
  FASTCOROT_GL_FUNCTIONS(FASTCOROT_GL_LOAD)
#undef FASTCOROT_GL_LOAD
}

}  // namespace render_detail

namespace {

using render_detail::GlFunctions;

// Attribute slots, bound before linking so that no lookup is needed.
enum Attribute : GLuint { kPosition = 0, kNormal = 1, kColor = 2 };

constexpr const char* kVertexShader = R"(#version 120
attribute vec3 position;
attribute vec3 normal;
attribute vec4 color;
uniform mat4 view;
uniform mat4 projection;
varying vec3 eye_normal;
varying vec3 eye_position;
varying vec4 base_color;
void main() {
  vec4 p = view * vec4(position, 1.0);
  eye_position = p.xyz;
  eye_normal = mat3(view) * normal;
  base_color = color;
  gl_Position = projection * p;
}
)";

// Two-sided lighting: |n·l|, because SOFA's drawn triangles have no consistent winding. A key light
// above and left of the camera shapes the surfaces; a headlight keeps faces toward the viewer lit.
constexpr const char* kFragmentShader = R"(#version 120
uniform int lighting;
varying vec3 eye_normal;
varying vec3 eye_position;
varying vec4 base_color;
void main() {
  vec3 c = base_color.rgb;
  if (lighting == 1 && dot(eye_normal, eye_normal) > 1e-12) {
    vec3 n = normalize(eye_normal);
    vec3 key = normalize(vec3(-0.3, 0.8, 0.5));
    vec3 head = normalize(-eye_position);
    c *= 0.28 + 0.52 * abs(dot(n, key)) + 0.25 * abs(dot(n, head));
  }
  gl_FragColor = vec4(min(c, vec3(1.0)), base_color.a);
}
)";

GLuint compile(const GlFunctions& gl, GLenum kind, const char* source) {
  const GLuint shader = gl.CreateShader(kind);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::array<char, 2048> log{};
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteShader(shader);
    throw make_error("OpenGL: a shader does not compile: ", log.data());
  }
  return shader;
}

Eigen::Matrix4f to_float(const Eigen::Matrix4d& m) {
  return m.cast<float>();
}

}  // namespace

struct GlRenderer::Impl {
  GlFunctions gl;
  GLuint program = 0;
  GLint view = -1, projection = -1, lighting = -1;
  std::array<GLuint, 3> buffers{};  // positions, normals, colours

  explicit Impl(GlLoader load) : gl(load) {
    const GLuint vertex = compile(gl, GL_VERTEX_SHADER, kVertexShader);
    const GLuint fragment = compile(gl, GL_FRAGMENT_SHADER, kFragmentShader);
    program = gl.CreateProgram();
    gl.AttachShader(program, vertex);
    gl.AttachShader(program, fragment);
    gl.BindAttribLocation(program, kPosition, "position");
    gl.BindAttribLocation(program, kNormal, "normal");
    gl.BindAttribLocation(program, kColor, "color");
    gl.LinkProgram(program);
    gl.DeleteShader(vertex);
    gl.DeleteShader(fragment);
    GLint ok = 0;
    gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
      std::array<char, 2048> log{};
      gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
      gl.DeleteProgram(program);
      throw make_error("OpenGL: the shaders do not link: ", log.data());
    }
    view = gl.GetUniformLocation(program, "view");
    projection = gl.GetUniformLocation(program, "projection");
    lighting = gl.GetUniformLocation(program, "lighting");
    gl.GenBuffers(3, buffers.data());
  }

  ~Impl() {
    gl.DeleteBuffers(3, buffers.data());
    gl.DeleteProgram(program);
  }

  template <class T>
  void attribute(Attribute slot, GLuint buffer, const std::vector<T>& data, GLint components) {
    gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                  GL_STREAM_DRAW);
    gl.EnableVertexAttribArray(slot);
    gl.VertexAttribPointer(slot, components, GL_FLOAT, GL_FALSE, 0, nullptr);
  }

  // Draws `count` vertices of `mode` from positions, colours and (when given) normals.
  void primitives(GLenum mode, const std::vector<Eigen::Vector3f>& positions,
                  const std::vector<Rgba>& colors, const std::vector<Eigen::Vector3f>* normals) {
    if (positions.empty()) return;
    attribute(kPosition, buffers[0], positions, 3);
    attribute(kColor, buffers[2], colors, 4);
    if (normals) {
      attribute(kNormal, buffers[1], *normals, 3);
    } else {
      gl.DisableVertexAttribArray(kNormal);
      gl.VertexAttrib3f(kNormal, 0, 0, 0);  // unlit
    }
    gl.DrawArrays(mode, 0, static_cast<GLsizei>(positions.size()));
    gl.DisableVertexAttribArray(kPosition);
    gl.DisableVertexAttribArray(kNormal);
    gl.DisableVertexAttribArray(kColor);
  }

  void matrices(const Eigen::Matrix4f& v, const Eigen::Matrix4f& p) {
    gl.UniformMatrix4fv(view, 1, GL_FALSE, v.data());  // Eigen is column-major, as GL expects
    gl.UniformMatrix4fv(projection, 1, GL_FALSE, p.data());
  }
};

GlRenderer::GlRenderer(GlLoader load) : impl_(std::make_unique<Impl>(load)) {}
GlRenderer::~GlRenderer() = default;

std::string GlRenderer::driver() const {
  auto text = [&](GLenum name) {
    const GLubyte* s = impl_->gl.GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

void GlRenderer::draw(const DrawGeometry& geometry, const Camera& camera, int width, int height,
                      const RenderStyle& style, float pixel_scale) {
  const GlFunctions& gl = impl_->gl;
  // Errors are sticky: drop any left by others sharing the context (the viewer's panel), so that
  // the check at the end reports ours only.
  for (int i = 0; i < 16 && gl.GetError() != GL_NO_ERROR; ++i) {
  }
  gl.Viewport(0, 0, width, height);
  gl.ClearColor(0, 0, 0, 1);
  gl.DepthMask(GL_TRUE);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.UseProgram(impl_->program);
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  // Background: a quad in clip space, behind everything and not written to depth.
  gl.Disable(GL_DEPTH_TEST);
  gl.Uniform1i(impl_->lighting, 0);
  impl_->matrices(Eigen::Matrix4f::Identity(), Eigen::Matrix4f::Identity());
  const std::vector<Eigen::Vector3f> quad = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0},
                                             {-1, -1, 0}, {1, 1, 0},  {-1, 1, 0}};
  const Rgba& b = style.background_bottom;
  const Rgba& t = style.background_top;
  impl_->primitives(GL_TRIANGLES, quad, {b, b, t, b, t, t}, nullptr);

  // Depth range from the geometry's box in eye space: tight planes keep the 24-bit depth precise.
  const Eigen::Matrix4d view = camera.view_matrix();
  double nearest = 1e300, farthest = -1e300;
  const Eigen::AlignedBox3d box = geometry.bounds();
  if (!box.isEmpty()) {
    for (int c = 0; c < 8; ++c) {
      const double depth =
          -(view * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).homogeneous()).z();
      nearest = std::min(nearest, depth);
      farthest = std::max(farthest, depth);
    }
  }
  const double far = farthest > 0 ? farthest * 1.05 + 1e-9 : 1.0;
  const double near = std::max(nearest * 0.95, far * 1e-4);
  impl_->matrices(to_float(view), to_float(camera.projection_matrix(
                                      static_cast<double>(width) / height, near, far)));

  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);
  gl.Uniform1i(impl_->lighting, style.lighting ? 1 : 0);
  // Surfaces step back a little in depth so that the points and lines lying on them stay visible.
  gl.Enable(GL_POLYGON_OFFSET_FILL);
  gl.PolygonOffset(1, 1);
  impl_->primitives(GL_TRIANGLES, geometry.triangles.positions, geometry.triangles.colors,
                    &geometry.triangles.normals);
  gl.Disable(GL_POLYGON_OFFSET_FILL);
  gl.Uniform1i(impl_->lighting, 0);
  gl.LineWidth(style.line_width * pixel_scale);
  impl_->primitives(GL_LINES, geometry.lines.positions, geometry.lines.colors, nullptr);
  gl.PointSize(style.point_size * pixel_scale);
  impl_->primitives(GL_POINTS, geometry.points.positions, geometry.points.colors, nullptr);
  // Markers are wide squares drawn at one depth, so a surface they lie on that turns away from the
  // view would cut them; each comes toward the eye along its own ray (its pixel unchanged) by its
  // width at its depth, at most 4 % of its distance (the near plane leaves 5 %).
  std::vector<Eigen::Vector3f> markers = geometry.markers.positions;
  const Eigen::Vector3d forward = (camera.target - camera.eye).normalized();
  const double pixel = 2 * std::tan(camera.fov_y_degrees * std::acos(-1.0) / 360) / height;
  for (Eigen::Vector3f& m : markers) {
    const Eigen::Vector3d to_eye = camera.eye - m.cast<double>();
    const double distance = to_eye.norm();
    if (!(distance > 0)) continue;
    const double width = style.marker_size * pixel_scale * pixel * std::max(0.0, -to_eye.dot(forward));
    m += (std::min(width, 0.04 * distance) / distance * to_eye).cast<float>();
  }
  gl.PointSize(style.marker_size * pixel_scale);
  impl_->primitives(GL_POINTS, markers, geometry.markers.colors, nullptr);
  gl.UseProgram(0);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) {
    throw make_error("OpenGL error 0x", std::hex, error, " while drawing");
  }
}

Image GlRenderer::read_pixels(int width, int height) const {
  const GlFunctions& gl = impl_->gl;
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.Finish();
  gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* from =
        rgba.data() + static_cast<std::size_t>(height - 1 - y) * width * 4;  // GL: bottom row first
    std::uint8_t* to = image.rgb.data() + static_cast<std::size_t>(y) * width * 3;
    for (int x = 0; x < width; ++x) {
      to[3 * x] = from[4 * x];
      to[3 * x + 1] = from[4 * x + 1];
      to[3 * x + 2] = from[4 * x + 2];
    }
  }
  return image;
}

}  // namespace fastcorot
