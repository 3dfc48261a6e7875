// Scene files (app/scene_json.h): a full example parses; bad files name the JSON path.
#include "visualize/scene_file.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace app {
namespace {

using nlohmann::json;

std::string ErrorOf(const std::string& text) {
  try {
    visualize::ParseSceneJson(json::parse(text), "s.json", TOPOPLAN_SOURCE_DIR "/assets/scenes");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneJsonTest, ExampleSceneParses) {
  const visualize::SceneDocument doc = visualize::LoadSceneFile(TOPOPLAN_SOURCE_DIR "/assets/scenes/example.json");
  EXPECT_TRUE(doc.has_camera);
  EXPECT_EQ(doc.width, 640);
  EXPECT_EQ(doc.scene.tubes.size(), 2u);
  EXPECT_EQ(doc.scene.tubes[0].segment_colors.size(), doc.scene.tubes[0].points.size() - 1);
  EXPECT_TRUE(doc.scene.grid.enabled);
  bool has_mesh = false;
  for (const render::Shape& s : doc.scene.shapes) {
    if (s.kind == render::Shape::Kind::kMesh) {
      has_mesh = true;
      ASSERT_TRUE(s.mesh);
      EXPECT_EQ(s.mesh->indices.size(), 3u * 1024u);  // torus.obj: 32 x 16 x 2 triangles
    }
  }
  EXPECT_TRUE(has_mesh);
}

TEST(SceneJsonTest, ShapesAndCamera) {
  const visualize::SceneDocument doc = visualize::ParseSceneJson(json::parse(R"({
    "camera": {"eye": [1, 2, 3], "target": [0, 0, 0], "fovy_deg": 30},
    "background": [0, 0, 0],
    "shapes": [
      {"type": "sphere", "center": [1, 0, 0], "radius": 0.5, "color": [1, 0, 0, 0.5]},
      {"type": "capsule", "from": [0, 0, 0], "to": [0, 0, 2], "radius": 0.1},
      {"type": "box", "center": [0, 0, 0], "size": [1, 2, 3], "rpy": [0, 0, 1.5707963]},
      {"type": "chain", "points": [[0, 0, 0], [1, 0, 0], [1, 1, 0]], "radius": 0.02},
      {"type": "lines", "points": [[0, 0, 0], [1, 1, 1]], "width": 2}
    ]})"),
                                           "s.json", ".");
  EXPECT_FLOAT_EQ(doc.camera.fovy_deg, 30.0f);
  EXPECT_EQ(doc.camera.up, Eigen::Vector3f(0, 0, 1));
  ASSERT_EQ(doc.scene.shapes.size(), 3u);
  EXPECT_FLOAT_EQ(doc.scene.shapes[0].material.rgba[3], 0.5f);
  EXPECT_FLOAT_EQ(doc.scene.shapes[1].size.y(), 2.0f);  // capsule length
  EXPECT_NEAR(doc.scene.shapes[1].world_from_shape(2, 3), 1.0f, 1e-6);
  // Box rotated 90 degrees about z: its x axis maps to world y.
  EXPECT_NEAR(doc.scene.shapes[2].world_from_shape(1, 0), 1.0f, 1e-6);
  EXPECT_EQ(doc.scene.tubes.size(), 1u);
  EXPECT_EQ(doc.scene.lines.size(), 1u);
}

TEST(SceneJsonTest, ErrorsNameTheJsonPath) {
  EXPECT_EQ(ErrorOf(R"({"shapes": [{"type": "sphere", "center": [0,0,0], "radius": "big"}]})"),
            "s.json: shapes[0].radius: expected a number");
  EXPECT_EQ(ErrorOf(R"({"shapes": [{"type": "sphere", "center": [0,0], "radius": 1}]})"),
            "s.json: shapes[0].center: expected 3 numbers, got 2");
  EXPECT_EQ(ErrorOf(R"({"shapes": [{"type": "sphere", "radius": 1}]})"),
            "s.json: shapes[0].center: missing");
  EXPECT_NE(ErrorOf(R"({"shapes": [{"type": "cone"}]})").find("shapes[0].type: unknown shape type"),
            std::string::npos);
  EXPECT_EQ(ErrorOf(R"({"shapes": [{"type": "sphere", "center": [0,0,0], "raduis": 1}]})"),
            "s.json: shapes[0].raduis: unknown key 'raduis' (did you mean 'radius'?)");
  EXPECT_EQ(ErrorOf(R"({"camera": {"eye": [0,0,1], "target": [0,0,0]}})"),
            "s.json: camera.up: must not be parallel to the view direction");
  EXPECT_EQ(ErrorOf(R"({"background": [1, 0, 2]})"),
            "s.json: background[2]: colour components must be in [0, 1]");
  EXPECT_NE(
      ErrorOf(R"({"shapes": [{"type": "mesh", "file": "nope.obj"}]})").find("shapes[0].file: "),
      std::string::npos);
  EXPECT_EQ(ErrorOf(R"({"shapes": [{"type": "chain", "points": [[0,0,0],[1,0,0]], "radius": 0.1,
                        "segment_colors": [[1,0,0],[0,1,0]]}]})"),
            "s.json: shapes[0].segment_colors: expected one colour per segment (1)");
  EXPECT_EQ(ErrorOf(R"([1, 2])"), "s.json: (root): expected an object");
}

}  // namespace
}  // namespace app
