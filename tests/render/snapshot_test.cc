// Golden images (snapshots/<suite>/<case>.png, 320x240) produced through the same code as the
// CLI: scene files via app::LoadSceneFile, heatmaps via app::WritheHeatmapFigure, plots via
// render::RenderPlot. UPDATE_SNAPSHOTS=1 rewrites them; failures write actual/expected/diff
// images into <build>/snapshot-diff/<suite>/.
#include <gtest/gtest.h>

#include <cmath>

#include "app/figures.h"
#include "app/scene_builder.h"
#include "app/scene_json.h"
#include "planning/mesh_io.h"
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
  const app::SceneDocument doc =
      app::LoadSceneFile(TOPOPLAN_SOURCE_DIR "/assets/scenes/example.json");
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
      app::ToRenderMesh(planning::LoadMesh(TOPOPLAN_SOURCE_DIR "/assets/scenes/torus.obj"));
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
  ExpectSnapshot(app::WritheHeatmapFigure(w, "hopf_a", "hopf_b", kW, kH), "figures",
                 "heatmap_hopf");
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
  o.x_label = "angle to unwrap [deg]";
  o.y_label = "collision checks";
  ExpectSnapshot(RenderPlot(series, o), "figures", "plot_unwrap");
}

}  // namespace
}  // namespace render
