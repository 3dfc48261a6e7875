// GLSL 3.30 core sources of the renderer's programs (see renderer_passes.cc and overlay_pass.cc
// for the uniforms), and the one compile/link helper pair every GL program is built with.
#pragma once

#include "render/internal/gl_api.h"

namespace render::internal {

// Compiles one shader stage (GL_VERTEX_SHADER or GL_FRAGMENT_SHADER) from the concatenation
// prefix + source. Throws render::ContextError
// "GL: compiling the <what> shader failed: <info log>".
GLuint CompileShader(const GlApi& gl, GLenum stage, const char* source, const char* what,
                     const char* prefix = "");

// Compiles both stages (each as prefix + its source) and links them into a program; the shader
// objects are released. Throws render::ContextError naming `what` with the compile or link info
// log ("GL: linking the <what> program failed: <info log>").
GLuint LinkProgram(const GlApi& gl, const char* vertex_source, const char* fragment_source,
                   const char* what, const char* prefix = "");

// Lit instanced meshes (shapes, tube pieces; the vertex shader also places the ground grid).
// Per-vertex: position (0), normal (1). Per-instance: model matrix columns (2..5), RGBA colour
// (6), material (7: specular, shininess), normal matrix columns (8..10).
// These have no #version line: the renderer prepends "#version 330 core" and the variant
// switches "#define SHADOWS 0|1" (shadow-map lookup for light 0) and, for the mesh fragment
// shader, "#define NUM_LIGHTS 1..4", compiling one program per variant instead of branching per
// fragment (llvmpipe evaluates both sides of a branch and every unrolled loop iteration), and
// puts kShadowLookupShader (Shadow(light_clip, n.l)) before each fragment shader.
extern const char* const kMeshVertexShader;
extern const char* const kShadowLookupShader;
extern const char* const kMeshFragmentShader;
// The ground grid: procedural lines on the plane colour, lit by per-frame constants (the plane
// is flat and has no highlight), so a fragment costs the line pattern and at most one shadow
// lookup instead of the lighting loop.
extern const char* const kGridFragmentShader;
// Depth-only pass from the first light into the shadow map (same vertex layout).
extern const char* const kDepthVertexShader;
extern const char* const kDepthFragmentShader;
// Unlit lines: position (0), uniform colour.
extern const char* const kLineVertexShader;
extern const char* const kLineFragmentShader;
// Overlays (text, images) in pixel coordinates: position (0), uv (1), RGBA colour (2); the
// colour times the atlas texture.
extern const char* const kOverlayVertexShader;
extern const char* const kOverlayFragmentShader;

}  // namespace render::internal
