// How collision set-up and checks grow with the number of links (issue 34). A chain of n capsule
// links (0.1 m apart along z, straight at q = 0) is parsed from URDF text, its CollisionData built
// and one CheckCollisions run: everything `topoplan check` does after reading the file.
//
//   BM_ChainCheck/n       parse + set-up + one check, n = 1000, 10000, 100000; the fitted
//                         complexity (Google Benchmark's BigO line) and the time per link
//   BM_ChainQuery/n       one boolean query after set-up (FK + broadphase refit + narrow phases)
//   BM_ChainFoldedQuery/n the same with the chain folded onto itself (every joint at 3 rad):
//                         stops at the first colliding pair
//   BM_RobotQuery         one boolean self-collision query of the URDF named by
//                         $TOPOPLAN_BENCH_ROBOT (package roots in $TOPOPLAN_BENCH_PACKAGE_PATH,
//                         its SRDF found as `check` finds it) at its zero configuration moved into
//                         the limits; skipped when unset. E.g. a 78-link mobile manipulator.
//   BM_RobotCheckAllPairs the same with CheckCollisions (every colliding pair, what `check` runs)
//
// The whole-process timing (process start, file reading, output) is tests/bench/check_scale.py.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "planning/collision/collision.h"
#include "planning/motion/robot_scene.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace {

using namespace planning;

std::string CapsuleChain(int n) {
  std::string urdf = "<robot name=\"chain\">\n";
  for (int i = 0; i < n; ++i) {
    urdf.append("<link name=\"l").append(std::to_string(i));
    urdf.append("\"><collision name=\"capsule\"><origin xyz=\"0 0 0.05\"/><geometry><cylinder ");
    urdf.append("radius=\"0.02\" length=\"0.06\"/></geometry></collision></link>\n");
  }
  for (int i = 1; i < n; ++i) {
    urdf.append("<joint name=\"j").append(std::to_string(i));
    urdf.append("\" type=\"revolute\"><parent link=\"l").append(std::to_string(i - 1));
    urdf.append("\"/><child link=\"l").append(std::to_string(i));
    urdf.append("\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"").append(i % 2 ? "1 0 0" : "0 1 0");
    urdf.append("\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/></joint>\n");
  }
  return urdf.append("</robot>\n");
}

void BM_ChainCheck(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string urdf = CapsuleChain(n);
  for (auto _ : state) {
    const Robot robot = ParseRobot(urdf, "chain.urdf", "");
    KinematicsData kin(robot);
    CollisionData coll(robot, {});
    ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
    const CollisionReport r = CheckCollisions(robot, kin, &coll);
    benchmark::DoNotOptimize(r.in_collision);
  }
  state.SetComplexityN(n);
  state.counters["per_link"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}
BENCHMARK(BM_ChainCheck)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(1)
    ->Complexity(benchmark::oAuto);

void Query(benchmark::State& state, double joint_value) {
  const int n = static_cast<int>(state.range(0));
  const Robot robot = ParseRobot(CapsuleChain(n), "chain.urdf", "");
  KinematicsData kin(robot);
  CollisionData coll(robot, {});
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(num_dofs(robot), joint_value);
  for (auto _ : state) {
    ForwardKinematics(robot, q, &kin);
    benchmark::DoNotOptimize(InCollision(robot, kin, &coll));
  }
  state.SetComplexityN(n);
}
void BM_ChainQuery(benchmark::State& state) { Query(state, 0.0); }
void BM_ChainFoldedQuery(benchmark::State& state) { Query(state, 3.0); }
BENCHMARK(BM_ChainQuery)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainFoldedQuery)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// all_pairs: CheckCollisions (every colliding pair, no early exit) instead of InCollision.
void RobotQuery(benchmark::State& state, bool all_pairs) {
  const char* urdf = std::getenv("TOPOPLAN_BENCH_ROBOT");
  if (urdf == nullptr || *urdf == '\0') {
    state.SkipWithError("set TOPOPLAN_BENCH_ROBOT to a URDF");
    return;
  }
  RobotInputOptions input;
  if (const char* p = std::getenv("TOPOPLAN_BENCH_PACKAGE_PATH")) input.package_paths = {p};
  const RobotScene scene = LoadRobotScene(urdf, input);
  KinematicsData kin(scene.robot);
  CollisionData coll(scene.robot, CollisionEnvironment(scene), scene.collision_options);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(scene.robot))
                                .cwiseMax(LowerLimits(scene.robot))
                                .cwiseMin(UpperLimits(scene.robot));
  for (auto _ : state) {
    ForwardKinematics(scene.robot, q, &kin);
    if (all_pairs) {
      benchmark::DoNotOptimize(CheckCollisions(scene.robot, kin, &coll).pairs.size());
    } else {
      benchmark::DoNotOptimize(InCollision(scene.robot, kin, &coll));
    }
  }
  state.counters["links"] = static_cast<double>(scene.robot.links.size());
}
void BM_RobotQuery(benchmark::State& state) { RobotQuery(state, false); }
void BM_RobotCheckAllPairs(benchmark::State& state) { RobotQuery(state, true); }
BENCHMARK(BM_RobotQuery)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RobotCheckAllPairs)->Unit(benchmark::kMicrosecond);

}  // namespace
