// Uses every installed topoplan library through its public headers only:
//   consumer SHARE_DIR      (SHARE_DIR = <prefix>/share/topoplan, the installed assets)
// Exit 0 when all checks hold; otherwise prints the failed check and exits 1.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "planning/motion/aico.h"
#include "planning/features/feature.h"
#include "planning/robot/kinematics.h"
#include "planning/physics/ode_runtime.h"
#include "planning/robot/robot_io.h"
#include "render/heatmap.h"
#include "render/image.h"
#include "topology/writhe.h"

namespace {

int failures = 0;

void Check(bool ok, const std::string& what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  if (!ok) ++failures;
}

// Two-joint planar arm in the xy plane: upper arm and forearm of length 0.5 each, a tip frame at
// the end of the forearm.
constexpr char kTwoJointArm[] = R"(<?xml version="1.0"?>
<robot name="two_joint_arm">
  <link name="base"/> <link name="upper"/> <link name="fore"/> <link name="tip"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="wrist" type="fixed">
    <parent link="fore"/><child link="tip"/><origin xyz="0.5 0 0"/>
  </joint>
</robot>)";

void CheckWrithe(const std::string& share) {
  // Two closed rings of 64 segments each, linked once: the Gauss linking number is −1.
  const topology::Chain a = topology::ReadChainCsv(share + "/chains/hopf_a.csv");
  const topology::Chain b = topology::ReadChainCsv(share + "/chains/hopf_b.csv");
  const Eigen::MatrixXd w = topology::WritheMatrix(a, b);
  Check(w.rows() == a.cols() - 1 && w.cols() == b.cols() - 1,
        "writhe matrix is segments x segments");
  Check(std::abs(w.sum() + 1.0) < 1e-9,
        "Hopf link total writhe = -1 (got " + std::to_string(w.sum()) + ")");

  render::HeatmapOptions options;
  options.width = 320;
  options.height = 240;
  const render::Image image = render::RenderHeatmap(w, options);
  const render::HeatmapLayout layout =
      render::ComputeHeatmapLayout(static_cast<int>(w.rows()), static_cast<int>(w.cols()), options);
  Check(image.width == layout.width && image.height == layout.height && image.width <= 320 &&
            image.height <= 240,
        "heatmap image size (the canvas follows the matrix, within 320x240)");
  Check(render::SameImage(render::DecodePng(render::EncodePng(image), "heatmap"), image),
        "heatmap PNG round trip");
}

void CheckKinematics(const std::string& share) {
  // The 20-link arm: a fixed 2 m stem, then hinges about local x, each 0.2 m past the last.
  const planning::Robot arm = planning::LoadRobot(share + "/robots/arm20_sdh.urdf");
  planning::KinematicsData kin(arm);
  Eigen::VectorXd q(planning::num_dofs(arm));
  for (int k = 0; k < q.size(); ++k) q[k] = 0.05 * (k % 7) - 0.1;
  planning::ForwardKinematics(arm, q, &kin);

  const int first = planning::FindLink(arm, "arm_link_1");
  const Eigen::Isometry3d& t1 = kin.world_from_link[first];
  Check(t1.translation().isApprox(Eigen::Vector3d(0, 0, 2), 1e-12),
        "arm_link_1 sits on the stem top");
  // URDF rpy (r, p, y) = (1.57079632679, 0, −π/4): R = Rz(y)·Ry(p)·Rx(r), then the hinge Rx(q_1).
  const int j1 = planning::FindJoint(arm, "arm_joint_1");
  int dof1 = 0;
  while (arm.dof_joints[dof1] != j1) ++dof1;
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(-0.785398163397, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(1.57079632679 + q[dof1], Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  Check(t1.linear().isApprox(expected, 1e-12), "arm_link_1 orientation = Rz(-pi/4) Rx(pi/2 + q1)");
  double worst = 0.0;
  for (int k = 1; k < 20; ++k) {
    const int i = planning::FindLink(arm, "arm_link_" + std::to_string(k));
    const int j = planning::FindLink(arm, "arm_link_" + std::to_string(k + 1));
    const double d =
        (kin.world_from_link[j].translation() - kin.world_from_link[i].translation()).norm();
    worst = std::max(worst, std::abs(d - 0.2));
  }
  Check(worst < 1e-12, "consecutive arm links are 0.2 m apart");
}

void CheckAico() {
  const planning::Robot arm = planning::ParseRobot(kTwoJointArm, "two_joint_arm", ".");
  planning::MotionProblem problem;
  problem.robot = &arm;
  problem.dynamic = false;
  problem.num_steps = 10;
  problem.q0 = Eigen::Vector2d(-0.4, 0.8);
  // Tip at (0, 0.5·√2, 0): shoulder π/4 with the elbow at +π/2 (or 3π/4 with −π/2).
  const Eigen::Vector3d goal(0.0, 0.5 * std::numbers::sqrt2, 0.0);
  planning::Task reach;
  reach.name = "tip";
  reach.feature =
      planning::MakePositionFeature(arm, planning::FindLink(arm, "tip"), Eigen::Vector3d::Zero());
  planning::SetConstantTarget(&reach, goal, 0.0, problem.num_steps);
  reach.precision[problem.num_steps] = 1e5;
  problem.tasks.push_back(std::move(reach));

  planning::AicoWorkspace ws(problem);
  planning::AicoOptions options;
  options.max_iterations = 50;
  options.tolerance = 1e-5;
  const planning::AicoResult result = planning::SolveAico(problem, options, &ws);
  Check(result.status == planning::SolveStatus::kConverged,
        std::string("AICO converges (") + planning::StatusName(result.status) + ")");
  const Eigen::Vector2d q = result.trajectory.q.col(problem.num_steps);
  const Eigen::Vector3d tip(0.5 * std::cos(q[0]) + 0.5 * std::cos(q[0] + q[1]),
                            0.5 * std::sin(q[0]) + 0.5 * std::sin(q[0] + q[1]), 0.0);
  Check((tip - goal).norm() < 1e-3, "AICO end configuration reaches the target");
  Check(std::abs(std::abs(q[1]) - std::numbers::pi / 2) < 1e-2, "elbow at ±pi/2");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SHARE_DIR\n");
    return 2;
  }
  const std::string share = argv[1];
  try {
    CheckWrithe(share);
    CheckKinematics(share);
    CheckAico();
    const planning::physics::OdeRuntime ode;
    Check(std::string(ode.configuration()).find("ODE_double_precision") != std::string::npos,
          "ODE runtime is the double-precision build");
  } catch (const std::exception& e) {
    std::printf("FAIL exception: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
