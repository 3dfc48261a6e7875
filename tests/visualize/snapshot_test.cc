// Golden images (snapshots/<suite>/<case>.png, at most 320x240) produced through the same code as
// the CLI: scene files via app::LoadSceneFile, heatmaps via app::WritheHeatmapFigure /
// app::WritheFigure, plots via render::RenderPlot, render::PanelsFigure and render::BarChartFigure.
// UPDATE_SNAPSHOTS=1 rewrites them; failures write actual/expected/diff images into
// <build>/snapshot-diff/<suite>/.
#include <gtest/gtest.h>

#include <cmath>

#include "visualize/figures.h"
#include "visualize/scene_builder.h"
#include "visualize/scene_file.h"
#include "planning/robot/mesh_io.h"
#include "render/diff.h"
#include "render/plot.h"
#include "tests/render/gl_fixture.h"
#include "topology/polyline.h"
#include "topology/writhe.h"

namespace render {
namespace {

constexpr int kW = 320, kH = 240;

void ExpectSnapshot(const Image& image, const std::string& suite, const std::string& name) {
  const std::string golden =
      std::string(TOPOPLAN_SOURCE_DIR) + "/snapshots/" + suite + "/" + name + ".png";
  const std::string artefacts = std::string(TOPOPLAN_BINARY_DIR) + "/snapshot-diff/" + suite;
  const SnapshotResult r = CheckSnapshot(image, golden, artefacts);
  EXPECT_TRUE(r.passed) << suite << "/" << name << ": " << r.message;
  std::printf("%s/%s: %s\n", suite.c_str(), name.c_str(), r.message.c_str());
}

TEST(SnapshotTest, ExampleSceneWithChainsAndPrimitives) {
  const visualize::SceneDocument doc =
      visualize::LoadSceneFile(TOPOPLAN_SOURCE_DIR "/assets/scenes/example.json");
  ExpectSnapshot(testing::SharedRenderer().Render(doc.scene, doc.camera, kW, kH), "render",
                 "scene_example");
}

TEST(SnapshotTest, TorusMesh) {
  Scene s;
  s.grid.enabled = true;
  s.grid.extent = 3.0f;
  Shape torus;
  torus.kind = Shape::Kind::kMesh;
  torus.mesh =
      visualize::ToRenderMesh(planning::LoadMesh(TOPOPLAN_SOURCE_DIR "/assets/scenes/torus.obj"));
  torus.world_from_shape.block<3, 1>(0, 3) = Eigen::Vector3f(0, 0, 0.6f);
  torus.world_from_shape.block<3, 3>(0, 0) =
      Eigen::AngleAxisf(0.6f, Eigen::Vector3f::UnitX()).toRotationMatrix();
  torus.material = MakeMaterial(0.55f, 0.4f, 0.75f);
  s.shapes.push_back(torus);
  Camera cam;
  cam.eye = {3.4f, -3.7f, 2.9f};
  cam.target = {0, 0, 0.3f};
  cam.fovy_deg = 40.0f;
  ExpectSnapshot(testing::SharedRenderer().Render(s, cam, kW, kH), "render", "mesh_torus");
}

TEST(SnapshotTest, HopfLinkHeatmap) {
  const topology::Chain a = topology::ReadChainCsv(TOPOPLAN_SOURCE_DIR "/assets/chains/hopf_a.csv");
  const topology::Chain b = topology::ReadChainCsv(TOPOPLAN_SOURCE_DIR "/assets/chains/hopf_b.csv");
  const Eigen::MatrixXd w = topology::WritheMatrix(a, b);
  ASSERT_NEAR(w.sum(), -1.0, 1e-9);
  ExpectSnapshot(visualize::WritheHeatmapFigure(w, "hopf_a", "hopf_b", kW, kH), "figures",
                 "heatmap_hopf");
}

// A 20x1 matrix (arm against a one-segment pole) is a strip with named axes and its peak marked.
TEST(SnapshotTest, StripHeatmapWithPeak) {
  Eigen::MatrixXd w(20, 1);
  for (int i = 0; i < 20; ++i) w(i, 0) = 0.04 * std::sin(0.5 * i) - 0.002 * i;
  visualize::WritheFigureOptions f;
  f.width = kW;
  f.height = kH;
  f.row_label = "Arm segment";
  f.col_label = "Pole segment";
  f.mark_peak = true;
  ExpectSnapshot(visualize::WritheFigure(w, "arm", "pole", f).Raster(), "figures", "heatmap_strip");
}

// Two panels with their own axes (writhe and cost over time) and grouped bars with whiskers.
TEST(SnapshotTest, PanelsAndBars) {
  std::vector<double> t, writhe, cost;
  for (int k = 0; k <= 50; ++k) {
    t.push_back(0.1 * k);
    writhe.push_back(-2.0 * std::exp(-0.08 * k));
    cost.push_back(300.0 * std::exp(-0.15 * k) + 5.0);
  }
  PlotPanel top, bottom;
  top.series = {PlotSeries("", t, writhe)};
  top.series[0].marker = Marker::kNone;
  top.axes.y_label = "Total writhe (turns)";
  top.axes.legend = LegendPosition::kNone;
  bottom.series = {PlotSeries("", t, cost)};
  bottom.series[0].marker = Marker::kNone;
  bottom.series[0].rgba = {214, 39, 40, 255};
  bottom.axes.x_label = "Time (s)";
  bottom.axes.y_label = "Task cost";
  bottom.axes.y_min = 0.0;
  bottom.axes.legend = LegendPosition::kNone;
  PanelLayout layout;
  layout.width = kW;
  layout.height = kH;
  ExpectSnapshot(PanelsFigure({top, bottom}, layout).Raster(), "figures", "plot_panels");

  BarChart chart;
  chart.categories = {"power", "pinch", "tripod"};
  BarSeries a, b;
  a.label = "winding";
  a.values = {6, 4, 5};
  a.lo = {5, 2, NAN};
  a.hi = {6, 5, NAN};
  b.label = "joint";
  b.values = {3, 0, 6};
  chart.series = {a, b};
  PlotOptions o;
  o.width = kW;
  o.height = kH;
  o.y_label = "Directions held";
  o.y_min = 0;
  o.y_max = 6;
  o.legend = LegendPosition::kOutsideRight;
  ExpectSnapshot(BarChartFigure(chart, o).Raster(), "figures", "plot_bars");
}

TEST(SnapshotTest, UnwrapPlotWithFailures) {
  std::vector<PlotSeries> series(3);
  series[0].label = "AICO";
  series[1].label = "BiRRT";
  series[1].marker = Marker::kSquare;
  series[2].label = "RRT";
  series[2].marker = Marker::kTriangle;
  for (int k = 0; k <= 8; ++k) {
    const double angle = 90.0 * k;
    series[0].x.push_back(angle);
    series[0].y.push_back(200.0 + 30.0 * k);
    series[1].x.push_back(angle);
    series[1].y.push_back(800.0 * std::exp(0.55 * k));
    if (k <= 4) {
      series[2].x.push_back(angle);
      series[2].y.push_back(1500.0 * std::exp(0.9 * k));
    } else {
      series[2].failure_x.push_back(angle);
    }
  }
  PlotOptions o;
  o.width = kW;
  o.height = kH;
  o.log_y = true;
  o.title = "Collision checks vs angle to unwrap";
  o.x_label = "Angle to unwrap (deg)";
  o.y_label = "Collision checks";
  ExpectSnapshot(RenderPlot(series, o), "figures", "plot_unwrap");
}

}  // namespace
}  // namespace render
