// Trajectory framing and task-region drawing of app/scene_builder.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "visualize/scene_builder.h"

namespace app {
namespace {

// Pixel (u, v) of world point p for `camera` in a width x height image (render/scene.h model).
Eigen::Vector2f Project(const render::Camera& c, const Eigen::Vector3f& p, int width, int height) {
  const Eigen::Vector3f back = (c.eye - c.target).normalized();
  const Eigen::Vector3f right = c.up.cross(back).normalized();
  const Eigen::Vector3f up = back.cross(right);
  const Eigen::Vector3f d = p - c.eye;
  const float f = 0.5f * height / std::tan(0.5f * c.fovy_deg * static_cast<float>(M_PI) / 180.0f);
  const float depth = -d.dot(back);
  return {0.5f * width + f * d.dot(right) / depth, 0.5f * height - f * d.dot(up) / depth};
}

TEST(SceneFramesTest, FitSceneCameraFillsTheImageWithEveryShape) {
  // A long thin "swept volume" away from the origin: spheres along a line across the view
  // (nearly perpendicular to the viewing direction (1, −1.3, 0.8)).
  render::Scene scene;
  std::vector<Eigen::Vector3f> centres;
  for (int k = 0; k <= 20; ++k) {
    centres.emplace_back(2.0f + 0.05f * k, 1.0f + 0.0385f * k, 0.5f + 0.02f * k);
    scene.shapes.push_back(
        render::MakeSphere(centres.back(), 0.02f, render::MakeMaterial(1, 0, 0)));
  }
  const int w = 640, h = 480;
  const render::Camera c =
      visualize::FitSceneCamera(scene, Eigen::Vector3f(1.0f, -1.3f, 0.8f), 35.0f, float(w) / h);
  float min_u = 1e9f, max_u = -1e9f, min_v = 1e9f, max_v = -1e9f;
  for (const Eigen::Vector3f& p : centres) {
    const Eigen::Vector2f px = Project(c, p, w, h);
    min_u = std::min(min_u, px.x());
    max_u = std::max(max_u, px.x());
    min_v = std::min(min_v, px.y());
    max_v = std::max(max_v, px.y());
  }
  EXPECT_GT(min_u, 0.0f);
  EXPECT_LT(max_u, w);
  EXPECT_GT(min_v, 0.0f);
  EXPECT_LT(max_v, h);
  // Tight: the geometry spans most of the image in at least one direction.
  EXPECT_GT(std::max((max_u - min_u) / w, (max_v - min_v) / h), 0.75f);
}

TEST(SceneFramesTest, TaskBoxesAreTranslucentBoxesWithTwelveEdges) {
  planning::ScenarioSpec spec;
  planning::TaskSpec box;
  box.feature.type = planning::FeatureType::kBox;
  box.feature.center = Eigen::Vector3d(0.7, 0.0, 0.9);
  box.feature.half_extent = Eigen::Vector3d(0.1, 0.2, 0.3);
  spec.tasks = {planning::TaskSpec{}, box};
  render::Scene scene;
  visualize::AddTaskBoxes(spec, &scene);
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_EQ(scene.shapes[0].kind, render::Shape::Kind::kBox);
  EXPECT_TRUE(scene.shapes[0].size.isApprox(Eigen::Vector3f(0.2f, 0.4f, 0.6f)));
  EXPECT_LT(scene.shapes[0].material.rgba[3], 0.5f);
  ASSERT_EQ(scene.lines.size(), 1u);
  ASSERT_EQ(scene.lines[0].points.size(), 24u);
  for (const Eigen::Vector3f& p : scene.lines[0].points) {
    const Eigen::Vector3f d = (p - Eigen::Vector3f(0.7f, 0.0f, 0.9f)).cwiseAbs();
    EXPECT_NEAR(d.x(), 0.1f, 1e-6f);
    EXPECT_NEAR(d.y(), 0.2f, 1e-6f);
    EXPECT_NEAR(d.z(), 0.3f, 1e-6f);
  }
}

}  // namespace
}  // namespace app
