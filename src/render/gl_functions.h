// Internal to the render layer: the OpenGL 2.1 entry points the renderer calls, fetched at run time
// from whoever made the context current (OSMesa for pictures, GLFW for the viewer). Calling
// through this table instead of linking libGL lets one program hold both OSMesa and a windowed GL
// without their identically named symbols colliding, and keeps libGL out of the link.
#pragma once

// Declares the prototypes that decltype reads below; nothing is linked against them.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "fastcorot/render/gl_renderer.h"

namespace fastcorot::render_detail {

// clang-format off
#define FASTCOROT_GL_FUNCTIONS(X)                                                                  \
  X(Viewport) X(ClearColor) X(Clear) X(Enable) X(Disable) X(DepthFunc) X(DepthMask)                \
  X(BlendFunc) X(PolygonOffset) X(LineWidth) X(PointSize) X(ReadPixels) X(PixelStorei)             \
  X(Finish) X(GetError) X(GetString) X(CreateShader) X(ShaderSource) X(CompileShader)              \
  X(GetShaderiv) X(GetShaderInfoLog) X(CreateProgram) X(AttachShader) X(BindAttribLocation)        \
  X(LinkProgram) X(GetProgramiv) X(GetProgramInfoLog) X(DeleteShader) X(DeleteProgram)             \
  X(UseProgram) X(GetUniformLocation) X(UniformMatrix4fv) X(Uniform1i) X(GenBuffers)               \
  X(BindBuffer) X(BufferData) X(DeleteBuffers) X(EnableVertexAttribArray)                          \
  X(DisableVertexAttribArray) X(VertexAttribPointer) X(VertexAttrib3f) X(DrawArrays)
// clang-format on

struct GlFunctions {
#define FASTCOROT_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
  FASTCOROT_GL_FUNCTIONS(FASTCOROT_GL_MEMBER)
#undef FASTCOROT_GL_MEMBER

  // Fetches every entry point; throws fastcorot::Error naming the first one the context lacks.
  explicit GlFunctions(GlLoader load);
};

}  // namespace fastcorot::render_detail
