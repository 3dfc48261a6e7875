// Kinematics and collision timings on the thesis' 20-link arm (+ SDH, 27 DOF) and the LWR4 + SDH:
// forward kinematics, point / chain Jacobians, one boolean collision check, one distance query,
// inverse kinematics of the LWR4 + SDH palm.
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "planning/collision/collision.h"
#include "planning/robot/ik.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace {

std::string Asset(const std::string& rel) {
  return std::string(TOPOPLAN_SOURCE_DIR) + "/assets/" + rel;
}

const planning::Robot& Arm20() {
  static const planning::Robot robot = planning::LoadRobot(Asset("robots/arm20_sdh.urdf"));
  return robot;
}

// The unwrapping scene: the rope of thesis §4.3.1 (along y, x = −0.1, z = 1.85), shifted 0.2 m
// so that it clears the stem.
planning::Environment RopeScene() {
  planning::Environment env;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(-0.1, -1.7, 1.85));
  pose.rotate(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  planning::AddObject(planning::LoadRobot(Asset("objects/pole.urdf")), pose, "rope", &env);
  return env;
}

Eigen::VectorXd SomeQ(const planning::Robot& robot) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  Eigen::VectorXd q(planning::num_dofs(robot));
  for (int k = 0; k < q.size(); ++k) q[k] = u(rng);
  return q;
}

void BM_ForwardKinematicsArm20(benchmark::State& state) {
  const planning::Robot& robot = Arm20();
  planning::KinematicsData kin(robot);
  const Eigen::VectorXd q = SomeQ(robot);
  for (auto _ : state) {
    planning::ForwardKinematics(robot, q, &kin);
    benchmark::DoNotOptimize(kin.world_from_link.back());
  }
}
BENCHMARK(BM_ForwardKinematicsArm20);

void BM_PointJacobianArm20Tip(benchmark::State& state) {
  const planning::Robot& robot = Arm20();
  planning::KinematicsData kin(robot);
  planning::ForwardKinematics(robot, SomeQ(robot), &kin);
  Eigen::MatrixXd J(3, planning::num_dofs(robot));
  const int link = planning::FindLink(robot, "arm_link_20");
  for (auto _ : state) {
    planning::PointJacobian(robot, kin, link, Eigen::Vector3d(0, 0, 0.2), J);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(BM_PointJacobianArm20Tip);

// FK + the (3·21)×27 Jacobian of the arm chain: what one writhe-feature evaluation needs.
void BM_FkAndChainJacobianArm20(benchmark::State& state) {
  const planning::Robot& robot = Arm20();
  planning::KinematicsData kin(robot);
  const Eigen::VectorXd q = SomeQ(robot);
  const int chain = planning::FindChain(robot, "arm");
  Eigen::Matrix3Xd P;
  Eigen::MatrixXd dP(3 * planning::ChainSize(robot, chain), planning::num_dofs(robot));
  for (auto _ : state) {
    planning::ForwardKinematics(robot, q, &kin);
    planning::ChainPoints(robot, kin, chain, &P);
    planning::ChainJacobian(robot, kin, chain, dP);
    benchmark::DoNotOptimize(dP.data());
  }
}
BENCHMARK(BM_FkAndChainJacobianArm20);

// One validity check: FK + broadphase update + narrow phase (arm vs rope and self).
void BM_CollisionCheckArm20(benchmark::State& state) {
  const planning::Robot& robot = Arm20();
  const planning::Environment env = RopeScene();
  planning::KinematicsData kin(robot);
  planning::CollisionData coll(robot, env);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(planning::num_dofs(robot));
  for (auto _ : state) {
    planning::ForwardKinematics(robot, q, &kin);
    benchmark::DoNotOptimize(planning::InCollision(robot, kin, &coll));
  }
  state.counters["narrow_phase_per_check"] =
      static_cast<double>(coll.narrow_phase_calls) / static_cast<double>(coll.queries);
}
BENCHMARK(BM_CollisionCheckArm20);

// Distance query for a collision feature: all pairs within 5 cm.
void BM_ProximityArm20(benchmark::State& state) {
  const planning::Robot& robot = Arm20();
  const planning::Environment env = RopeScene();
  planning::KinematicsData kin(robot);
  planning::CollisionData coll(robot, env);
  std::vector<planning::ProximityPair> pairs;
  planning::ForwardKinematics(robot, Eigen::VectorXd::Zero(planning::num_dofs(robot)), &kin);
  for (auto _ : state) {
    planning::ComputeProximity(robot, kin, 0.05, &coll, &pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["narrow_phase_per_query"] =
      static_cast<double>(coll.narrow_phase_calls) / static_cast<double>(coll.queries);
}
BENCHMARK(BM_ProximityArm20);

void BM_CollisionCheckLwr(benchmark::State& state) {
  static const planning::Robot robot = planning::LoadRobot(Asset("robots/lwr4_sdh.urdf"));
  planning::KinematicsData kin(robot);
  planning::CollisionData coll(robot, planning::Environment{});
  const Eigen::VectorXd q = SomeQ(robot);
  for (auto _ : state) {
    planning::ForwardKinematics(robot, q, &kin);
    benchmark::DoNotOptimize(planning::InCollision(robot, kin, &coll));
  }
}
BENCHMARK(BM_CollisionCheckLwr);

// One IK solve of the LWR4 + SDH palm (a point 0.1 m along its z axis) from the middle of the
// limits, default options, cycling through 64 targets from FK of random in-limit q; with
// state.range(0) = 1 the palm's z axis is a target too. Counters: solved fraction, iterations.
void BM_IkLwr(benchmark::State& state) {
  const planning::Robot robot = planning::LoadRobot(Asset("robots/lwr4_sdh.urdf"));
  const int palm = planning::FindLink(robot, "sdh_palm");
  const Eigen::VectorXd lo = planning::LowerLimits(robot), hi = planning::UpperLimits(robot);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  planning::KinematicsData kin(robot);
  std::vector<planning::IkProblem> problems(64);
  for (planning::IkProblem& p : problems) {
    Eigen::VectorXd q(planning::num_dofs(robot));
    for (int k = 0; k < q.size(); ++k) q[k] = lo[k] + u(rng) * (hi[k] - lo[k]);
    planning::ForwardKinematics(robot, q, &kin);
    planning::IkTarget t;
    t.link = palm;
    t.offset = Eigen::Vector3d(0, 0, 0.1);
    t.position = kin.world_from_link[palm] * t.offset;
    if (state.range(0) == 1) {
      t.axis =
          planning::IkAxis{Eigen::Vector3d::UnitZ(), kin.world_from_link[palm].linear().col(2)};
    }
    p.targets = {t};
  }
  planning::IkData data(robot);
  const planning::IkOptions options;
  long solves = 0, solved = 0, iterations = 0;
  for (auto _ : state) {
    const planning::IkResult r =
        planning::SolveIk(robot, problems[solves % problems.size()], options, &data);
    ++solves;
    solved += r.status == planning::IkStatus::kSolved ? 1 : 0;
    iterations += r.iterations;
  }
  state.counters["solved"] = static_cast<double>(solved) / static_cast<double>(solves);
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(solves);
}
BENCHMARK(BM_IkLwr)->Arg(0)->Arg(1);

}  // namespace
