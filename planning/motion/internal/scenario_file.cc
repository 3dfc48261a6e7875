// The JSON that `scenario new` writes (internal/scenario_file.h).
#include "planning/motion/internal/scenario_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace planning::internal {
namespace fs = std::filesystem;

Json Vec(const Eigen::Vector3d& v) {
  const auto r = [](double x) { return std::round(x * 1e6) / 1e6; };
  return Json::array({r(v.x()), r(v.y()), r(v.z())});
}

Json QJson(const Eigen::VectorXd& q) {
  Json a = Json::array();
  for (Eigen::Index k = 0; k < q.size(); ++k) a.push_back(std::round(q[k] * 1e6) / 1e6);
  return a;
}

Json RpyJson(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double roll = std::atan2(r(2, 1), r(2, 2)), yaw = std::atan2(r(1, 0), r(0, 0));
  if (std::abs(std::cos(pitch)) < 1e-9) {  // gimbal lock: put it all in yaw
    roll = 0.0;
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  const auto q = [](double x) { return std::round(x * 1e9) / 1e9; };
  return Json::array({q(roll), q(pitch), q(yaw)});
}

Json LimitsTask(double margin, double precision) {
  return {{"name", "limits"},
          {"feature", {{"type", "joint_limits"}, {"margin", margin}, {"prismatic_margin", 0.002}}},
          {"precision", precision}};
}

Json QdotTask() {
  return {{"name", "qdot"},
          {"feature", {{"type", "joint_position"}}},
          {"order", 1},
          {"precision", 0.1},
          {"final_precision", 0}};
}

Json ScenarioHead(const RobotScene& scene, const std::string& urdf, const NewScenarioOptions& o,
                  const ArmSetup& setup, const std::string& description,
                  const std::string& chain_name, const LinkPoints& points,
                  const std::string& chain_comment) {
  const Robot& robot = scene.robot;
  Json j;
  j["name"] = o.name.empty() ? robot.name + "_" + o.task : o.name;
  j["description"] = description;
  j["robot"] = fs::absolute(urdf).lexically_normal().string();
  if (scene.srdf) j["srdf"] = fs::absolute(scene.srdf->source).lexically_normal().string();
  if (!o.package_paths.empty()) {
    Json pp = Json::array();
    for (const std::string& p : o.package_paths)
      pp.push_back(fs::absolute(p).lexically_normal().string());
    j["package_paths"] = pp;
  }
  if (!setup.arm.other_dofs.empty()) {
    const std::vector<std::string> dof_names = DofNames(robot);
    j["// frozen_joints"] = "joints off the arm (fingers, other limbs), held at their start values";
    Json fj = Json::array();
    for (int k : setup.arm.other_dofs) fj.push_back(dof_names[k]);
    j["frozen_joints"] = fj;
  }
  j["// robot_chains"] = chain_comment;
  Json chain = Json::array();
  for (const auto& [link, xyz] : points)
    chain.push_back({{"link", robot.links[link].name}, {"xyz", Vec(xyz)}});
  j["robot_chains"] = Json::array({{{"name", chain_name}, {"points", chain}}});
  if (!setup.touching.empty()) {
    j["// collision"] =
        "link pairs in contact in the start pose, never checked (as MoveIt's "
        "set-up assistant disables them); remove a pair to check it";
    Json pairs = Json::array();
    for (const auto& [a, b] : setup.touching) pairs.push_back(Json::array({a, b}));
    j["collision"] = {{"disabled_pairs", pairs}};
  }
  return j;
}

}  // namespace planning::internal
