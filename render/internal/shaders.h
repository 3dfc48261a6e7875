// GLSL 3.30 core sources of the renderer's three programs (see renderer.cc for the uniforms).
#pragma once

namespace render::internal {

// Lit instanced meshes (shapes, tube pieces, the ground grid). Per-vertex: position (0), normal
// (1). Per-instance: model matrix columns (2..5), RGBA colour (6), material (7: specular,
// shininess).
// These two have no #version line: the renderer prepends "#version 330 core" and the variant
// switches "#define SHADOWS 0|1" (shadow-map lookup for light 0) and "#define GRID 0|1"
// (procedural grid lines), compiling one program per variant instead of branching per fragment.
extern const char* const kMeshVertexShader;
extern const char* const kMeshFragmentShader;
// Depth-only pass from the first light into the shadow map (same vertex layout).
extern const char* const kDepthVertexShader;
extern const char* const kDepthFragmentShader;
// Unlit lines: position (0), uniform colour.
extern const char* const kLineVertexShader;
extern const char* const kLineFragmentShader;

}  // namespace render::internal
