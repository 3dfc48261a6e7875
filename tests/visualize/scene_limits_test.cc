// Limits of scene files (app/scene_json.h): shape count, chain and line points, mesh triangles,
// chain-file values beyond single precision and quaternions near the float limit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "visualize/scene_file.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string ErrorOf(const json& doc, const std::string& base_dir = ".") {
  try {
    visualize::ParseSceneJson(doc, "s.json", base_dir);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

// {"shapes": [shape, shape, ...]} with n copies.
json Shapes(const json& shape, size_t n) {
  json doc = {{"shapes", json::array()}};
  for (size_t i = 0; i < n; ++i) doc["shapes"].push_back(shape);
  return doc;
}

json Points(size_t n) {
  json pts = json::array();
  for (size_t i = 0; i < n; ++i) pts.push_back({static_cast<double>(i), 0.0, 0.0});
  return pts;
}

TEST(SceneLimits, ShapeCountIsCheckedBeforeParsingAny) {
  const json sphere = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}};
  EXPECT_EQ(ErrorOf(Shapes(sphere, visualize::kMaxSceneShapes)), "(no error)");
  EXPECT_EQ(ErrorOf(Shapes(sphere, visualize::kMaxSceneShapes + 1)),
            "s.json: shapes: 1001 shapes, more than 1000 (limit)");
}

TEST(SceneLimits, ChainAndLinePointsCountTogether) {
  const json half = {{"type", "chain"}, {"points", Points(visualize::kMaxScenePoints / 2)}, {"radius", 0.1}};
  EXPECT_EQ(ErrorOf(Shapes(half, 2)), "(no error)");
  json doc = Shapes(half, 2);
  doc["shapes"].push_back({{"type", "lines"}, {"points", Points(2)}});
  EXPECT_EQ(ErrorOf(doc),
            "s.json: shapes[2].points: more than 100000 chain and line points (limit)");
}

fs::path TempDir() {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "scene_limits";
  fs::create_directories(dir);
  return dir;
}

TEST(SceneLimits, MeshTrianglesCountEveryReferenceOfOneFileReadOnce) {
  // A 100 x 50 grid of 10 000 triangles: 200 references fit 2 000 000 triangles, 201 do not.
  const fs::path obj = TempDir() / "grid.obj";
  {
    std::ofstream out(obj);
    for (int i = 0; i <= 100; ++i) {
      for (int j = 0; j <= 50; ++j) out << "v " << i << " " << j << " 0\n";
    }
    auto v = [](int i, int j) { return i * 51 + j + 1; };
    for (int i = 0; i < 100; ++i) {
      for (int j = 0; j < 50; ++j) {
        out << "f " << v(i, j) << " " << v(i + 1, j) << " " << v(i + 1, j + 1) << "\n";
        out << "f " << v(i, j) << " " << v(i + 1, j + 1) << " " << v(i, j + 1) << "\n";
      }
    }
  }
  const json mesh = {{"type", "mesh"}, {"file", "grid.obj"}};
  const visualize::SceneDocument doc = visualize::ParseSceneJson(Shapes(mesh, 200), "s.json", TempDir().string());
  ASSERT_EQ(doc.scene.shapes.size(), 200u);
  EXPECT_EQ(doc.scene.shapes[0].mesh->indices.size(), 3u * 10000u);
  EXPECT_EQ(doc.scene.shapes[0].mesh, doc.scene.shapes[199].mesh);  // read once, shared
  EXPECT_EQ(ErrorOf(Shapes(mesh, 201), TempDir().string()),
            "s.json: shapes[200].file: more than 2000000 mesh triangles (limit)");
}

TEST(SceneLimits, ChainFileValuesMustFitSinglePrecision) {
  const fs::path dir = TempDir();
  std::ofstream(dir / "far.csv") << "0,0,0\n1e300,0,0\n0,1,0\n";
  const json chain = {{"type", "chain"}, {"file", "far.csv"}, {"radius", 0.1}};
  EXPECT_EQ(ErrorOf(Shapes(chain, 1), dir.string()),
            "s.json: shapes[0].file: " + (dir / "far.csv").string() +
                ": point 2 is too large for single precision");
}

TEST(SceneLimits, HugeQuaternionComponentsKeepTheirRotation) {
  auto rotation = [](double w, double x) {
    const json box = {
        {"type", "box"}, {"center", {0, 0, 0}}, {"size", {1, 1, 1}}, {"quaternion", {w, x, 0, 0}}};
    return visualize::ParseSceneJson(Shapes(box, 1), "s.json", ".").scene.shapes[0].world_from_shape;
  };
  // [1e30, 1e30, 0, 0] is the same 90-degree turn about x as [1, 1, 0, 0].
  EXPECT_TRUE(rotation(1e30, 1e30).isApprox(rotation(1, 1), 1e-6f))
      << rotation(1e30, 1e30) << "\nvs\n"
      << rotation(1, 1);
}

}  // namespace
}  // namespace app
