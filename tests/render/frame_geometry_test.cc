// The screen rectangle of the ground that light 0 can shadow (render/internal/frame_geometry.h:
// GroundShadowRect), which lets the renderer skip shadow lookups on the rest of the grid.
#include "render/internal/frame_geometry.h"

#include <gtest/gtest.h>

#include <random>

#include "render/renderer.h"

namespace render::internal {
namespace {

constexpr int kW = 640, kH = 480;

Eigen::Matrix4f ViewProj(const Camera& c) {
  return ProjectionMatrix(c, static_cast<float>(kW) / kH, 0.1f, 50.0f) * ViewMatrix(c);
}

Camera LookingDown() {
  Camera c;
  c.eye = {3.0f, -3.0f, 2.5f};
  c.target = {0.0f, 0.0f, 0.3f};
  return c;
}

Bounds Box(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  Bounds b;
  b.Add(lo, 0.0f);
  b.Add(hi, 0.0f);
  return b;
}

bool Contains(const PixelRect& r, const Eigen::Vector2f& gl_pixel) {
  return gl_pixel.x() >= static_cast<float>(r.x0) && gl_pixel.x() <= static_cast<float>(r.x1) &&
         gl_pixel.y() >= static_cast<float>(r.y0) && gl_pixel.y() <= static_cast<float>(r.y1);
}

TEST(GroundShadowRectTest, ContainsTheShadowOfEveryCasterPointAndNotTheWholeImage) {
  const Camera cam = LookingDown();
  const Eigen::Vector3f light = Eigen::Vector3f(0.4f, 0.3f, 1.0f).normalized();
  const Bounds casters = Box({-0.2f, -0.1f, 0.1f}, {0.3f, 0.2f, 0.9f});
  const PixelRect r = GroundShadowRect(casters, 0.01f, light, 0.0f, ViewProj(cam), kW, kH);
  ASSERT_FALSE(r.empty());
  EXPECT_LT((r.x1 - r.x0) * (r.y1 - r.y0), kW * kH / 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3f p =
        casters.lo +
        (casters.hi - casters.lo).cwiseProduct(Eigen::Vector3f(u(rng), u(rng), u(rng)));
    const Eigen::Vector3f ground = p - light * (p.z() / light.z());
    Eigen::Vector2f pixel;  // top-down rows; the rectangle is in GL rows (bottom-up)
    ASSERT_TRUE(ProjectToPixel(cam, kW, kH, ground, &pixel));
    EXPECT_TRUE(Contains(r, {pixel.x(), static_cast<float>(kH) - pixel.y()}))
        << "ground point " << ground.transpose() << " at pixel " << pixel.transpose();
  }
}

TEST(GroundShadowRectTest, ConservativeOrEmptyInTheHardCases) {
  const Camera cam = LookingDown();
  const Eigen::Matrix4f vp = ViewProj(cam);
  const PixelRect all{0, 0, kW, kH};
  const Bounds casters = Box({-0.2f, -0.2f, 0.1f}, {0.2f, 0.2f, 0.5f});
  EXPECT_TRUE(GroundShadowRect(Bounds{}, 0.01f, {0, 0, 1}, 0.0f, vp, kW, kH).empty());
  // Light at or below the horizon: the shadows can reach anywhere.
  EXPECT_EQ(GroundShadowRect(casters, 0.01f, {1, 0, 0}, 0.0f, vp, kW, kH), all);
  EXPECT_EQ(
      GroundShadowRect(casters, 0.01f, Eigen::Vector3f(1, 0, -0.5f).normalized(), 0.0f, vp, kW, kH),
      all);
  // Shadow region reaching behind the camera (a long shadow from a low light towards it).
  const Eigen::Vector3f low = Eigen::Vector3f(-1.0f, 1.0f, 0.1f).normalized();
  EXPECT_EQ(
      GroundShadowRect(Box({-0.2f, -0.2f, 0.1f}, {0.2f, 0.2f, 3.0f}), 0.01f, low, 0.0f, vp, kW, kH),
      all);
  // Casters far off to the right, in front of the camera, under an overhead light: no shadow on
  // screen.
  EXPECT_TRUE(GroundShadowRect(Box({20.0f, 20.0f, 0.1f}, {21.0f, 21.0f, 0.5f}), 0.01f, {0, 0, 1},
                               0.0f, vp, kW, kH)
                  .empty());
}

}  // namespace
}  // namespace render::internal
