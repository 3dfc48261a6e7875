// Building a scenario's features and tasks from their specs with the objects of a state: shared by
// the set-up (scenario_setup.cc) and the state functions (scenario.cc). Private to
// planning/motion.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/motion/scenario.h"

namespace planning::internal {

// find(robot, name) with the spec's JSON path prefixed to its error.
int FindIn(const SpecName& n, int (*find)(const Robot&, const std::string&), const Robot& r);
// The world points (3 × M) of chain `chain` of object `object` in state `w`.
Eigen::Matrix3Xd ObjectChain(const ScenarioState& w, const SpecName& object, const SpecName& chain);
// The feature of a task spec with the objects of state `w`.
std::unique_ptr<Feature> BuildFeature(const Scenario& s, const ScenarioState& w,
                                      const FeatureSpec& f);
// Task from its spec; target resolution needs q0 (and q̂_T for "final_pose").
Task BuildTask(const Scenario& s, const ScenarioState& w, const TaskSpec& spec,
               const Eigen::VectorXd& q0, const Eigen::VectorXd* q_final);

}  // namespace planning::internal
