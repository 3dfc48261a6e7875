// The renderer glue (our mjv_updateScene): robot + configuration + chains + objects →
// render::Scene. The only code that knows both planning:: and render:: types.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "planning/motion/robot_scene.h"
#include "visualize/scene_file.h"
#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"
#include "planning/motion/scenario_spec.h"
#include "render/scene.h"

namespace visualize {

struct SceneBuildOptions {
  bool visuals = true;        // draw <visual> geometry (else <collision> geometry, in grey-blue)
  bool chains = true;         // draw every robot and object chain as a tube
  float chain_radius = 0.0f;  // tube radius [m]; 0: 1.2% of the scene's size
  bool objects = true;        // draw the environment's objects
  bool grid = true;           // ground grid at z = 0
};

// Converted meshes, shared between frames so the renderer uploads each one once. Keyed by the
// planning::Mesh address: the Robot / Environment must outlive the cache.
struct SceneMeshCache {
  std::map<const planning::Mesh*, std::shared_ptr<const render::TriangleMesh>> meshes;
};

// The render copy of a loaded mesh (planning/robot/mesh_io.h): the same vertices, unit normals and
// triangles (counter-clockwise vertex index triples, flattened to 3 indices per triangle).
std::shared_ptr<const render::TriangleMesh> ToRenderMesh(const planning::Mesh& mesh);

// Appends the shapes of `robot` at the configuration in `kin` (ForwardKinematics done), placed by
// world_from_robot, and (if options.chains) its chains as tubes, one colour per chain.
void AddRobotShapes(const planning::Robot& robot, const planning::KinematicsData& kin,
                    const Eigen::Isometry3d& world_from_robot, const SceneBuildOptions& options,
                    SceneMeshCache* cache, render::Scene* scene);

// Appends every object of `env` (at its zero configuration) with its chains.
void AddEnvironmentShapes(const planning::Environment& env, const SceneBuildOptions& options,
                          SceneMeshCache* cache, render::Scene* scene);

// Robot at q + environment + ground grid + default lights.
render::Scene BuildRobotScene(const planning::Robot& robot, const planning::KinematicsData& kin,
                              const planning::Environment& env, const SceneBuildOptions& options,
                              SceneMeshCache* cache);

// A camera that frames every shape of `scene`, looking from the direction `view_dir` (from the
// target towards the eye, world frame) with vertical field of view fovy_deg.
render::Camera FrameSceneCamera(const render::Scene& scene,
                                const Eigen::Vector3f& view_dir = Eigen::Vector3f(1.0f, -1.3f,
                                                                                  0.8f),
                                float fovy_deg = 35.0f);

// A camera looking from `view_dir` (target towards the eye, +z up) that fits every shape and
// tube of `scene` tightly into an image of width/height `aspect` with vertical field of view
// fovy_deg: the bounding balls of the geometry (as FrameSceneCamera's) fill a fraction `fill`
// (0.1..1) of the half-angles, the target is the middle of their extents along the view axes.
// Used with a scene holding a whole trajectory's robot shapes (its swept volume).
render::Camera FitSceneCamera(const render::Scene& scene, const Eigen::Vector3f& view_dir,
                              float fovy_deg, float aspect, float fill = 0.92f);

// The "remain inside a box" task regions of `spec` (feature type box; centre and half extents,
// world frame [m]): a translucent orange box and its 12 edges as 2-px lines, appended to `scene`.
void AddTaskBoxes(const planning::ScenarioSpec& spec, render::Scene* scene);

// What `topoplan render ROBOT.urdf|SCENE.json` draws: the scene's robot at its q (or `q_text`
// from --q when not empty) with objects and chains; the camera from the JSON's "camera" or framed
// automatically; the size from the JSON's "size" if present.
SceneDocument RobotSceneDocument(const std::string& path, const std::string& q_text,
                                 const SceneBuildOptions& options = {});
// Same with --package-path/--srdf (`input`) and --pose (`pose`, a group_state of the SRDF).
SceneDocument RobotSceneDocument(const std::string& path, const std::string& q_text,
                                 const std::string& pose, const planning::RobotInputOptions& input,
                                 const SceneBuildOptions& options = {});

}  // namespace visualize
