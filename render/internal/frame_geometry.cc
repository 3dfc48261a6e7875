// Camera checks, clip distances, lights and the shadow-map projection of a frame (see
// frame_geometry.h).
#include "render/internal/frame_geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/numbers.h"
#include "render/renderer.h"

namespace render::internal {

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
                                base::FormatShortest(camera.fovy_deg));
  }
}

BoundingSphere SphereAround(const Bounds& bounds) {
  BoundingSphere s;
  if (!bounds.empty()) {
    s.centre = 0.5f * (bounds.lo + bounds.hi);
    s.radius = std::max(0.5f * (bounds.hi - bounds.lo).norm(), 1e-3f);
  }
  return s;
}

Bounds WithGrid(const Bounds& bounds, const Grid& grid) {
  Bounds clip_bounds = bounds;
  if (grid.enabled) {
    const float h = 0.5f * grid.extent;
    for (float sx : {-h, h}) {
      for (float sy : {-h, h}) {
        clip_bounds.Add(Eigen::Vector3f(grid.center.x() + sx, grid.center.y() + sy, grid.height),
                        0.0f);
      }
    }
  }
  return clip_bounds;
}

ClipRange FrameClipRange(const Camera& camera, const Bounds& clip_bounds) {
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
  return {near_clip, far_clip};
}

std::vector<Light> FrameLights(const Scene& scene, const Camera& camera) {
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
  return lights;
}

Eigen::Matrix4f LightViewProjection(const BoundingSphere& sphere,
                                    const Eigen::Vector3f& direction) {
  const Eigen::Vector3f& centre = sphere.centre;
  const float radius = sphere.radius;
  Camera light_cam;
  light_cam.eye = centre + 2.0f * radius * direction;
  light_cam.target = centre;
  light_cam.up =
      std::abs(direction.z()) < 0.95f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
  Eigen::Matrix4f ortho = Eigen::Matrix4f::Identity();
  const float n = 0.5f * radius, f = 3.5f * radius;
  ortho(0, 0) = 1.0f / radius;
  ortho(1, 1) = 1.0f / radius;
  ortho(2, 2) = -2.0f / (f - n);
  ortho(2, 3) = -(f + n) / (f - n);
  return ortho * ViewMatrix(light_cam);
}

PixelRect GroundShadowRect(const Bounds& casters, float margin, const Eigen::Vector3f& direction,
                           float plane_height, const Eigen::Matrix4f& view_proj, int width,
                           int height) {
  const PixelRect all{0, 0, width, height};
  if (casters.empty()) return {};
  if (!(direction.z() > 0.05f)) return all;
  const Eigen::Vector3f lo = casters.lo - Eigen::Vector3f::Constant(margin);
  const Eigen::Vector3f hi = casters.hi + Eigen::Vector3f::Constant(margin);
  // The shadow region on the plane lies in the convex hull of the box corners projected along
  // the light; its image lies in the hull of the corners' images while all are in front of the
  // camera (w > 0).
  float u0 = 1e30f, v0 = 1e30f, u1 = -1e30f, v1 = -1e30f;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3f p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                            (corner & 4) ? hi.z() : lo.z());
    const Eigen::Vector3f on_plane = p - direction * ((p.z() - plane_height) / direction.z());
    const Eigen::Vector4f c = view_proj * on_plane.homogeneous();
    if (!(c.w() > 1e-6f)) return all;
    const float u = (0.5f * c.x() / c.w() + 0.5f) * static_cast<float>(width);
    const float v = (0.5f * c.y() / c.w() + 0.5f) * static_cast<float>(height);
    if (!std::isfinite(u) || !std::isfinite(v)) return all;
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  // To whole pixels, one more on every side, clamped to the image (in float first: no overflow).
  const auto to_pixel = [](float x, int size) {
    return static_cast<int>(std::clamp(x, 0.0f, static_cast<float>(size)));
  };
  PixelRect r;
  r.x0 = to_pixel(std::floor(u0) - 1.0f, width);
  r.x1 = to_pixel(std::ceil(u1) + 1.0f, width);
  r.y0 = to_pixel(std::floor(v0) - 1.0f, height);
  r.y1 = to_pixel(std::ceil(v1) + 1.0f, height);
  return r.empty() ? PixelRect{} : r;
}

}  // namespace render::internal
