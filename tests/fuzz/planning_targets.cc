// Fuzz targets of the files read by planning/: scenarios, URDF, chain sidecars, SRDF, grasps, the
// grasp-object catalogue and mesh files.
#include <cctype>
#include <stdexcept>
#include <string>

#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/robot/mesh_io.h"
#include "planning/robot/robot_io.h"
#include "planning/motion/scenario_spec.h"
#include "planning/robot/srdf.h"
#include "tests/fuzz/fuzz_targets.h"

namespace topoplan_fuzz {
namespace {

// Robots read once per process (the references the fuzzed files are checked against).
const planning::Robot& Arm20() {
  static const planning::Robot robot = [] {
    planning::RobotLoadOptions o;
    o.load_meshes = false;
    o.chains_path = AssetPath("robots/arm20_sdh.chains.json");
    return planning::LoadRobot(AssetPath("robots/arm20_sdh.urdf"), o);
  }();
  return robot;
}

}  // namespace

const planning::Robot& TinyArm() {
  static const planning::Robot robot = [] {
    planning::RobotLoadOptions o;
    o.load_meshes = false;
    return planning::LoadRobot(AssetPath("robots/tinyarm/urdf/tinyarm.urdf"), o);
  }();
  return robot;
}

namespace {

const planning::Robot& HumanHand() {
  static const planning::Robot robot = planning::LoadRobot(AssetPath("robots/human_hand.urdf"));
  return robot;
}

const std::vector<planning::GraspObject>& Objects() {
  static const std::vector<planning::GraspObject> objects =
      planning::LoadGraspObjects(AssetPath("grasps/objects.json"));
  return objects;
}

}  // namespace

int ScenarioJson(const uint8_t* data, size_t size) {
  try {
    planning::ParseScenarioSpec(WriteInput(data, size, "scenario.json"), {AssetPath("")});
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Urdf(const uint8_t* data, size_t size) {
  const std::string text = Text(data, size);
  const size_t nul = text.find('\0');
  try {
    // Mesh references resolve as for the tiny arm (package://tinyarm/..., relative paths), and
    // the meshes found are loaded.
    planning::Robot robot =
        planning::ParseRobot(text.substr(0, nul), "fuzz.urdf", AssetPath("robots/tinyarm/urdf"));
    if (nul != std::string::npos) {
      const std::string sidecar = text.substr(nul + 1);
      planning::LoadChains(WriteInput(reinterpret_cast<const uint8_t*>(sidecar.data()),
                                      sidecar.size(), "robot.chains.json"),
                           &robot);
    }
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int ChainsSidecar(const uint8_t* data, size_t size) {
  planning::Robot robot = Arm20();
  robot.chains.clear();
  try {
    planning::LoadChains(WriteInput(data, size, "arm.chains.json"), &robot);
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Srdf(const uint8_t* data, size_t size) {
  try {
    const planning::Srdf srdf = planning::ParseSrdf(Text(data, size), "fuzz.srdf");
    planning::CheckSrdf(srdf, TinyArm());
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Grasp(const uint8_t* data, size_t size) {
  try {
    const planning::HumanGrasp grasp = planning::LoadHumanGrasp(WriteInput(data, size, "g.json"));
    planning::FindGraspObject(Objects(), grasp.object);
    planning::HumanConfiguration(HumanHand(), grasp);
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int GraspObjects(const uint8_t* data, size_t size) {
  try {
    for (const planning::GraspObject& object :
         planning::LoadGraspObjects(WriteInput(data, size, "objects.json"))) {
      Eigen::Vector3d grad;
      planning::SignedDistance(object, Eigen::Vector3d(0.01, 0.02, 0.03), &grad);
      planning::TransformReference(object.reference, Eigen::Isometry3d::Identity());
    }
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Mesh(const uint8_t* data, size_t size) {
  const std::string text = Text(data, size);
  const size_t newline = text.find('\n');
  std::string ext = newline == std::string::npos ? "" : text.substr(0, newline);
  bool plain = !ext.empty() && ext.size() <= 8;
  for (char c : ext) plain = plain && std::isalnum(static_cast<unsigned char>(c));
  if (!plain) ext = "bin";
  const std::string body = newline == std::string::npos ? text : text.substr(newline + 1);
  try {
    const planning::Mesh mesh = planning::LoadMesh(
        WriteInput(reinterpret_cast<const uint8_t*>(body.data()), body.size(), "mesh." + ext));
    planning::ConvexHull(mesh);
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

}  // namespace topoplan_fuzz
