// planning/mesh_io: COLLADA <up_axis>/<unit> handling, axis-free formats, and one mesh for both
// collision and drawing (robot visuals and scene-file mesh entries get the loader's vertices).
#include "planning/robot/mesh_io.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "visualize/scene_builder.h"
#include "visualize/scene_file.h"
#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

// The tetrahedron's corners in the z-up link frame: the origin and one point on each axis.
struct Corners {
  Eigen::Vector3f x_axis, y_axis, z_axis;
};

// Every loaded vertex must be one of the origin and the three expected corners, and each corner
// must occur (the loader may split vertices per face).
void ExpectCorners(const Mesh& mesh, const Corners& c) {
  const Eigen::Vector3f expected[] = {Eigen::Vector3f::Zero(), c.x_axis, c.y_axis, c.z_axis};
  bool seen[4] = {false, false, false, false};
  for (const Eigen::Vector3f& v : mesh.vertices) {
    bool matched = false;
    for (int k = 0; k < 4; ++k) {
      if ((v - expected[k]).norm() < 1e-6f) matched = seen[k] = true;
    }
    EXPECT_TRUE(matched) << "unexpected vertex " << v.transpose() << " in " << mesh.path;
  }
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(seen[k]) << "corner " << k << " missing in " << mesh.path;
  EXPECT_EQ(mesh.triangles.size(), 4u);
  ASSERT_EQ(mesh.normals.size(), mesh.vertices.size());
  for (const Eigen::Vector3f& n : mesh.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
}

TEST(MeshIo, ColladaZUpKeepsItsCoordinates) {
  ExpectCorners(LoadMesh(TestDataFile("axes/tet_z_up.dae")),
                {{0.1f, 0, 0}, {0, 0.2f, 0}, {0, 0, 0.3f}});
}

TEST(MeshIo, ColladaYUpTurnsItsUpAxisIntoZ) {
  // File y (up) → +z, file z (towards the viewer) → −y.
  const Corners y_up{{0.1f, 0, 0}, {0, 0, 0.2f}, {0, -0.3f, 0}};
  ExpectCorners(LoadMesh(TestDataFile("axes/tet_y_up.dae")), y_up);
  // <unit meter="0.01">: centimetre coordinates come back in metres.
  ExpectCorners(LoadMesh(TestDataFile("axes/tet_y_up_cm.dae")), y_up);
}

TEST(MeshIo, ObjHasNoAxisMetadataAndIsTakenAsIs) {
  ExpectCorners(LoadMesh(TestDataFile("axes/tet.obj")), {{0.1f, 0, 0}, {0, 0.2f, 0}, {0, 0, 0.3f}});
}

TEST(MeshIo, MissingAndEmptyFilesNameThePath) {
  try {
    LoadMesh(TestDataFile("axes/nope.stl"));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nope.stl: mesh file not found"), std::string::npos);
  }
}

// One link whose visual and collision geometry is the Y_UP tetrahedron.
Robot TetBot() {
  const std::string urdf =
      "<robot name=\"tet_bot\"><link name=\"base\">"
      "<visual><geometry><mesh filename=\"tet_y_up.dae\"/></geometry></visual>"
      "<collision><geometry><mesh filename=\"tet_y_up.dae\"/></geometry></collision>"
      "</link></robot>";
  return ParseRobot(urdf, "tet_bot.urdf", TestDataFile("axes"));
}

TEST(MeshIo, CollisionSeesTheZUpMesh) {
  const Robot robot = TetBot();
  ASSERT_EQ(robot.meshes.size(), 1u);  // visual and collision share one loaded file
  Environment env;
  Geometry ball;
  ball.kind = Geometry::Kind::kSphere;
  ball.size = Eigen::Vector3d(0.02, 0, 0);
  // 3 cm above the apex at z = 0.2 (the file's y axis); the file's z corner (0.3) lies on −y.
  AddObject(MakePrimitiveObject("ball", ball), Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.25)),
            "ball", &env);
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd(0), &kin);
  CollisionData coll(robot, env);
  EXPECT_NEAR(MinDistance(robot, kin, &coll), 0.03, 1e-6);
}

TEST(MeshIo, RenderingDrawsTheVerticesCollisionUses) {
  const Robot robot = TetBot();
  const Mesh& mesh = robot.meshes[0];
  // Robot visuals through the scene builder.
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd(0), &kin);
  visualize::SceneMeshCache cache;
  const render::Scene scene = visualize::BuildRobotScene(robot, kin, {}, {}, &cache);
  const render::TriangleMesh* drawn = nullptr;
  for (const render::Shape& s : scene.shapes) {
    if (s.kind == render::Shape::Kind::kMesh) drawn = s.mesh.get();
  }
  ASSERT_NE(drawn, nullptr);
  EXPECT_EQ(drawn->positions, mesh.vertices);
  EXPECT_EQ(drawn->normals, mesh.normals);
  ASSERT_EQ(drawn->indices.size(), 3 * mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(drawn->indices[3 * t + i], static_cast<std::uint32_t>(mesh.triangles[t][i]));
    }
  }
  // A scene file's mesh entry reads the same file through the same loader.
  const nlohmann::json doc =
      nlohmann::json::parse(R"({"shapes": [{"type": "mesh", "file": "tet_y_up.dae"}]})");
  const visualize::SceneDocument sd = visualize::ParseSceneJson(doc, "test.json", TestDataFile("axes"));
  ASSERT_EQ(sd.scene.shapes.size(), 1u);
  EXPECT_EQ(sd.scene.shapes[0].mesh->positions, mesh.vertices);
  EXPECT_EQ(sd.scene.shapes[0].mesh->normals, mesh.normals);
  EXPECT_EQ(sd.scene.shapes[0].mesh->indices, drawn->indices);
}

}  // namespace
}  // namespace planning
