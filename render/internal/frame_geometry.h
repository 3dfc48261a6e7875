// Per-frame geometry of the scene renderer, pure CPU: camera validation, the bounding sphere of
// the drawn objects, automatic near/far clip distances, the lights of a frame (the scene's or a
// default camera rig) and the orthographic view-projection of the shadow map.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "render/internal/instance.h"
#include "render/scene.h"

namespace render::internal {

// Throws std::invalid_argument for eye == target, up parallel to the view direction (or not
// finite) or fovy_deg outside (0, 180).
void CheckCamera(const Camera& camera);

// Sphere enclosing `bounds` (world frame): the box centre and half its diagonal (at least 1e-3);
// centre 0 and radius 1 when the bounds are empty.
struct BoundingSphere {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  float radius = 1.0f;
};
BoundingSphere SphereAround(const Bounds& bounds);

// `bounds` plus the four corners of an enabled ground grid (the grid only affects clipping; it
// is large and flat, so shadows fit the objects alone).
Bounds WithGrid(const Bounds& bounds, const Grid& grid);

// Near and far clip distances (world units along the view direction).
struct ClipRange {
  float near_clip, far_clip;
};
// The camera's own near/far when 0 < near < far. Otherwise a near <= 0 is replaced by the fitted
// near and then a far <= near by the fitted far, fitted to the sphere around `clip_bounds`
// (centre at depth d along the view direction, radius r): far = 1.05 max(d + r, 0.01),
// near = max(0.95 (d - r), far / 1000); both 1 when the bounds are empty.
ClipRange FrameClipRange(const Camera& camera, const Bounds& clip_bounds);

// The scene's lights, or when there are none a key and a fill light attached to the camera;
// at most 4, directions normalised (zero directions stay zero).
std::vector<Light> FrameLights(const Scene& scene, const Camera& camera);

// Clip from world for the shadow map of a light along unit `direction` (towards the light):
// an orthographic box of half-width `radius` seen from centre + 2 radius direction, depth range
// [0.5 radius, 3.5 radius].
Eigen::Matrix4f LightViewProjection(const BoundingSphere& sphere, const Eigen::Vector3f& direction);

// A rectangle of pixels in GL window coordinates (x right, y up from the bottom row): columns
// x0 <= x < x1, rows y0 <= y < y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool operator==(const PixelRect&) const = default;
};

// Pixels of a width x height image (clip from world `view_proj`) where the ground plane
// z = plane_height can lie in the shadow of `casters` (bounds of everything drawn into the
// shadow map) from a light along unit `direction` (towards the light): the screen bounds of the
// casters' box, grown by `margin` (the shadow map's filter reach, world units), projected along
// the light onto the plane, plus one pixel. Conservative: the whole image when the light is
// within ~3 degrees of the horizon or below it, or when that region reaches behind the camera;
// empty when there are no casters or the region is off screen.
PixelRect GroundShadowRect(const Bounds& casters, float margin, const Eigen::Vector3f& direction,
                           float plane_height, const Eigen::Matrix4f& view_proj, int width,
                           int height);

}  // namespace render::internal
