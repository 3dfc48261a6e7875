// Rendering benchmarks (README target: a 1280x720 frame of arm + hand + chains <= 40 ms with
// readback; PNG write <= 30 ms). Run: build/tests/bench/bench_render
//
// The scene imitates the robot scenes: an 8-link arm of capsules, a 5-finger hand of 10 capsules,
// a 16-bead closed chain, a box and the ground grid -- about 55k triangles at the finest
// tessellation (the "triangles" counter; levels of detail draw about 15k at 1280x720, and back
// faces are culled). BM_RenderFrame's "cpu_all_ms" counter is the process CPU time per frame over
// all threads (llvmpipe rasterises on its own threads; the CPU column is the calling thread only).
#include <benchmark/benchmark.h>
#include <stb_image_write.h>
#include <time.h>

#include <cmath>
#include <string>

#include "render/diff.h"
#include "render/heatmap.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"

namespace {

using render::Image;

// Triangles per primitive in render/internal/tessellate.cc (32 slices, 16 stacks).
constexpr int kSphereTris = 32 * 2 * 16 - 2 * 32;
constexpr int kCylinderTris = 32 * 2 + 2 * 32;

render::Scene BenchScene(int* triangles) {
  render::Scene s;
  s.grid.enabled = true;
  int tris = 2;
  Eigen::Vector3f p(0, 0, 0);
  for (int i = 0; i < 8; ++i) {  // arm
    const Eigen::Vector3f q =
        p + Eigen::Vector3f(0.12f * std::cos(0.7f * i), 0.12f * std::sin(0.7f * i), 0.18f);
    s.shapes.push_back(render::MakeCapsule(p, q, 0.05f, render::MakeMaterial(0.9f, 0.55f, 0.2f)));
    tris += kCylinderTris + 2 * kSphereTris;
    p = q;
  }
  for (int f = 0; f < 5; ++f) {  // hand
    Eigen::Vector3f a = p;
    for (int k = 0; k < 2; ++k) {
      const float ang = -0.8f + 0.4f * f;
      const Eigen::Vector3f b =
          a + Eigen::Vector3f(0.05f * std::cos(ang), 0.05f * std::sin(ang), 0.02f);
      s.shapes.push_back(
          render::MakeCapsule(a, b, 0.012f, render::MakeMaterial(0.3f, 0.3f, 0.35f)));
      tris += kCylinderTris + 2 * kSphereTris;
      a = b;
    }
  }
  render::Tube chain;  // closed chain around the arm
  chain.radius = 0.01f;
  chain.bead_radius = 0.02f;
  chain.material = render::MakeMaterial(0.2f, 0.4f, 0.85f);
  for (int i = 0; i <= 16; ++i) {
    const float t = 6.2831853f * static_cast<float>(i) / 16.0f;
    chain.points.emplace_back(0.4f * std::cos(t), 0.4f * std::sin(t),
                              0.6f + 0.1f * std::sin(3 * t));
  }
  tris += 16 * kCylinderTris + 17 * kSphereTris;
  s.tubes.push_back(chain);
  s.shapes.push_back(render::MakeBox({0.6f, 0.5f, 0.1f}, {0.2f, 0.2f, 0.2f},
                                     render::MakeMaterial(0.4f, 0.7f, 0.4f)));
  tris += 12;
  *triangles = tris;
  return s;
}

render::Camera BenchCamera() {
  render::Camera c;
  c.eye = {2.0f, -2.2f, 1.6f};
  c.target = {0.1f, 0.1f, 0.6f};
  c.fovy_deg = 40.0f;
  return c;
}

struct Gl {
  render::OffscreenContext context;
  render::Renderer renderer{context.proc_loader()};
};

// CPU seconds of the whole process (every thread, llvmpipe's rasteriser threads included).
double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Gl& SharedGl() {
  static Gl gl;
  gl.context.MakeCurrent();
  return gl;
}

// Render + readback of a 50k-triangle frame. Args: width, height, msaa samples, shadows (0/1),
// shadow-map size.
void BM_RenderFrame(benchmark::State& state) {
  Gl& gl = SharedGl();
  int triangles = 0;
  const render::Scene scene = BenchScene(&triangles);
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  render::RenderOptions options;
  options.msaa_samples = static_cast<int>(state.range(2));
  options.shadows = state.range(3) != 0;
  options.shadow_map_size = static_cast<int>(state.range(4));
  benchmark::DoNotOptimize(gl.renderer.Render(scene, BenchCamera(), w, h, options));  // JIT warm-up
  const double cpu0 = ProcessCpuSeconds();
  for (auto _ : state) {
    Image img = gl.renderer.Render(scene, BenchCamera(), w, h, options);
    benchmark::DoNotOptimize(img.rgba.data());
  }
  state.counters["triangles"] = triangles;
  // The "CPU" column is the calling thread only; this is the frame's CPU over all threads, ms.
  state.counters["cpu_all_ms"] = benchmark::Counter(1e3 * (ProcessCpuSeconds() - cpu0) /
                                                    static_cast<double>(state.iterations()));
}
BENCHMARK(BM_RenderFrame)
    ->ArgNames({"w", "h", "msaa", "shadows", "map"})
    ->Args({1280, 720, 0, 1, 1024})
    ->Args({1280, 720, 0, 0, 1024})
    ->Args({1280, 720, 4, 1, 1024})
    ->Args({640, 480, 0, 1, 1024})
    ->Args({480, 360, 0, 1, 1024})  // the grasp frames: before and with their 512² map
    ->Args({480, 360, 0, 1, 512})
    ->Args({480, 360, 0, 0, 1024})
    ->Args({320, 240, 0, 1, 1024})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

const Image& Frame720() {
  static const Image img = [] {
    int triangles = 0;
    return SharedGl().renderer.Render(BenchScene(&triangles), BenchCamera(), 1280, 720);
  }();
  return img;
}

// libpng with the project's settings (zlib level = arg, "sub" filter).
void BM_PngWriteLibpng(benchmark::State& state) {
  const Image& img = Frame720();
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string png = render::EncodePng(img, static_cast<int>(state.range(0)));
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_PngWriteLibpng)->Arg(1)->Arg(2)->Arg(6)->Unit(benchmark::kMillisecond);

// stb_image_write at its defaults, for comparison (what the issue warns about).
void BM_PngWriteStbDefault(benchmark::State& state) {
  const Image& img = Frame720();
  size_t bytes = 0;
  for (auto _ : state) {
    std::string png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
          static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                     static_cast<size_t>(size));
        },
        &png, img.width, img.height, 4, img.rgba.data(), img.width * 4);
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_PngWriteStbDefault)->Unit(benchmark::kMillisecond);

void BM_DecodePng(benchmark::State& state) {
  const std::string png = render::EncodePng(Frame720());
  for (auto _ : state) benchmark::DoNotOptimize(render::DecodePng(png, "bench").rgba.data());
}
BENCHMARK(BM_DecodePng)->Unit(benchmark::kMillisecond);

void BM_CompareImages(benchmark::State& state) {
  const Image& a = Frame720();
  Image b = a;
  for (int y = 100; y < 110; ++y) {
    for (int x = 100; x < 110; ++x) b.at(x, y)[0] ^= 0x80;
  }
  for (auto _ : state) benchmark::DoNotOptimize(render::CompareImages(a, b).diff_pixels);
}
BENCHMARK(BM_CompareImages)->Unit(benchmark::kMillisecond);

void BM_Heatmap64x64(benchmark::State& state) {
  Eigen::MatrixXd w(64, 64);
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) w(i, j) = std::sin(0.2 * i) * std::cos(0.15 * j);
  }
  render::HeatmapOptions o;
  o.title = "bench";
  for (auto _ : state) benchmark::DoNotOptimize(render::RenderHeatmap(w, o).rgba.data());
}
BENCHMARK(BM_Heatmap64x64)->Unit(benchmark::kMillisecond);

void BM_Plot(benchmark::State& state) {
  std::vector<render::PlotSeries> series(3);
  for (int s = 0; s < 3; ++s) {
    series[s].label = "series " + std::to_string(s);
    for (int k = 0; k < 50; ++k) {
      series[s].x.push_back(k);
      series[s].y.push_back(std::exp(0.05 * (s + 1) * k));
    }
  }
  render::PlotOptions o;
  o.log_y = true;
  o.title = "bench";
  for (auto _ : state) benchmark::DoNotOptimize(render::RenderPlot(series, o).rgba.data());
}
BENCHMARK(BM_Plot)->Unit(benchmark::kMillisecond);

}  // namespace
