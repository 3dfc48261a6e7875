// Shared by the scenario and OMPL tests: an independent re-check of a planned path.
#pragma once

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

}  // namespace planning
