// Frozen joints (FreezeDofs) and SRDF groups (GroupDofs): the reduced robot moves exactly as the
// full one with the frozen joints at their values, mimic joints included.
#include <gtest/gtest.h>

#include <random>

#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"
#include "planning/robot/srdf.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

const std::string kTiny = "robots/tinyarm/urdf/tinyarm.urdf";

TEST(FreezeDofs, ReducedRobotHasTheSameForwardKinematics) {
  for (const std::string& file : {kTiny, std::string("robots/lwr4_sdh.urdf")}) {
    const Robot full = LoadRobot(AssetFile(file));
    const int n = num_dofs(full);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Eigen::VectorXd lo = LowerLimits(full), hi = UpperLimits(full);
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd q(n);
      for (int k = 0; k < n; ++k) q[k] = lo[k] + u(rng) * (hi[k] - lo[k]);
      std::vector<int> frozen;
      for (int k = 0; k < n; ++k) {
        if (u(rng) < 0.4) frozen.push_back(k);
      }
      Robot reduced = full;
      const std::vector<int> kept = FreezeDofs(frozen, q, &reduced);
      ASSERT_EQ(num_dofs(reduced), n - static_cast<int>(frozen.size()));
      Eigen::VectorXd qr(static_cast<Eigen::Index>(kept.size()));
      for (size_t i = 0; i < kept.size(); ++i) qr[static_cast<Eigen::Index>(i)] = q[kept[i]];
      KinematicsData a(full), b(reduced);
      ForwardKinematics(full, q, &a);
      ForwardKinematics(reduced, qr, &b);
      for (size_t l = 0; l < full.links.size(); ++l) {
        EXPECT_TRUE(a.world_from_link[l].isApprox(b.world_from_link[l], 1e-12))
            << file << " link " << full.links[l].name;
      }
      // The kept dofs keep their names and order.
      const std::vector<std::string> all = DofNames(full), left = DofNames(reduced);
      for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(left[i], all[kept[i]]);
    }
  }
  Robot r = LoadRobot(AssetFile(kTiny));
  EXPECT_THROW(FreezeDofs({99}, Eigen::VectorXd::Zero(num_dofs(r)), &r), std::invalid_argument);
  EXPECT_THROW(FreezeDofs({0}, Eigen::VectorXd::Zero(2), &r), std::invalid_argument);
}

TEST(GroupDofs, JointsChainsAndUnknownGroups) {
  const Robot robot = LoadRobot(AssetFile(kTiny));
  const Srdf srdf = LoadSrdf(AssetFile("robots/tinyarm/srdf/tinyarm.srdf"));
  EXPECT_EQ(GroupDofs(robot, srdf, "gripper"), std::vector<int>({5}));          // finger_left_joint
  EXPECT_EQ(GroupDofs(robot, srdf, "arm"), std::vector<int>({0, 1, 2, 3, 4}));  // base → tool
  try {
    GroupDofs(robot, srdf, "hand");
    ADD_FAILURE() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no group named 'hand' (have: arm, gripper)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace planning
