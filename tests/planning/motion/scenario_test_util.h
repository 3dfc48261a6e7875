// Shared by the scenario and OMPL tests: an independent re-check of a planned path, and scenario
// files written for a test.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario.h"

namespace planning {

// True when no configuration along `path` (densified at the scenario's check resolution) is in
// collision, checked with a fresh CollisionData (joint limits not checked).
inline bool PathCollisionFree(const Scenario& s, const Trajectory& path) {
  CollisionData coll(s.robot, s.initial.env, s.collision);
  KinematicsData kin(s.robot);
  const ValidityFn free = [&](const Eigen::VectorXd& q) {
    ForwardKinematics(s.robot, q, &kin);
    return !InCollision(s.robot, kin, &coll);
  };
  return PathIsValid(path, s.check_resolution, free);
}

// Writes `text` to TOPOPLAN_BINARY_DIR/`dir`/`name` (the directory made if needed); returns the
// file's path.
inline std::string WriteTestFile(const std::string& dir, const std::string& name,
                                 const std::string& text) {
  const std::filesystem::path d = std::filesystem::path(TOPOPLAN_BINARY_DIR) / dir;
  std::filesystem::create_directories(d);
  const std::string path = (d / name).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace planning
