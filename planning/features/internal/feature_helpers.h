// Private: argument checks and per-evaluation buffers shared by the feature classes in
// planning/features/ (not installed; included only by their .cc files).
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "planning/features/feature.h"
#include "planning/robot/robot.h"
#include "topology/writhe.h"

namespace planning::internal {

// Throws std::invalid_argument "WHAT: link index L out of range (robot has N links)" unless
// 0 <= link < robot.links.size().
inline void CheckLink(const Robot& robot, int link, const char* what) {
  if (link < 0 || link >= static_cast<int>(robot.links.size())) {
    throw std::invalid_argument(std::string(what) + ": link index " + std::to_string(link) +
                                " out of range (robot has " + std::to_string(robot.links.size()) +
                                " links)");
  }
}

// Throws std::invalid_argument "WHAT: chain index C out of range (robot has N chains)" unless
// 0 <= chain < robot.chains.size().
inline void CheckChain(const Robot& robot, int chain, const char* what) {
  if (chain < 0 || chain >= static_cast<int>(robot.chains.size())) {
    throw std::invalid_argument(std::string(what) + ": chain index " + std::to_string(chain) +
                                " out of range (robot has " + std::to_string(robot.chains.size()) +
                                " chains)");
  }
}

// Buffers holding one 3 × n point Jacobian or a 6 × n frame Jacobian (n = num_dofs).
struct JacobianData : FeatureData {
  explicit JacobianData(int rows, int n) : jac(rows, n) {}
  Eigen::MatrixXd jac;
};

// Buffers of the chain features (writhe, winding, line clearance): the chain points P (3 × N),
// their Jacobian dP (3N × n), the writhe matrix W and its Jacobian dW, the topology workspaces
// and gradients (3 × N; of the object chain for writhe).
struct ChainData : FeatureData {
  ChainData(int points, int n) : P(3, points), dP(3 * points, n) {}
  long evaluations = 0;  // Evals through this data (counted by the world-querying features)
  Eigen::Matrix3Xd P;
  Eigen::MatrixXd dP;
  Eigen::MatrixXd W, dW;
  topology::WritheJacobian wjac;
  topology::WritheWorkspace ws;
  Eigen::Matrix3Xd grad, grad_object;
  // The chain closed by its chord (WritheFeature with closed_by_chord): 3 × (N+1), 3(N+1) × n.
  Eigen::Matrix3Xd closed_P;
  Eigen::MatrixXd closed_dP;
};

}  // namespace planning::internal
