// The GL renderer: geometry lands where the pinhole model says, renders are deterministic and
// backend-independent, and the diff catches a one-bead change (label: snapshot, needs OSMesa).
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/diff.h"
#include "tests/render/gl_fixture.h"

namespace render {
namespace {

constexpr int kW = 320, kH = 240;

Camera TestCamera() {
  Camera c;
  c.eye = {2.5f, -2.0f, 1.5f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.fovy_deg = 40.0f;
  return c;
}

// Independent pinhole model: pixel (u, v) with rows top-down, pixel centres at +0.5.
Eigen::Vector2d Pinhole(const Camera& c, int w, int h, const Eigen::Vector3d& p) {
  const Eigen::Vector3d eye = c.eye.cast<double>();
  const Eigen::Vector3d forward = (c.target.cast<double>() - eye).normalized();
  const Eigen::Vector3d right = forward.cross(c.up.cast<double>()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const Eigen::Vector3d d = p - eye;
  const double f = 0.5 * h / std::tan(0.5 * c.fovy_deg * M_PI / 180.0);
  return {0.5 * w + f * d.dot(right) / d.dot(forward), 0.5 * h - f * d.dot(up) / d.dot(forward)};
}

bool IsBackground(const Image& img, int x, int y) {
  const std::uint8_t* p = img.at(x, y);
  return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

Scene Plain() {
  Scene s;
  s.background = {1.0f, 1.0f, 1.0f};
  return s;
}

RenderOptions NoShadows() {
  RenderOptions o;
  o.shadows = false;
  return o;
}

TEST(RendererTest, ReportsLlvmpipe) {
  const GlInfo info = testing::SharedRenderer().info();
  std::printf("GL_VERSION %s\nGL_RENDERER %s\n", info.version.c_str(), info.renderer.c_str());
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos)
      << "goldens were made with llvmpipe; set GALLIUM_DRIVER=llvmpipe";
}

TEST(RendererTest, SphereLandsOnThePinholePixel) {
  const Camera cam = TestCamera();
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, -0.3, 0.2), Eigen::Vector3d(-0.8, 0.6, -0.4),
        Eigen::Vector3d(0.3, 0.9, 0.5)}) {
    Scene s = Plain();
    s.shapes.push_back(MakeSphere(p.cast<float>(), 0.03f, MakeMaterial(0.8f, 0.1f, 0.1f)));
    const Image img = testing::SharedRenderer().Render(s, cam, kW, kH, NoShadows());
    double sx = 0, sy = 0;
    int n = 0;
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        if (!IsBackground(img, x, y)) {
          sx += x + 0.5;
          sy += y + 0.5;
          ++n;
        }
      }
    }
    ASSERT_GT(n, 10) << "sphere not visible at " << p.transpose();
    const Eigen::Vector2d want = Pinhole(cam, kW, kH, p);
    EXPECT_NEAR(sx / n, want.x(), 0.5) << p.transpose();
    EXPECT_NEAR(sy / n, want.y(), 0.5) << p.transpose();
    // The library's own projection agrees with the independent model.
    Eigen::Vector2f mine;
    ASSERT_TRUE(ProjectToPixel(cam, kW, kH, p.cast<float>(), &mine));
    EXPECT_NEAR(mine.x(), want.x(), 1e-3);
    EXPECT_NEAR(mine.y(), want.y(), 1e-3);
  }
}

TEST(RendererTest, TubeCoversItsProjectedSegment) {
  const Camera cam = TestCamera();
  const Eigen::Vector3d a(-0.8, -0.5, 0.1), b(0.7, 0.4, 0.3);
  Scene s = Plain();
  Tube t;
  t.points = {a.cast<float>(), b.cast<float>()};
  t.radius = 0.02f;
  t.material = MakeMaterial(0.1f, 0.3f, 0.8f);
  s.tubes.push_back(t);
  const Image img = testing::SharedRenderer().Render(s, cam, kW, kH, NoShadows());
  const Eigen::Vector2d pa = Pinhole(cam, kW, kH, a), pb = Pinhole(cam, kW, kH, b);
  const Eigen::Vector2d normal = Eigen::Vector2d(-(pb - pa).y(), (pb - pa).x()).normalized();
  for (int k = 0; k <= 20; ++k) {
    const double u = k / 20.0;
    const Eigen::Vector2d q = Pinhole(cam, kW, kH, a + u * (b - a));
    EXPECT_FALSE(IsBackground(img, static_cast<int>(q.x()), static_cast<int>(q.y())))
        << "t = " << u << " pixel " << q.transpose();
    // 12 pixels to the side there is nothing (the tube is ~5 px wide).
    const Eigen::Vector2d off = q + 12.0 * normal;
    EXPECT_TRUE(IsBackground(img, static_cast<int>(off.x()), static_cast<int>(off.y())));
  }
}

Scene BeadChain(int skip_bead) {
  Scene s = Plain();
  s.grid.enabled = true;
  Tube t;
  t.radius = 0.006f;
  t.material = MakeMaterial(0.3f, 0.3f, 0.3f);
  for (int i = 0; i < 24; ++i) {
    const float a = 6.2831853f * static_cast<float>(i) / 24.0f;
    t.points.emplace_back(0.6f * std::cos(a), 0.6f * std::sin(a), 0.4f + 0.1f * std::sin(3 * a));
    if (i != skip_bead) {
      s.shapes.push_back(MakeSphere(t.points.back(), 0.035f, MakeMaterial(0.9f, 0.5f, 0.1f)));
    }
  }
  s.tubes.push_back(t);
  return s;
}

TEST(RendererTest, RendersAreDeterministicAndTheDiffCatchesOneBead) {
  Renderer& r = testing::SharedRenderer();
  const Image a = r.Render(BeadChain(-1), TestCamera(), kW, kH);
  const Image a2 = r.Render(BeadChain(-1), TestCamera(), kW, kH);
  EXPECT_TRUE(SameImage(a, a2)) << "same scene rendered twice differs";
  EXPECT_TRUE(CompareImages(a, a2).passed);
  const Image b = r.Render(BeadChain(7), TestCamera(), kW, kH);
  const DiffResult d = CompareImages(a, b);
  EXPECT_FALSE(d.passed) << d.diff_pixels << " px";
  EXPECT_GT(d.diff_pixels, d.allowed);
}

TEST(RendererTest, MsaaRendersAndDiffersOnlyAtEdges) {
  Renderer& r = testing::SharedRenderer();
  RenderOptions msaa;
  msaa.msaa_samples = 4;
  const Image plain = r.Render(BeadChain(-1), TestCamera(), kW, kH);
  const Image smooth = r.Render(BeadChain(-1), TestCamera(), kW, kH, msaa);
  EXPECT_FALSE(SameImage(plain, smooth));
  const Image again = r.Render(BeadChain(-1), TestCamera(), kW, kH, msaa);
  EXPECT_TRUE(SameImage(smooth, again));
}

// A translucent panel-like quad over the left half, untextured.
Overlay HalfPanel() {
  Overlay o;
  o.vertices = {{0, 0, 0, 0, 0x80c08040u},
                {kW / 2.0f, 0, 0, 0, 0x80c08040u},
                {kW / 2.0f, kH, 0, 0, 0x80c08040u},
                {0, kH, 0, 0, 0x80c08040u}};
  o.indices = {0, 1, 2, 0, 2, 3};
  o.commands.push_back({0, 6, 0, 0, 0, kW, kH});
  return o;
}

TEST(RendererTest, CachedSceneEqualsAFreshRender) {
  {
    OffscreenContext context;
    Renderer fresh(context.proc_loader());
    EXPECT_THROW(fresh.ReadCachedScene(nullptr), std::logic_error);
    EXPECT_THROW(fresh.DrawCachedScene(0), std::logic_error);
  }
  Renderer& r = testing::SharedRenderer();
  const Overlay panel = HalfPanel();
  r.CacheScene(BeadChain(-1), TestCamera(), kW, kH);
  // Renders in between (another scene, another size) leave the cached image alone.
  r.Render(BeadChain(7), TestCamera(), kW / 2, kH / 2);
  const Image fresh = r.Render(BeadChain(-1), TestCamera(), kW, kH, {}, &panel);
  EXPECT_TRUE(SameImage(r.ReadCachedScene(&panel), fresh));
  EXPECT_TRUE(SameImage(r.ReadCachedScene(nullptr), r.Render(BeadChain(-1), TestCamera(), kW, kH)));
  RenderOptions msaa;
  msaa.msaa_samples = 4;
  r.CacheScene(BeadChain(-1), TestCamera(), kW, kH, msaa);
  EXPECT_TRUE(SameImage(r.ReadCachedScene(&panel),
                        r.Render(BeadChain(-1), TestCamera(), kW, kH, msaa, &panel)));
}

TEST(RendererTest, EglMatchesOsmesa) {
  Scene s = BeadChain(-1);
  const Image a = testing::SharedRenderer().Render(s, TestCamera(), kW, kH);
  std::unique_ptr<OffscreenContext> egl;
  try {
    egl = std::make_unique<OffscreenContext>(GlBackend::kEgl);
  } catch (const ContextError& e) {
    GTEST_SKIP() << "no EGL surfaceless context: " << e.what();
  }
  Image b;
  {
    Renderer r(egl->proc_loader());
    b = r.Render(s, TestCamera(), kW, kH);
  }
  egl.reset();
  EXPECT_TRUE(SameImage(a, b)) << CompareImages(a, b).changed_pixels << " pixels differ";
}

// Whether pixel k of a and b differ at all.
bool PixelDiffers(const Image& a, const Image& b, size_t k) {
  return !std::equal(a.rgba.begin() + 4 * k, a.rgba.begin() + 4 * k + 4, b.rgba.begin() + 4 * k);
}

// The shadow map's size changes shadow pixels only (pixels shadowed in one of the two renders),
// renders at each size are deterministic, and going back to the default size gives the default
// render again (the map is resized in place).
TEST(RendererTest, ShadowMapSizeChangesShadowPixelsOnly) {
  Renderer& r = testing::SharedRenderer();
  const Scene s = BeadChain(-1);
  RenderOptions small;
  small.shadow_map_size = 256;
  const Image big = r.Render(s, TestCamera(), kW, kH);
  const Image coarse = r.Render(s, TestCamera(), kW, kH, small);
  const Image none = r.Render(s, TestCamera(), kW, kH, NoShadows());
  EXPECT_TRUE(SameImage(coarse, r.Render(s, TestCamera(), kW, kH, small)));
  EXPECT_TRUE(SameImage(big, r.Render(s, TestCamera(), kW, kH)));
  int changed = 0, outside_shadows = 0;
  for (size_t k = 0; k < static_cast<size_t>(kW) * kH; ++k) {
    if (!PixelDiffers(big, coarse, k)) continue;
    ++changed;
    outside_shadows += !PixelDiffers(big, none, k) && !PixelDiffers(coarse, none, k);
  }
  EXPECT_GT(changed, 0);  // the map's resolution shows in the beads' shadows on the grid
  EXPECT_EQ(outside_shadows, 0);
  for (int bad : {0, 32, 100, 8192}) {
    RenderOptions o;
    o.shadow_map_size = bad;
    EXPECT_THROW(r.Render(s, TestCamera(), kW, kH, o), std::invalid_argument) << bad;
  }
}

TEST(RendererTest, BadSizesAndCamerasThrow) {
  Renderer& r = testing::SharedRenderer();
  EXPECT_THROW(r.Render(Plain(), TestCamera(), 0, 10), std::invalid_argument);
  Camera c = TestCamera();
  c.target = c.eye;
  EXPECT_THROW(r.Render(Plain(), c, 10, 10), std::invalid_argument);
  c = TestCamera();
  c.fovy_deg = 190.0f;
  EXPECT_THROW(r.Render(Plain(), c, 10, 10), std::invalid_argument);
}

}  // namespace
}  // namespace render
