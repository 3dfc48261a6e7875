#include "app/viewer/scene_pacer.h"

#include <cstdint>
#include <cstring>

namespace app::ui {
namespace {

// FNV-1a, one 32-bit word at a time.
class Hasher {
 public:
  void Word(std::uint32_t w) {
    h_ ^= w;
    h_ *= 0x100000001b3ull;
  }
  void Int(long long v) {
    Word(static_cast<std::uint32_t>(v));
    Word(static_cast<std::uint32_t>(static_cast<unsigned long long>(v) >> 32));
  }
  void Floats(const float* f, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      std::uint32_t w;
      std::memcpy(&w, &f[i], sizeof w);
      Word(w);
    }
  }
  template <typename Matrix>
  void Dense(const Matrix& m) {
    Floats(m.data(), static_cast<size_t>(m.size()));
  }
  template <size_t N>
  void Array(const std::array<float, N>& a) {
    Floats(a.data(), N);
  }
  void Points(const std::vector<Eigen::Vector3f>& p) {
    Int(static_cast<long long>(p.size()));
    if (!p.empty()) Floats(p.front().data(), 3 * p.size());
  }
  void Surface(const render::Material& m) {
    Array(m.rgba);
    Floats(&m.specular, 1);
    Floats(&m.shininess, 1);
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t SceneHash(const render::Scene& scene) {
  Hasher h;
  h.Int(static_cast<long long>(scene.shapes.size()));
  for (const render::Shape& s : scene.shapes) {
    h.Int(static_cast<int>(s.kind));
    h.Dense(s.world_from_shape);
    h.Dense(s.size);
    h.Surface(s.material);
    // A mesh by identity (the renderer caches its upload by pointer too) and size.
    h.Int(static_cast<long long>(reinterpret_cast<std::uintptr_t>(s.mesh.get())));
    if (s.mesh) {
      h.Int(static_cast<long long>(s.mesh->positions.size()));
      h.Int(static_cast<long long>(s.mesh->indices.size()));
    }
  }
  h.Int(static_cast<long long>(scene.tubes.size()));
  for (const render::Tube& t : scene.tubes) {
    h.Points(t.points);
    h.Floats(&t.radius, 1);
    h.Floats(&t.bead_radius, 1);
    h.Surface(t.material);
    h.Int(static_cast<long long>(t.segment_colors.size()));
    for (const auto& c : t.segment_colors) h.Array(c);
  }
  h.Int(static_cast<long long>(scene.lines.size()));
  for (const render::Lines& l : scene.lines) {
    h.Points(l.points);
    h.Int(l.strip ? 1 : 0);
    h.Floats(&l.width, 1);
    h.Array(l.rgba);
  }
  const render::Grid& g = scene.grid;
  h.Int(g.enabled ? 1 : 0);
  h.Dense(g.center);
  h.Floats(&g.height, 1);
  h.Floats(&g.extent, 1);
  h.Floats(&g.spacing, 1);
  h.Array(g.plane_rgba);
  h.Array(g.line_rgba);
  h.Int(static_cast<long long>(scene.lights.size()));
  for (const render::Light& l : scene.lights) {
    h.Dense(l.direction);
    h.Array(l.rgb);
  }
  h.Array(scene.ambient);
  h.Array(scene.background);
  return h.value();
}

std::uint64_t ViewHash(const render::Camera& camera, int width, int height) {
  Hasher h;
  h.Dense(camera.eye);
  h.Dense(camera.target);
  h.Dense(camera.up);
  h.Floats(&camera.fovy_deg, 1);
  h.Floats(&camera.near_clip, 1);
  h.Floats(&camera.far_clip, 1);
  h.Int(width);
  h.Int(height);
  return h.value();
}

bool ScenePacer::Due(std::uint64_t content, std::uint64_t view, bool busy, bool force,
                     double now_s) const {
  if (force || !rendered_ || view != view_) return true;
  if (content == content_) return false;
  return !busy || now_s - last_s_ >= interval_s_;
}

void ScenePacer::Rendered(std::uint64_t content, std::uint64_t view, double now_s) {
  rendered_ = true;
  content_ = content;
  view_ = view;
  last_s_ = now_s;
  ++renders_;
}

}  // namespace app::ui
