// The state behind render::Renderer: GL programs, unit meshes per level of detail, the user-mesh
// cache, the shadow map, the framebuffer targets and the per-frame instance batches. Its member
// functions are defined in renderer.cc (set-up and the public entry points),
// internal/renderer_passes.cc (one frame: shadow and lit passes), internal/renderer_collect.cc
// (scene -> instances) and internal/renderer_gpu.cc (GL buffers, textures and framebuffers).
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "render/internal/frame_geometry.h"
#include "render/internal/gl_api.h"
#include "render/internal/instance.h"
#include "render/internal/overlay_pass.h"
#include "render/renderer.h"

namespace render {
namespace internal {

// Per-frame values every lit program variant receives (world frame).
struct LitFrame {
  Eigen::Matrix4f view_proj;        // camera clip from world
  Eigen::Matrix4f light_view_proj;  // light 0's shadow-map clip from world (identity: no shadows)
  bool shadows = false;
  int shadow_map_size = 1024;  // texels on a side of the shadow map (RenderOptions)
  // Pixel rectangle of the ground that light 0 can shadow (GroundShadowRect); the grid outside
  // it is drawn without shadow lookups.
  PixelRect ground_shadow_rect;
  int num_lights = 0;                              // 1..4
  std::array<float, 12> light_dir{}, light_rgb{};  // xyz per light; directions towards the light
  Eigen::Vector3f eye, up;                         // camera position and unit up
  std::array<float, 3> ambient;                    // hemispheric ambient RGB
};

}  // namespace internal

class Renderer::Impl {
 public:
  explicit Impl(const GlProcLoader& load);
  ~Impl();

  GlInfo info() const;
  Image Render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options, const Overlay* overlay);
  void CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                  const RenderOptions& options);
  void DrawCachedScene(GLuint fbo);
  Image ReadCachedScene(const Overlay* overlay);
  void DrawOverlay(const Overlay& overlay, int width, int height, GLuint fbo);
  void Draw(const Scene& scene, const Camera& camera, int width, int height, GLuint fbo,
            const RenderOptions& options);

 private:
  using GpuMesh = internal::GpuMesh;
  using Instance = internal::Instance;

  // Opaque instances of one mesh drawn together; `cull`: back faces may be culled in the lit pass
  // (closed unit meshes placed with a positive determinant, whose back faces are hidden).
  struct Batch {
    const GpuMesh* mesh = nullptr;
    bool cull = false;
    std::vector<Instance> items;
  };
  struct CachedMesh {
    std::weak_ptr<const TriangleMesh> owner;
    GpuMesh gpu;
  };
  // A framebuffer object with colour and depth renderbuffers.
  struct Target {
    GLuint fbo = 0, color = 0, depth = 0;
  };

  // renderer.cc: sizes, read-back.
  static void CheckSize(int width, int height);
  // target_ (width x height) read back into an image, rows top-down.
  Image ReadBack(int width, int height);

  // renderer_passes.cc: one frame.
  GLint Uniform(GLuint program, const char* name) const;
  // Bounds of this frame's opaque instances (the shadow casters; world frame).
  internal::Bounds OpaqueBounds() const;
  // `opaque` plus this frame's translucent instances and the scene's lines.
  internal::Bounds FrameBounds(const internal::Bounds& opaque,
                               const std::vector<Lines>& lines) const;
  // Renders the opaque instances into the shadow map from `light_view_proj` (clip from world).
  void ShadowPass(const Eigen::Matrix4f& light_view_proj, int size);
  // Draws the opaque batches with the current program; `cull_back_faces`: cull those of the
  // batches that allow it (Batch::cull).
  void DrawOpaque(bool cull_back_faces);
  // Clears framebuffer `fbo` to the scene background and draws opaque instances, the grid,
  // translucent instances and lines.
  void LitPass(const Scene& scene, const Camera& camera, int width, int height, GLuint fbo,
               const internal::LitFrame& frame);
  // The lit mesh program variant for `shadows` and 1..4 lights, linked on first use.
  GLuint MeshProgram(bool shadows, int num_lights);
  // Binds the lit mesh program variant and sets its uniforms.
  void UseLitProgram(const internal::LitFrame& frame);
  // The grid: the shadowing variant inside frame.ground_shadow_rect, the plain one around it.
  void DrawGrid(const Grid& grid, const internal::LitFrame& frame, int width, int height);
  // Binds grid program variant `shadows` and sets its uniforms (lighting of the flat plane).
  void UseGridProgram(const Grid& grid, const internal::LitFrame& frame, bool shadows);
  // translucent_ sorted back to front by view depth of the instance origin, then blended.
  void DrawTranslucent(const Camera& camera);
  void DrawLines(const std::vector<Lines>& lines, const Eigen::Matrix4f& view_proj);

  // renderer_collect.cc: scene -> instance batches (opaque_, in first-use order) and
  // translucent_ instances.
  void Collect(const Scene& scene);
  void CollectShape(const Shape& shape);
  void CollectTube(const Tube& tube);
  void Add(const GpuMesh* mesh, const Eigen::Matrix4f& model, const std::array<float, 4>& rgba,
           const Material& material);
  // Level of detail for a round primitive of `radius` centred at `centre` (world frame): from
  // its projected radius in pixels. Deterministic (depends on the geometry and camera only).
  int Lod(const Eigen::Vector3f& centre, float radius) const;
  const GpuMesh* SphereAt(const Eigen::Matrix4f& model) const;
  const GpuMesh* CylinderAt(const Eigen::Matrix4f& model) const;

  // renderer_gpu.cc: GL resources.
  GpuMesh Upload(const TriangleMesh& input);
  void Release(GpuMesh* g);
  const GpuMesh* MeshFor(const std::shared_ptr<const TriangleMesh>& mesh);
  void DrawInstances(const GpuMesh& mesh, const std::vector<Instance>& items);
  // Creates the shadow-map texture and framebuffer (size x size), or resizes the texture.
  void CreateShadowMap(int size);
  void MakeTarget(int width, int height, int samples, Target* t);
  void ReleaseTarget(Target* t);
  // Colour copy (same size; resolves a multisampled source). Unaffected by the scissor test,
  // which nothing leaves enabled.
  void Copy(GLuint from, GLuint to, int width, int height);
  // Single-sample colour+depth FBO (target_) and, for MSAA, a multisample one resolved into it.
  void EnsureTargets(int width, int height, int samples);
  void ReleaseTargets();

  internal::GlApi gl_;
  GLuint mesh_programs_[2][4] = {};   // [shadows][lights - 1]; linked on first use
  GLuint grid_programs_[2] = {0, 0};  // [shadows]
  GLuint depth_program_ = 0, line_program_ = 0;
  GpuMesh sphere_[3], cylinder_[3], box_, quad_;  // spheres and cylinders per level of detail
  // Pixels per unit length at unit depth (f of the pinhole model) and the camera, for choosing
  // levels of detail in Collect().
  float focal_px_ = 1.0f;
  Eigen::Vector3f lod_eye_ = Eigen::Vector3f::Zero(), lod_forward_ = Eigen::Vector3f::UnitZ();
  std::map<const TriangleMesh*, CachedMesh> mesh_cache_;
  GLuint line_vao_ = 0, line_buffer_ = 0;
  GLuint shadow_fbo_ = 0, shadow_texture_ = 0;
  int shadow_size_ = 0;   // texels on a side of shadow_texture_
  Target target_, msaa_;  // Render()'s read-back target and its multisampled twin
  int target_w_ = 0, target_h_ = 0, target_samples_ = 0;
  Target cache_;  // CacheScene()'s image
  int cache_w_ = 0, cache_h_ = 0;
  // Per-frame scratch, reused between frames (no reallocation once sized).
  std::vector<Batch> opaque_;
  std::vector<std::pair<const GpuMesh*, Instance>> translucent_;
  std::vector<Instance> scratch_;
  std::unique_ptr<internal::OverlayPass> overlay_pass_;  // created on first use
};

}  // namespace render
