// Private: the JSON that `scenario new` writes (planning/motion/scenario_new.h), shared by its
// tasks: rounded numbers and the keys every file starts with.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "planning/motion/internal/scenario_arm.h"
#include "planning/motion/robot_scene.h"
#include "planning/motion/scenario_new.h"

namespace planning::internal {

using Json = nlohmann::ordered_json;

// [x, y, z] rounded to 1 µm (readable files).
Json Vec(const Eigen::Vector3d& v);
// [q_0, ..., q_{n−1}] rounded to 1e-6.
Json QJson(const Eigen::VectorXd& q);
// Roll, pitch, yaw (URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation, rad.
Json RpyJson(const Eigen::Matrix3d& r);

// The "limits" task (joint_limits: `margin` rad for revolute joints, 0.002 m for prismatic ones,
// precision `precision`) and the "qdot" task (joint velocity, precision 0.1, none at the end).
Json LimitsTask(double margin, double precision);
Json QdotTask();

// The keys every `scenario new` file starts with, in this order: name (options.name, else
// ROBOT_TASK), description, robot (absolute path of `urdf`), srdf, package_paths, frozen_joints
// (setup.arm.other_dofs), robot_chains (one chain `chain_name` of `points`, with the comment
// `chain_comment`) and collision (setup.touching).
Json ScenarioHead(const RobotScene& scene, const std::string& urdf,
                  const NewScenarioOptions& options, const ArmSetup& setup,
                  const std::string& description, const std::string& chain_name,
                  const LinkPoints& points, const std::string& chain_comment);

}  // namespace planning::internal
