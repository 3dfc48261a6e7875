// The GL 3.3 core scene renderer (see renderer.h).
//
// Per frame: 1. turn every shape, tube segment and bead into instances of four shared unit meshes
// (or of a cached user mesh); 2. compute the scene's bounding sphere for clip planes and the
// shadow frustum; 3. depth pass from light 0 into a 1024^2 shadow map; 4. lit pass: grid, opaque
// instance batches, translucent instances back to front, lines; 5. (Render only) resolve MSAA and
// read back, flipping rows to top-down.
#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/internal/gl_api.h"
#include "render/internal/overlay_pass.h"
#include "render/internal/shaders.h"
#include "render/internal/tessellate.h"

namespace render {
namespace {

using internal::GlApi;

constexpr int kShadowMapSize = 1024;
constexpr int kMaxSize = 8192;

// One drawn copy of a unit mesh: model matrix, colour, material (specular, shininess, 0, 0).
struct Instance {
  std::array<float, 16> model;
  std::array<float, 4> color;
  std::array<float, 4> material;
  std::array<float, 9> normal;  // column-major inverse transpose of the model's 3x3
};
static_assert(sizeof(Instance) == 33 * sizeof(float));

struct GpuMesh {
  GLuint vao = 0, vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;
  GLsizei index_count = 0;
  float bound_radius = 1.0f;  // radius about the mesh origin enclosing every vertex
};

Eigen::Matrix4f Scale(const Eigen::Vector3f& s) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = s.x();
  m(1, 1) = s.y();
  m(2, 2) = s.z();
  return m;
}

Eigen::Matrix4f Translate(const Eigen::Vector3f& t) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 3) = t;
  return m;
}

// A rigid frame whose z axis runs from a to b, origin at their midpoint.
Eigen::Matrix4f SegmentFrame(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const Eigen::Vector3f z = (b - a).normalized();
  const Eigen::Vector3f helper =
      std::abs(z.z()) < 0.9f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
  const Eigen::Vector3f x = helper.cross(z).normalized();
  const Eigen::Vector3f y = z.cross(x);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 0) = x;
  m.block<3, 1>(0, 1) = y;
  m.block<3, 1>(0, 2) = z;
  m.block<3, 1>(0, 3) = 0.5f * (a + b);
  return m;
}

Instance MakeInstance(const Eigen::Matrix4f& model, const std::array<float, 4>& rgba,
                      const Material& material) {
  Instance inst;
  std::copy(model.data(), model.data() + 16, inst.model.begin());
  inst.color = rgba;
  inst.material = {material.specular, material.shininess, 0.0f, 0.0f};
  const Eigen::Matrix3f linear = model.block<3, 3>(0, 0);
  const float det = linear.determinant();
  const Eigen::Matrix3f normal =
      std::abs(det) > 0.0f ? Eigen::Matrix3f(linear.inverse().transpose()) : linear;
  std::copy(normal.data(), normal.data() + 9, inst.normal.begin());
  return inst;
}

void CheckCamera(const Camera& camera) {
  const Eigen::Vector3f forward = camera.target - camera.eye;
  if (!forward.allFinite() || forward.norm() <= 0.0f) {
    throw std::invalid_argument("camera: eye and target must differ");
  }
  if (!camera.up.allFinite() || forward.normalized().cross(camera.up).norm() < 1e-6f) {
    throw std::invalid_argument("camera: up must not be parallel to the view direction");
  }
  if (!(camera.fovy_deg > 0.0f && camera.fovy_deg < 180.0f)) {
    throw std::invalid_argument("camera: fovy_deg must be in (0, 180), got " +
                                std::to_string(camera.fovy_deg));
  }
}

// Axis-aligned bounds accumulated from spheres.
struct Bounds {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = Eigen::Vector3f::Constant(-1e30f);
  void Add(const Eigen::Vector3f& c, float r) {
    lo = lo.cwiseMin(c - Eigen::Vector3f::Constant(r));
    hi = hi.cwiseMax(c + Eigen::Vector3f::Constant(r));
  }
  bool empty() const { return lo.x() > hi.x(); }
};

}  // namespace

Eigen::Matrix4f ViewMatrix(const Camera& camera) {
  const Eigen::Vector3f f = (camera.target - camera.eye).normalized();
  const Eigen::Vector3f s = f.cross(camera.up).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(camera.eye);
  m(1, 3) = -u.dot(camera.eye);
  m(2, 3) = f.dot(camera.eye);
  return m;
}

Eigen::Matrix4f ProjectionMatrix(const Camera& camera, float aspect, float near_clip,
                                 float far_clip) {
  const float t = 1.0f / std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = -(far_clip + near_clip) / (far_clip - near_clip);
  m(2, 3) = -2.0f * far_clip * near_clip / (far_clip - near_clip);
  m(3, 2) = -1.0f;
  return m;
}

bool ProjectToPixel(const Camera& camera, int width, int height, const Eigen::Vector3f& p,
                    Eigen::Vector2f* pixel) {
  const Eigen::Vector4f c = ViewMatrix(camera) * p.homogeneous();
  if (c.z() >= 0.0f) return false;
  const float f = 0.5f * static_cast<float>(height) /
                  std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  *pixel = Eigen::Vector2f(0.5f * static_cast<float>(width) + f * c.x() / -c.z(),
                           0.5f * static_cast<float>(height) - f * c.y() / -c.z());
  return true;
}

class Renderer::Impl {
 public:
  explicit Impl(const GlProcLoader& load) {
    internal::LoadGlApi(load, &gl_);
    const char* version = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    GLint major = 0, minor = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (version == nullptr || major * 10 + minor < 33) {
      throw ContextError(std::string("GL: need OpenGL >= 3.3 core, context reports '") +
                         (version ? version : "(none)") + "'");
    }
    for (int shadows = 0; shadows < 2; ++shadows) {
      for (int grid = 0; grid < 2; ++grid) {
        const std::string prefix = "#version 330 core\n#define SHADOWS " + std::to_string(shadows) +
                                   "\n#define GRID " + std::to_string(grid) + "\n";
        mesh_programs_[shadows][grid] =
            internal::LinkProgram(gl_, internal::kMeshVertexShader, internal::kMeshFragmentShader,
                                  "mesh", prefix.c_str());
      }
    }
    depth_program_ = internal::LinkProgram(gl_, internal::kDepthVertexShader,
                                           internal::kDepthFragmentShader, "depth");
    line_program_ = internal::LinkProgram(gl_, internal::kLineVertexShader,
                                          internal::kLineFragmentShader, "line");
    for (int lod = 0; lod < 3; ++lod) {
      sphere_[lod] = Upload(internal::UnitSphere(internal::kLodSlices[lod]));
      cylinder_[lod] = Upload(internal::UnitCylinder(internal::kLodSlices[lod]));
    }
    box_ = Upload(internal::UnitBox());
    quad_ = Upload(internal::UnitQuad());
    gl_.GenVertexArrays(1, &line_vao_);
    gl_.GenBuffers(1, &line_buffer_);
    gl_.BindVertexArray(line_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, line_buffer_);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl_.BindVertexArray(0);
    CreateShadowMap();
  }

  ~Impl() {
    for (int lod = 0; lod < 3; ++lod) {
      Release(&sphere_[lod]);
      Release(&cylinder_[lod]);
    }
    Release(&box_);
    Release(&quad_);
    for (auto& [key, entry] : mesh_cache_) Release(&entry.gpu);
    gl_.DeleteVertexArrays(1, &line_vao_);
    gl_.DeleteBuffers(1, &line_buffer_);
    for (auto& row : mesh_programs_) {
      for (GLuint program : row) gl_.DeleteProgram(program);
    }
    gl_.DeleteProgram(depth_program_);
    gl_.DeleteProgram(line_program_);
    gl_.DeleteFramebuffers(1, &shadow_fbo_);
    gl_.DeleteTextures(1, &shadow_texture_);
    ReleaseTargets();
    ReleaseTarget(&cache_);
  }

  GlInfo info() const {
    GlInfo i;
    const auto* v = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    const auto* r = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
    i.version = v ? v : "";
    i.renderer = r ? r : "";
    return i;
  }

  Image Render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options, const Overlay* overlay) {
    CheckSize(width, height);
    const int samples = options.msaa_samples > 1 ? options.msaa_samples : 0;
    EnsureTargets(width, height, samples);
    Draw(scene, camera, width, height, samples ? msaa_.fbo : target_.fbo, options);
    if (samples) Copy(msaa_.fbo, target_.fbo, width, height);
    if (overlay != nullptr) DrawOverlay(*overlay, width, height, target_.fbo);
    return ReadBack(width, height);
  }

  void CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                  const RenderOptions& options) {
    CheckSize(width, height);
    const int samples = options.msaa_samples > 1 ? options.msaa_samples : 0;
    if (!cache_.fbo || width != cache_w_ || height != cache_h_) {
      ReleaseTarget(&cache_);
      cache_w_ = cache_h_ = 0;
      MakeTarget(width, height, 0, &cache_);
      cache_w_ = width;
      cache_h_ = height;
    }
    if (samples) {
      EnsureTargets(width, height, samples);
      Draw(scene, camera, width, height, msaa_.fbo, options);
      Copy(msaa_.fbo, cache_.fbo, width, height);
    } else {
      Draw(scene, camera, width, height, cache_.fbo, options);
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  void DrawCachedScene(GLuint fbo) {
    if (!cache_.fbo) throw std::logic_error("DrawCachedScene: no scene cached");
    Copy(cache_.fbo, fbo, cache_w_, cache_h_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl_.Viewport(0, 0, cache_w_, cache_h_);
  }

  Image ReadCachedScene(const Overlay* overlay) {
    if (!cache_.fbo) throw std::logic_error("ReadCachedScene: no scene cached");
    if (!target_.fbo || target_w_ != cache_w_ || target_h_ != cache_h_) {
      EnsureTargets(cache_w_, cache_h_, 0);
    }
    Copy(cache_.fbo, target_.fbo, cache_w_, cache_h_);
    if (overlay != nullptr) DrawOverlay(*overlay, cache_w_, cache_h_, target_.fbo);
    return ReadBack(cache_w_, cache_h_);
  }

  // target_ (width x height) read back into an image, rows top-down.
  Image ReadBack(int width, int height) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, target_.fbo);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    Image out;
    out.width = width;
    out.height = height;
    out.rgba.resize(4 * static_cast<size_t>(width) * height);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    // GL rows are bottom-up: swap them in place. Alpha is already 255 everywhere (cleared to 1,
    // and blending keeps destination alpha 1).
    const size_t row = 4 * static_cast<size_t>(width);
    for (int y = 0; y < height / 2; ++y) {
      std::swap_ranges(out.rgba.begin() + static_cast<std::ptrdiff_t>(row * y),
                       out.rgba.begin() + static_cast<std::ptrdiff_t>(row * (y + 1)),
                       out.rgba.begin() + static_cast<std::ptrdiff_t>(row * (height - 1 - y)));
    }
    return out;
  }

  void DrawOverlay(const Overlay& overlay, int width, int height, GLuint fbo) {
    CheckSize(width, height);
    if (!overlay_pass_) overlay_pass_ = std::make_unique<internal::OverlayPass>(gl_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl_.Viewport(0, 0, width, height);
    overlay_pass_->Draw(overlay, width, height);
  }

  void Draw(const Scene& scene, const Camera& camera, int width, int height, GLuint fbo,
            const RenderOptions& options) {
    CheckSize(width, height);
    CheckCamera(camera);
    focal_px_ = 0.5f * static_cast<float>(height) /
                std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
    lod_eye_ = camera.eye;
    lod_forward_ = (camera.target - camera.eye).normalized();
    Collect(scene);

    // Bounds -> clip planes and the shadow frustum.
    Bounds bounds;
    for (const auto& batch : opaque_) {
      for (const Instance& inst : batch.second) AddBounds(&bounds, inst, batch.first->bound_radius);
    }
    for (const auto& [mesh, inst] : translucent_) AddBounds(&bounds, inst, mesh->bound_radius);
    for (const Lines& l : scene.lines) {
      for (const auto& p : l.points) bounds.Add(p, 0.0f);
    }
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    float radius = 1.0f;
    if (!bounds.empty()) {
      centre = 0.5f * (bounds.lo + bounds.hi);
      radius = std::max(0.5f * (bounds.hi - bounds.lo).norm(), 1e-3f);
    }
    // The grid only affects clipping (it is large and flat); shadows fit the objects.
    Bounds clip_bounds = bounds;
    if (scene.grid.enabled) {
      const float h = 0.5f * scene.grid.extent;
      for (float sx : {-h, h}) {
        for (float sy : {-h, h}) {
          clip_bounds.Add(Eigen::Vector3f(scene.grid.center.x() + sx, scene.grid.center.y() + sy,
                                          scene.grid.height),
                          0.0f);
        }
      }
    }
    float near_clip = camera.near_clip, far_clip = camera.far_clip;
    if (near_clip <= 0.0f || far_clip <= near_clip) {
      const Eigen::Vector3f forward = (camera.target - camera.eye).normalized();
      float far_d = 1.0f, near_d = 1.0f;
      if (!clip_bounds.empty()) {
        const Eigen::Vector3f c = 0.5f * (clip_bounds.lo + clip_bounds.hi);
        const float r = 0.5f * (clip_bounds.hi - clip_bounds.lo).norm();
        const float d = (c - camera.eye).dot(forward);
        far_d = std::max(d + r, 1e-2f) * 1.05f;
        near_d = std::max(0.95f * (d - r), far_d * 1e-3f);
      }
      near_clip = near_clip > 0.0f ? near_clip : near_d;
      far_clip = far_clip > near_clip ? far_clip : far_d;
    }
    const Eigen::Matrix4f view_proj =
        ProjectionMatrix(camera, static_cast<float>(width) / static_cast<float>(height), near_clip,
                         far_clip) *
        ViewMatrix(camera);

    // Lights: the scene's, or a default rig attached to the camera.
    std::vector<Light> lights = scene.lights;
    if (lights.empty()) {
      const Eigen::Vector3f f = (camera.target - camera.eye).normalized();
      const Eigen::Vector3f right = f.cross(camera.up).normalized();
      const Eigen::Vector3f up = camera.up.normalized();
      lights.push_back({(1.0f * up + 0.45f * right - 0.5f * f), {0.72f, 0.72f, 0.72f}});
      lights.push_back({(0.3f * up - 0.8f * right - 0.4f * f), {0.30f, 0.30f, 0.32f}});
    }
    if (lights.size() > 4) lights.resize(4);
    for (Light& l : lights) {
      if (l.direction.norm() > 0.0f) l.direction.normalize();
    }

    // Shadow pass.
    const bool shadows = options.shadows && !bounds.empty() && lights[0].direction.norm() > 0.0f;
    Eigen::Matrix4f light_view_proj = Eigen::Matrix4f::Identity();
    if (shadows) {
      Camera light_cam;
      light_cam.eye = centre + 2.0f * radius * lights[0].direction;
      light_cam.target = centre;
      light_cam.up = std::abs(lights[0].direction.z()) < 0.95f ? Eigen::Vector3f::UnitZ()
                                                               : Eigen::Vector3f::UnitX();
      Eigen::Matrix4f ortho = Eigen::Matrix4f::Identity();
      const float n = 0.5f * radius, f = 3.5f * radius;
      ortho(0, 0) = 1.0f / radius;
      ortho(1, 1) = 1.0f / radius;
      ortho(2, 2) = -2.0f / (f - n);
      ortho(2, 3) = -(f + n) / (f - n);
      light_view_proj = ortho * ViewMatrix(light_cam);
      gl_.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
      gl_.Viewport(0, 0, kShadowMapSize, kShadowMapSize);
      gl_.Enable(GL_DEPTH_TEST);
      gl_.DepthMask(GL_TRUE);
      gl_.Clear(GL_DEPTH_BUFFER_BIT);
      gl_.Enable(GL_POLYGON_OFFSET_FILL);
      gl_.PolygonOffset(1.5f, 4.0f);
      gl_.UseProgram(depth_program_);
      gl_.UniformMatrix4fv(gl_.GetUniformLocation(depth_program_, "u_light_view_proj"), 1, GL_FALSE,
                           light_view_proj.data());
      for (const auto& [mesh, items] : opaque_) DrawInstances(*mesh, items);
      gl_.Disable(GL_POLYGON_OFFSET_FILL);
    }

    // Lit pass.
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl_.Viewport(0, 0, width, height);
    gl_.ClearColor(scene.background[0], scene.background[1], scene.background[2], 1.0f);
    gl_.ClearDepth(1.0);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.DepthMask(GL_TRUE);
    gl_.Disable(GL_BLEND);
    gl_.Disable(GL_CULL_FACE);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    std::array<float, 12> dirs{}, rgbs{};
    for (size_t k = 0; k < lights.size(); ++k) {
      for (int c = 0; c < 3; ++c) {
        dirs[3 * k + c] = lights[k].direction[c];
        rgbs[3 * k + c] = lights[k].rgb[c];
      }
    }
    const Eigen::Vector3f up = camera.up.normalized();
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, shadow_texture_);
    // Binds the lit program variant and sets the uniforms every variant shares.
    auto use_lit = [&](bool grid) {
      const GLuint p = mesh_programs_[shadows ? 1 : 0][grid ? 1 : 0];
      gl_.UseProgram(p);
      gl_.UniformMatrix4fv(Uniform(p, "u_view_proj"), 1, GL_FALSE, view_proj.data());
      gl_.UniformMatrix4fv(Uniform(p, "u_light_view_proj"), 1, GL_FALSE, light_view_proj.data());
      gl_.Uniform3f(Uniform(p, "u_eye"), camera.eye.x(), camera.eye.y(), camera.eye.z());
      gl_.Uniform3f(Uniform(p, "u_up"), up.x(), up.y(), up.z());
      gl_.Uniform1i(Uniform(p, "u_num_lights"), static_cast<GLint>(lights.size()));
      gl_.Uniform3fv(Uniform(p, "u_light_dir"), 4, dirs.data());
      gl_.Uniform3fv(Uniform(p, "u_light_rgb"), 4, rgbs.data());
      gl_.Uniform3f(Uniform(p, "u_ambient"), scene.ambient[0], scene.ambient[1], scene.ambient[2]);
      gl_.Uniform1i(Uniform(p, "u_shadow_map"), 0);
      gl_.Uniform1f(Uniform(p, "u_shadow_texel"), 1.0f / kShadowMapSize);
      return p;
    };

    if (scene.grid.enabled && scene.grid.extent > 0.0f && scene.grid.spacing > 0.0f) {
      const Grid& g = scene.grid;
      const GLuint p = use_lit(true);
      gl_.Uniform2f(Uniform(p, "u_grid_center"), g.center.x(), g.center.y());
      gl_.Uniform1f(Uniform(p, "u_grid_spacing"), g.spacing);
      gl_.Uniform4f(Uniform(p, "u_grid_line"), g.line_rgba[0], g.line_rgba[1], g.line_rgba[2],
                    g.line_rgba[3]);
      Material flat;
      flat.specular = 0.0f;
      const Eigen::Matrix4f model =
          Translate(Eigen::Vector3f(g.center.x(), g.center.y(), g.height)) *
          Scale(Eigen::Vector3f(g.extent, g.extent, 1.0f));
      scratch_.assign(1, MakeInstance(model, g.plane_rgba, flat));
      // Pushed back in depth so that shapes resting on the ground do not z-fight with it.
      gl_.Enable(GL_POLYGON_OFFSET_FILL);
      gl_.PolygonOffset(1.0f, 2.0f);
      DrawInstances(quad_, scratch_);
      gl_.Disable(GL_POLYGON_OFFSET_FILL);
    }
    use_lit(false);
    for (const auto& [mesh, items] : opaque_) DrawInstances(*mesh, items);

    if (!translucent_.empty()) {
      // Back to front by view depth of the instance origin.
      const Eigen::Matrix4f view = ViewMatrix(camera);
      std::stable_sort(
          translucent_.begin(), translucent_.end(), [&view](const auto& a, const auto& b) {
            const float za = (view * Eigen::Vector4f(a.second.model[12], a.second.model[13],
                                                     a.second.model[14], 1.0f))
                                 .z();
            const float zb = (view * Eigen::Vector4f(b.second.model[12], b.second.model[13],
                                                     b.second.model[14], 1.0f))
                                 .z();
            return za < zb;
          });
      gl_.Enable(GL_BLEND);
      gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      gl_.DepthMask(GL_FALSE);
      for (const auto& [mesh, inst] : translucent_) {
        scratch_.assign(1, inst);
        DrawInstances(*mesh, scratch_);
      }
      gl_.DepthMask(GL_TRUE);
      gl_.Disable(GL_BLEND);
    }

    if (!scene.lines.empty()) {
      gl_.UseProgram(line_program_);
      gl_.UniformMatrix4fv(Uniform(line_program_, "u_view_proj"), 1, GL_FALSE, view_proj.data());
      gl_.BindVertexArray(line_vao_);
      gl_.BindBuffer(GL_ARRAY_BUFFER, line_buffer_);
      for (const Lines& l : scene.lines) {
        if (l.points.size() < 2) continue;
        gl_.Uniform4f(Uniform(line_program_, "u_color"), l.rgba[0], l.rgba[1], l.rgba[2],
                      l.rgba[3]);
        gl_.BufferData(GL_ARRAY_BUFFER,
                       static_cast<GLsizeiptr>(l.points.size() * sizeof(Eigen::Vector3f)),
                       l.points.data(), GL_STREAM_DRAW);
        gl_.LineWidth(std::max(1.0f, l.width));
        gl_.DrawArrays(l.strip ? GL_LINE_STRIP : GL_LINES, 0,
                       static_cast<GLsizei>(l.strip ? l.points.size() : l.points.size() / 2 * 2));
      }
      gl_.LineWidth(1.0f);
      gl_.BindVertexArray(0);
    }
    gl_.UseProgram(0);
  }

 private:
  struct CachedMesh {
    std::weak_ptr<const TriangleMesh> owner;
    GpuMesh gpu;
  };

  static void CheckSize(int width, int height) {
    if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
      throw std::invalid_argument("render size " + std::to_string(width) + "x" +
                                  std::to_string(height) + " outside 1..8192");
    }
  }

  GLint Uniform(GLuint program, const char* name) const {
    return gl_.GetUniformLocation(program, name);
  }

  static void AddBounds(Bounds* b, const Instance& inst, float mesh_radius) {
    const Eigen::Map<const Eigen::Matrix4f> m(inst.model.data());
    const float scale =
        std::max({m.col(0).head<3>().norm(), m.col(1).head<3>().norm(), m.col(2).head<3>().norm()});
    b->Add(m.block<3, 1>(0, 3), scale * mesh_radius);
  }

  GpuMesh Upload(const TriangleMesh& input) {
    const TriangleMesh mesh = internal::WithNormals(input);
    GpuMesh g;
    std::vector<float> interleaved;
    interleaved.reserve(6 * mesh.positions.size());
    float r2 = 0.0f;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      for (int c = 0; c < 3; ++c) interleaved.push_back(mesh.positions[i][c]);
      for (int c = 0; c < 3; ++c) interleaved.push_back(mesh.normals[i][c]);
      r2 = std::max(r2, mesh.positions[i].squaredNorm());
    }
    g.bound_radius = std::sqrt(r2);
    g.index_count = static_cast<GLsizei>(mesh.indices.size());
    gl_.GenVertexArrays(1, &g.vao);
    gl_.GenBuffers(1, &g.vertex_buffer);
    gl_.GenBuffers(1, &g.index_buffer);
    gl_.GenBuffers(1, &g.instance_buffer);
    gl_.BindVertexArray(g.vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, g.vertex_buffer);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                   interleaved.data(), GL_STATIC_DRAW);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    gl_.EnableVertexAttribArray(1);
    gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                            reinterpret_cast<void*>(3 * sizeof(float)));
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.index_buffer);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                   mesh.indices.data(), GL_STATIC_DRAW);
    gl_.BindBuffer(GL_ARRAY_BUFFER, g.instance_buffer);
    // Instance attributes: model columns (2..5), colour (6), material (7), normal matrix
    // columns (8..10).
    for (int k = 0; k < 9; ++k) {
      const auto location = static_cast<GLuint>(2 + k);
      gl_.EnableVertexAttribArray(location);
      gl_.VertexAttribPointer(
          location, k < 6 ? 4 : 3, GL_FLOAT, GL_FALSE, sizeof(Instance),
          reinterpret_cast<void*>((k < 6 ? 4 * k : 24 + 3 * (k - 6)) * sizeof(float)));
      gl_.VertexAttribDivisor(location, 1);
    }
    gl_.BindVertexArray(0);
    return g;
  }

  void Release(GpuMesh* g) {
    gl_.DeleteVertexArrays(1, &g->vao);
    GLuint buffers[] = {g->vertex_buffer, g->index_buffer, g->instance_buffer};
    gl_.DeleteBuffers(3, buffers);
    *g = GpuMesh{};
  }

  const GpuMesh* MeshFor(const std::shared_ptr<const TriangleMesh>& mesh) {
    auto it = mesh_cache_.find(mesh.get());
    if (it != mesh_cache_.end() && it->second.owner.lock() == mesh) return &it->second.gpu;
    if (it != mesh_cache_.end()) {
      Release(&it->second.gpu);
      mesh_cache_.erase(it);
    }
    // Drop entries whose meshes are gone so the cache does not grow without bound.
    for (auto e = mesh_cache_.begin(); e != mesh_cache_.end();) {
      if (e->second.owner.expired()) {
        Release(&e->second.gpu);
        e = mesh_cache_.erase(e);
      } else {
        ++e;
      }
    }
    CachedMesh entry{mesh, Upload(*mesh)};
    return &mesh_cache_.emplace(mesh.get(), entry).first->second.gpu;
  }

  void Add(const GpuMesh* mesh, const Eigen::Matrix4f& model, const std::array<float, 4>& rgba,
           const Material& material) {
    const Instance inst = MakeInstance(model, rgba, material);
    if (rgba[3] < 1.0f) {
      translucent_.emplace_back(mesh, inst);
      return;
    }
    for (auto& batch : opaque_) {
      if (batch.first == mesh) {
        batch.second.push_back(inst);
        return;
      }
    }
    opaque_.emplace_back(mesh, std::vector<Instance>{inst});
  }

  // Level of detail for a round primitive of `radius` centred at `centre` (world frame): from
  // its projected radius in pixels. Deterministic (depends on the geometry and camera only).
  int Lod(const Eigen::Vector3f& centre, float radius) const {
    const float depth = std::max((centre - lod_eye_).dot(lod_forward_), 1e-6f);
    const float px = focal_px_ * radius / depth;
    return px < internal::kLodMaxRadiusPx[0] ? 0 : (px < internal::kLodMaxRadiusPx[1] ? 1 : 2);
  }
  const GpuMesh* SphereAt(const Eigen::Matrix4f& model) const {
    const float r = std::max({model.col(0).head<3>().norm(), model.col(1).head<3>().norm(),
                              model.col(2).head<3>().norm()});
    return &sphere_[Lod(model.block<3, 1>(0, 3), r)];
  }
  const GpuMesh* CylinderAt(const Eigen::Matrix4f& model) const {
    const float r = std::max(model.col(0).head<3>().norm(), model.col(1).head<3>().norm());
    return &cylinder_[Lod(model.block<3, 1>(0, 3), r)];
  }

  // Scene -> instance batches (opaque_, in first-use order) and translucent_ instances.
  void Collect(const Scene& scene) {
    for (auto& batch : opaque_) batch.second.clear();
    translucent_.clear();
    for (const Shape& s : scene.shapes) {
      const Eigen::Matrix4f& w = s.world_from_shape;
      const std::array<float, 4>& rgba = s.material.rgba;
      switch (s.kind) {
        case Shape::Kind::kSphere: {
          const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f::Constant(s.size.x()));
          Add(SphereAt(m), m, rgba, s.material);
        } break;
        case Shape::Kind::kCapsule: {
          const float r = s.size.x(), len = s.size.y();
          if (len > 0.0f) {
            const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f(r, r, len));
            Add(CylinderAt(m), m, rgba, s.material);
          }
          for (float z : {-0.5f * len, 0.5f * len}) {
            const Eigen::Matrix4f m =
                w * Translate(Eigen::Vector3f(0, 0, z)) * Scale(Eigen::Vector3f::Constant(r));
            Add(SphereAt(m), m, rgba, s.material);
          }
          break;
        }
        case Shape::Kind::kCylinder: {
          const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f(s.size.x(), s.size.x(), s.size.y()));
          Add(CylinderAt(m), m, rgba, s.material);
        } break;
        case Shape::Kind::kBox:
          Add(&box_, w * Scale(s.size), rgba, s.material);
          break;
        case Shape::Kind::kMesh:
          if (s.mesh && !s.mesh->indices.empty()) {
            Add(MeshFor(s.mesh), w * Scale(s.size), rgba, s.material);
          }
          break;
      }
    }
    for (const Tube& t : scene.tubes) {
      const size_t n = t.points.size();
      const bool per_segment = !t.segment_colors.empty() && t.segment_colors.size() + 1 >= n;
      auto colour = [&](size_t seg) {
        return per_segment ? t.segment_colors[std::min(seg, t.segment_colors.size() - 1)]
                           : t.material.rgba;
      };
      for (size_t i = 0; i + 1 < n; ++i) {
        const Eigen::Vector3f& a = t.points[i];
        const Eigen::Vector3f& b = t.points[i + 1];
        const float len = (b - a).norm();
        if (!(len > 0.0f)) continue;
        const Eigen::Matrix4f m =
            SegmentFrame(a, b) * Scale(Eigen::Vector3f(t.radius, t.radius, len));
        Add(CylinderAt(m), m, colour(i), t.material);
      }
      const float bead = t.bead_radius > 0.0f ? t.bead_radius : t.radius;
      for (size_t i = 0; i < n; ++i) {
        const Eigen::Matrix4f m = Translate(t.points[i]) * Scale(Eigen::Vector3f::Constant(bead));
        Add(SphereAt(m), m, colour(i == 0 ? 0 : (i + 1 < n ? i : i - 1)), t.material);
      }
    }
    // Batches unused this frame may point at meshes dropped from the cache: forget them.
    std::erase_if(opaque_, [](const auto& batch) { return batch.second.empty(); });
  }

  void DrawInstances(const GpuMesh& mesh, const std::vector<Instance>& items) {
    if (items.empty()) return;
    gl_.BindVertexArray(mesh.vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, mesh.instance_buffer);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(items.size() * sizeof(Instance)),
                   items.data(), GL_STREAM_DRAW);
    gl_.DrawElementsInstanced(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(items.size()));
    gl_.BindVertexArray(0);
  }

  void CreateShadowMap() {
    gl_.GenTextures(1, &shadow_texture_);
    gl_.BindTexture(GL_TEXTURE_2D, shadow_texture_);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0,
                   GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl_.GenFramebuffers(1, &shadow_fbo_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture_,
                             0);
    gl_.DrawBuffer(GL_NONE);
    gl_.ReadBuffer(GL_NONE);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw ContextError("GL: shadow-map framebuffer incomplete");
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  // A framebuffer object with colour and depth renderbuffers.
  struct Target {
    GLuint fbo = 0, color = 0, depth = 0;
  };

  void MakeTarget(int width, int height, int samples, Target* t) {
    gl_.GenFramebuffers(1, &t->fbo);
    gl_.GenRenderbuffers(1, &t->color);
    gl_.GenRenderbuffers(1, &t->depth);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, t->color);
    if (samples) {
      gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    } else {
      gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    }
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->color);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, t->depth);
    if (samples) {
      gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width,
                                         height);
    } else {
      gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
    }
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                t->depth);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
      throw ContextError("GL: framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                         " with " + std::to_string(samples) +
                         " samples is incomplete (MSAA unsupported?)");
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  void ReleaseTarget(Target* t) {
    if (t->fbo) gl_.DeleteFramebuffers(1, &t->fbo);
    for (GLuint* r : {&t->color, &t->depth}) {
      if (*r) gl_.DeleteRenderbuffers(1, r);
    }
    *t = Target{};
  }

  // Colour copy (same size; resolves a multisampled source). Unaffected by the scissor test,
  // which nothing leaves enabled.
  void Copy(GLuint from, GLuint to, int width, int height) {
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, from);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
    gl_.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }

  // Single-sample colour+depth FBO (target_) and, for MSAA, a multisample one resolved into it.
  void EnsureTargets(int width, int height, int samples) {
    if (target_.fbo && width == target_w_ && height == target_h_ && samples == target_samples_) {
      return;
    }
    ReleaseTargets();
    MakeTarget(width, height, 0, &target_);
    if (samples) MakeTarget(width, height, samples, &msaa_);
    target_w_ = width;
    target_h_ = height;
    target_samples_ = samples;
  }

  void ReleaseTargets() {
    ReleaseTarget(&target_);
    ReleaseTarget(&msaa_);
  }

  GlApi gl_;
  GLuint mesh_programs_[2][2] = {{0, 0}, {0, 0}};  // [shadows][grid]
  GLuint depth_program_ = 0, line_program_ = 0;
  GpuMesh sphere_[3], cylinder_[3], box_, quad_;  // spheres and cylinders per level of detail
  // Pixels per unit length at unit depth (f of the pinhole model) and the camera, for choosing
  // levels of detail in Collect().
  float focal_px_ = 1.0f;
  Eigen::Vector3f lod_eye_ = Eigen::Vector3f::Zero(), lod_forward_ = Eigen::Vector3f::UnitZ();
  std::map<const TriangleMesh*, CachedMesh> mesh_cache_;
  GLuint line_vao_ = 0, line_buffer_ = 0;
  GLuint shadow_fbo_ = 0, shadow_texture_ = 0;
  Target target_, msaa_;  // Render()'s read-back target and its multisampled twin
  int target_w_ = 0, target_h_ = 0, target_samples_ = 0;
  Target cache_;  // CacheScene()'s image
  int cache_w_ = 0, cache_h_ = 0;
  // Per-frame scratch, reused between frames (no reallocation once sized).
  std::vector<std::pair<const GpuMesh*, std::vector<Instance>>> opaque_;
  std::vector<std::pair<const GpuMesh*, Instance>> translucent_;
  std::vector<Instance> scratch_;
  std::unique_ptr<internal::OverlayPass> overlay_pass_;  // created on first use
};

Renderer::Renderer(const GlProcLoader& load) : impl_(std::make_unique<Impl>(load)) {}
Renderer::~Renderer() = default;

Image Renderer::Render(const Scene& scene, const Camera& camera, int width, int height,
                       const RenderOptions& options, const Overlay* overlay) {
  return impl_->Render(scene, camera, width, height, options, overlay);
}

void Renderer::DrawOverlay(const Overlay& overlay, int width, int height, unsigned fbo) {
  impl_->DrawOverlay(overlay, width, height, fbo);
}

void Renderer::Draw(const Scene& scene, const Camera& camera, int width, int height, unsigned fbo,
                    const RenderOptions& options) {
  impl_->Draw(scene, camera, width, height, fbo, options);
}

void Renderer::CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                          const RenderOptions& options) {
  impl_->CacheScene(scene, camera, width, height, options);
}

void Renderer::DrawCachedScene(unsigned fbo) { impl_->DrawCachedScene(fbo); }

Image Renderer::ReadCachedScene(const Overlay* overlay) { return impl_->ReadCachedScene(overlay); }

GlInfo Renderer::info() const { return impl_->info(); }

}  // namespace render
