// Private: the writhe continuations of the scenario set-up (scenario_setup.cc): the coil start,
// the unwrapped goal init and the unwinding path (see "Start coil" in scenario.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "planning/motion/scenario.h"

namespace planning::internal {

// From `from` (size n) toward total writhe `target` (turns, of the scenario's writhe_report pair)
// in steps of `step` turns: damped Gauss–Newton final-pose estimates under a writhe task, a soft
// collision task with `margin` (m) and a joint-limit task, until the writhe is within 0.005 of
// `target` or stops moving. Every accepted configuration (from included) is appended to `path`
// if not null. Returns the last configuration (n).
Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin,
                                   std::vector<Eigen::VectorXd>* path = nullptr);

// The start coil: WritheContinuation from `from` to `target`, made a state the robot can be in
// (collision-free, inside the joint limits) and retried from seeded perturbations when it stops
// short (start_coil.cc says how). Sets *collides when no collision-free start was found.
// Deterministic.
Eigen::VectorXd StartCoil(const Scenario& s, const Eigen::VectorXd& from, double target,
                          double step, double margin, bool* collides);

// True if the robot at q (size n) touches neither itself nor the scenario's initial objects.
bool CollisionFree(const Scenario& s, const Eigen::VectorXd& q);

}  // namespace planning::internal
