// Private: the writhe continuations of the scenario set-up (scenario_setup.cc): the coil start,
// the unwrapped goal init and the unwinding path (see "Start coil" in scenario.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/motion/scenario.h"
#include "planning/motion/trajectory.h"

namespace planning::internal {

// From `from` (size n) toward total writhe `target` (turns, of the scenario's writhe_report pair)
// in steps of `step` turns: damped Gauss–Newton final-pose estimates under a writhe task, a soft
// collision task with `margin` (m) and a joint-limit task, until the writhe is within 0.005 of
// `target` or stops moving. Every accepted configuration (from included) is appended to `path`
// if not null. Returns the last configuration (n). In the scenario's initial world.
Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin,
                                   std::vector<Eigen::VectorXd>* path = nullptr);

// `path` (at least one configuration of size n) resampled at num_points equally spaced
// joint-space arc lengths (linear between its configurations): n × num_points.
Eigen::MatrixXd ResampleByArcLength(const std::vector<Eigen::VectorXd>& path, int num_points);

// The unwinding init of an AICO attempt ("aico.retry.init": "unwinding"): the writhe continuation
// from q0 (size n) to total writhe 0 in `world` (step and margin of the scenario's start spec),
// resampled by ResampleByArcLength to T + 1 slices, dt = duration / T. Adds its counts to *counts:
// its only world query is its collision task, so its state queries are also its collision queries
// and its pair tests its narrow-phase calls.
Trajectory UnwindingInit(const Scenario& s, const ScenarioState& world, const Eigen::VectorXd& q0,
                         QueryCounts* counts);

// The start coil: WritheContinuation from `from` to `target`, made a state the robot can be in
// (collision-free, inside the joint limits) and retried from seeded perturbations when it stops
// short (start_coil.cc says how). Sets *collides when no collision-free start was found.
// Deterministic.
Eigen::VectorXd StartCoil(const Scenario& s, const Eigen::VectorXd& from, double target,
                          double step, double margin, bool* collides);

// True if the robot at q (size n) touches neither itself nor the scenario's initial objects.
bool CollisionFree(const Scenario& s, const Eigen::VectorXd& q);

}  // namespace planning::internal
