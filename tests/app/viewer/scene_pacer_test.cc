// When the viewer renders its 3-D scene again (app/viewer/scene_pacer.h): only on changes, content
// changes rate-limited while the worker computes, view changes and screenshots at once.
#include "app/viewer/scene_pacer.h"

#include <gtest/gtest.h>

namespace app::ui {
namespace {

render::Scene TwoShapes() {
  render::Scene s;
  s.shapes.push_back(render::MakeSphere({0, 0, 1}, 0.1f, render::MakeMaterial(1, 0, 0)));
  s.shapes.push_back(render::MakeBox({1, 0, 0}, {0.2f, 0.2f, 0.2f}, render::MakeMaterial(0, 1, 0)));
  render::Tube t;
  t.points = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}};
  s.tubes.push_back(t);
  render::Lines l;
  l.points = {{0, 0, 0}, {1, 1, 1}};
  s.lines.push_back(l);
  s.grid.enabled = true;
  return s;
}

TEST(SceneHashTest, EqualScenesHashEqualAndEveryPartCounts) {
  const render::Scene a = TwoShapes();
  EXPECT_EQ(SceneHash(a), SceneHash(TwoShapes()));
  auto differs = [&](auto&& edit) {
    render::Scene b = TwoShapes();
    edit(&b);
    return SceneHash(b) != SceneHash(a);
  };
  EXPECT_TRUE(differs([](render::Scene* s) { s->shapes[0].world_from_shape(0, 3) += 1e-4f; }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->shapes[1].material.rgba[3] = 0.5f; }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->shapes.pop_back(); }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->tubes[0].points[2].z() = 1.5f; }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->tubes[0].radius = 0.02f; }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->lines[0].points.push_back({2, 2, 2}); }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->grid.enabled = false; }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->lights.emplace_back(); }));
  EXPECT_TRUE(differs([](render::Scene* s) { s->background[0] = 0.5f; }));
  render::Camera c;
  EXPECT_EQ(ViewHash(c, 640, 400), ViewHash(c, 640, 400));
  EXPECT_NE(ViewHash(c, 640, 400), ViewHash(c, 640, 401));
  render::Camera moved = c;
  moved.eye.x() += 0.01f;
  EXPECT_NE(ViewHash(c, 640, 400), ViewHash(moved, 640, 400));
}

TEST(ScenePacerTest, RendersOnChangesAndRateLimitsContentWhileBusy) {
  ScenePacer p(0.2);
  EXPECT_TRUE(p.Due(1, 10, false, false, 0.0));  // nothing cached yet
  p.Rendered(1, 10, 0.0);
  EXPECT_FALSE(p.Due(1, 10, false, false, 0.01));  // unchanged: reuse the image
  EXPECT_FALSE(p.Due(1, 10, true, false, 5.0));
  EXPECT_TRUE(p.Due(1, 10, false, true, 0.01));   // a screenshot always renders
  EXPECT_TRUE(p.Due(2, 10, false, false, 0.01));  // idle: content changes render at once
  EXPECT_TRUE(p.Due(1, 11, true, false, 0.01));   // camera/size: at once, also while busy
  EXPECT_FALSE(p.Due(2, 10, true, false, 0.1));   // busy: not before 0.2 s after the last
  EXPECT_TRUE(p.Due(2, 10, true, false, 0.2));
  p.Rendered(2, 10, 0.2);
  EXPECT_FALSE(p.Due(3, 10, true, false, 0.39));
  EXPECT_TRUE(p.Due(3, 10, true, false, 0.41));
  EXPECT_EQ(p.renders(), 2);
  ScenePacer every(0.0);
  every.Rendered(1, 10, 0.0);
  EXPECT_TRUE(every.Due(2, 10, true, false, 0.0));
}

}  // namespace
}  // namespace app::ui
