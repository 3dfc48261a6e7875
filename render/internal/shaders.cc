// GLSL sources and the compile/link helpers (see shaders.h).
#include "render/internal/shaders.h"

#include <string>

#include "render/offscreen_context.h"

namespace render::internal {

namespace {

// Throws ContextError `message` + the object's info log, after deleting the object, unless its
// `status` (GL_COMPILE_STATUS of a shader, GL_LINK_STATUS of a program) is set.
void CheckStatus(GLuint object, GLenum status, PFNGLGETSHADERIVPROC get_iv,
                 PFNGLGETSHADERINFOLOGPROC get_log, PFNGLDELETESHADERPROC destroy,
                 const std::string& message) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return;
  char log[2048] = {};
  get_log(object, sizeof(log), nullptr, log);
  destroy(object);
  throw ContextError(message + log);
}

}  // namespace

GLuint CompileShader(const GlApi& gl, GLenum stage, const char* source, const char* what,
                     const char* prefix) {
  const GLuint shader = gl.CreateShader(stage);
  const char* sources[] = {prefix, source};
  gl.ShaderSource(shader, 2, sources, nullptr);
  gl.CompileShader(shader);
  CheckStatus(shader, GL_COMPILE_STATUS, gl.GetShaderiv, gl.GetShaderInfoLog, gl.DeleteShader,
              std::string("GL: compiling the ") + what + " shader failed: ");
  return shader;
}

GLuint LinkProgram(const GlApi& gl, const char* vertex_source, const char* fragment_source,
                   const char* what, const char* prefix) {
  const GLuint v = CompileShader(gl, GL_VERTEX_SHADER, vertex_source, what, prefix);
  const GLuint f = CompileShader(gl, GL_FRAGMENT_SHADER, fragment_source, what, prefix);
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, v);
  gl.AttachShader(program, f);
  gl.LinkProgram(program);
  gl.DeleteShader(v);
  gl.DeleteShader(f);
  CheckStatus(program, GL_LINK_STATUS, gl.GetProgramiv, gl.GetProgramInfoLog, gl.DeleteProgram,
              std::string("GL: linking the ") + what + " program failed: ");
  return program;
}

const char* const kMeshVertexShader = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 i_model0;
layout(location = 3) in vec4 i_model1;
layout(location = 4) in vec4 i_model2;
layout(location = 5) in vec4 i_model3;
layout(location = 6) in vec4 i_color;
layout(location = 7) in vec4 i_material;
layout(location = 8) in vec3 i_normal0;
layout(location = 9) in vec3 i_normal1;
layout(location = 10) in vec3 i_normal2;
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_color;
out vec2 v_material;
out vec4 v_light;
void main() {
  mat4 model = mat4(i_model0, i_model1, i_model2, i_model3);
  vec4 world = model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = mat3(i_normal0, i_normal1, i_normal2) * a_normal;
  v_color = i_color;
  v_material = i_material.xy;
  v_light = u_light_view_proj * world;
  gl_Position = u_view_proj * world;
}
)";

const char* const kShadowLookupShader = R"(
#if SHADOWS
uniform sampler2DShadow u_shadow_map;
uniform float u_shadow_texel;
#endif

// Fraction of light 0 reaching a point whose shadow-map clip position is `light`, on a surface
// with n.l = `ndl`: 4 bilinear depth comparisons 1.5 texels apart (percentage-closer filtering;
// soft edges about 3 shadow-map texels wide).
float Shadow(vec4 light, float ndl) {
#if !SHADOWS
  return 1.0;
#else
  vec3 p = light.xyz / light.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  float bias = 0.001 + 0.004 * (1.0 - clamp(ndl, 0.0, 1.0));
  vec2 o = vec2(0.75 * u_shadow_texel, -0.75 * u_shadow_texel);
  return 0.5 * (texture(u_shadow_map, vec3(p.xy + o.xx, p.z - bias)) +
                texture(u_shadow_map, vec3(p.xy - o.xx, p.z - bias)));
#endif
}
)";

const char* const kMeshFragmentShader = R"(
in vec3 v_world;
in vec3 v_normal;
in vec4 v_color;
in vec2 v_material;
in vec4 v_light;
uniform vec3 u_eye;
uniform vec3 u_up;
uniform vec3 u_light_dir[4];
uniform vec3 u_light_rgb[4];
uniform vec3 u_ambient;
out vec4 frag_color;

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(u_eye - v_world);
  vec3 base = v_color.rgb;
  float hemi = 0.5 + 0.5 * dot(n, u_up);
  vec3 color = base * u_ambient * mix(0.6, 1.0, hemi);
  // Light 0's shadow once, outside the loop (llvmpipe runs both sides of every branch).
  float shadow0 = Shadow(v_light, dot(n, u_light_dir[0]));
  for (int k = 0; k < NUM_LIGHTS; ++k) {
    vec3 l = u_light_dir[k];
    float ndl = dot(n, l);
    if (ndl <= 0.0) continue;
    float s = (k == 0) ? shadow0 : 1.0;
    vec3 h = normalize(l + v);
    float spec = v_material.x * pow(max(dot(n, h), 0.0), v_material.y);
    color += s * u_light_rgb[k] * (base * ndl + vec3(spec));
  }
  frag_color = vec4(clamp(color, 0.0, 1.0), v_color.a);
}
)";

const char* const kGridFragmentShader = R"(
in vec3 v_world;
in vec4 v_light;
uniform vec4 u_plane_rgba;
uniform vec2 u_grid_center;
uniform float u_grid_spacing;
uniform vec4 u_grid_line;
// Index 0: the plane seen from above (front face, normal +z); 1: from below (normal -z).
uniform vec3 u_unshadowed[2];  // ambient (hemispheric) + lights 1..3: rgb max(n.l, 0)
uniform vec3 u_key[2];         // light 0: rgb max(n.l, 0)
uniform float u_key_ndl[2];    // light 0: n.l (shadow bias)
out vec4 frag_color;

// Grid line coverage (0..1) of lines every `spacing` world units, about `px` pixels wide.
float GridLines(vec2 g, float px) {
  vec2 fw = max(fwidth(g), vec2(1e-6));
  vec2 d = abs(fract(g - 0.5) - 0.5) / fw;
  return 1.0 - clamp(min(d.x, d.y) / px, 0.0, 1.0);
}

void main() {
  int side = gl_FrontFacing ? 0 : 1;
  vec3 base = u_plane_rgba.rgb;
  vec2 g = (v_world.xy - u_grid_center) / u_grid_spacing;
  float fade = clamp(1.5 - 3.0 * max(fwidth(g).x, fwidth(g).y), 0.0, 1.0);
  base = mix(base, u_grid_line.rgb, 0.7 * fade * GridLines(g, 1.0));
  base = mix(base, u_grid_line.rgb * 0.75, GridLines(g / 5.0, 1.2));
  float s = Shadow(v_light, u_key_ndl[side]);
  vec3 color = base * (u_unshadowed[side] + s * u_key[side]);
  frag_color = vec4(clamp(color, 0.0, 1.0), u_plane_rgba.a);
}
)";

const char* const kDepthVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 2) in vec4 i_model0;
layout(location = 3) in vec4 i_model1;
layout(location = 4) in vec4 i_model2;
layout(location = 5) in vec4 i_model3;
uniform mat4 u_light_view_proj;
void main() {
  mat4 model = mat4(i_model0, i_model1, i_model2, i_model3);
  gl_Position = u_light_view_proj * (model * vec4(a_position, 1.0));
}
)";

const char* const kDepthFragmentShader = R"(#version 330 core
void main() {}
)";

const char* const kLineVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
void main() { gl_Position = u_view_proj * vec4(a_position, 1.0); }
)";

const char* const kLineFragmentShader = R"(#version 330 core
uniform vec4 u_color;
out vec4 frag_color;
void main() { frag_color = u_color; }
)";

const char* const kOverlayVertexShader = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 color;
uniform vec2 viewport;
out vec2 frag_uv;
out vec4 frag_color;
void main() {
  frag_uv = uv;
  frag_color = color;
  gl_Position = vec4(2.0 * position.x / viewport.x - 1.0, 1.0 - 2.0 * position.y / viewport.y, 0.0, 1.0);
}
)";
const char* const kOverlayFragmentShader = R"(#version 330 core
in vec2 frag_uv;
in vec4 frag_color;
uniform sampler2D atlas;
out vec4 out_color;
void main() { out_color = frag_color * texture(atlas, frag_uv); }
)";

}  // namespace render::internal
