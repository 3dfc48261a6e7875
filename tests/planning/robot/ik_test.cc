// Inverse kinematics: targets from FK of random in-limit configurations on the shipped robots and
// on generated random chains, joint limits, axis targets, frozen joints, unreachable targets,
// validity rejection, bad input, no allocation in the iterations.
#include "planning/robot/ik.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "base/random.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"

// Counts malloc calls in this process (Eigen allocates through malloc): glibc's own allocator is
// called underneath, free() is unchanged.
extern "C" void* __libc_malloc(std::size_t n);  // NOLINT(bugprone-reserved-identifier)
static std::atomic<long> g_mallocs{0};
extern "C" void* malloc(std::size_t n) {  // NOLINT
  ++g_mallocs;
  return __libc_malloc(n);
}

namespace planning {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Every returned q lies inside the limits and equals the seed on the frozen dofs.
void ExpectInLimits(const Robot& robot, const Eigen::VectorXd& q) {
  const Eigen::VectorXd lo = LowerLimits(robot), hi = UpperLimits(robot);
  ASSERT_EQ(q.size(), num_dofs(robot));
  for (int k = 0; k < q.size(); ++k) {
    EXPECT_GE(q[k], lo[k]) << DofNames(robot)[k];
    EXPECT_LE(q[k], hi[k]) << DofNames(robot)[k];
  }
}

IkTarget TargetAt(const Robot& robot, const Eigen::VectorXd& q, int link,
                  const Eigen::Vector3d& offset) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  IkTarget t;
  t.link = link;
  t.offset = offset;
  t.position = kin.world_from_link[link] * offset;
  return t;
}

struct ShippedCase {
  std::string urdf, link;
  Eigen::Vector3d offset;
};

// (a) + (c): FK targets of random in-limit q on every shipped robot are reached to 1 mm, inside
// the limits.
TEST(Ik, ShippedRobotsReachFkTargets) {
  const std::vector<ShippedCase> cases = {
      {"robots/lwr4_sdh.urdf", "sdh_palm", Eigen::Vector3d(0, 0, 0.1)},
      {"robots/lwr4_sdh.urdf", "sdh_finger_1_tip", Eigen::Vector3d::Zero()},  // mimic knuckle
      {"robots/tinyarm/urdf/tinyarm.urdf", "tool", Eigen::Vector3d::Zero()},
      {"robots/arm20_sdh.urdf", "arm_link_20", Eigen::Vector3d(0, 0, 0.2)},
      {"robots/human_hand.urdf", "index_tip", Eigen::Vector3d::Zero()},  // prismatic, continuous
  };
  for (const ShippedCase& c : cases) {
    SCOPED_TRACE(c.urdf + " " + c.link);
    RobotLoadOptions load;
    load.load_meshes = false;
    const Robot robot = LoadRobot(AssetFile(c.urdf), load);
    const int link = FindLink(robot, c.link);
    IkData data(robot);
    std::mt19937 rng(7);
    int solved = 0;
    const int trials = 20;
    for (int i = 0; i < trials; ++i) {
      IkProblem problem;
      problem.targets.push_back(TargetAt(robot, RandomQ(robot, &rng), link, c.offset));
      const IkResult r = SolveIk(robot, problem, IkOptions{}, &data);
      ExpectInLimits(robot, r.q);
      if (r.status == IkStatus::kSolved) {
        ++solved;
        EXPECT_LT(r.position_error, 1e-3);
      }
    }
    EXPECT_EQ(solved, trials);
  }
}

// A random serial chain: 5–8 joints (revolute 70 %, prismatic 30 %) with random axes, joint
// origins (±0.3 m, random rpy) and limits (revolute: width 0.6–5 rad starting anywhere in
// [−3, 1.5], so that many exclude zero; prismatic: width 0.1–0.5 m starting in [−0.3, 0.2]).
std::string RandomChainUrdf(std::mt19937* rng, int* num_joints) {
  const auto u = [rng](double lo, double hi) { return lo + base::UniformUnit(rng) * (hi - lo); };
  const int n = 5 + static_cast<int>(base::UniformIndex(rng, 4));
  *num_joints = n;
  std::ostringstream x;
  x.precision(17);
  x << "<robot name=\"random_chain\">\n<link name=\"l0\"/>\n";
  for (int j = 0; j < n; ++j) {
    const bool prismatic = base::UniformUnit(rng) < 0.3;
    Eigen::Vector3d axis(u(-1, 1), u(-1, 1), u(-1, 1));
    axis = axis.norm() > 1e-3 ? axis.normalized() : Eigen::Vector3d::UnitZ();
    double lower, upper;
    if (prismatic) {
      lower = u(-0.3, 0.2);
      upper = lower + u(0.1, 0.5);
    } else {
      lower = u(-3.0, 1.5);
      upper = std::min(lower + u(0.6, 5.0), kPi);
    }
    x << "<link name=\"l" << j + 1 << "\"/>\n<joint name=\"j" << j + 1 << "\" type=\""
      << (prismatic ? "prismatic" : "revolute") << "\"><parent link=\"l" << j
      << "\"/><child link=\"l" << j + 1 << "\"/><origin xyz=\"" << u(-0.3, 0.3) << " "
      << u(-0.3, 0.3) << " " << u(-0.3, 0.3) << "\" rpy=\"" << u(-kPi, kPi) << " " << u(-kPi, kPi)
      << " " << u(-kPi, kPi) << "\"/><axis xyz=\"" << axis.x() << " " << axis.y() << " " << axis.z()
      << "\"/><limit lower=\"" << lower << "\" upper=\"" << upper
      << "\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  x << "</robot>\n";
  return x.str();
}

struct ChainRate {
  int cases = 0, reached = 0, first_start = 0, excluding_zero = 0;
  long iterations = 0;
};

// Solves FK targets (a random point on the last link, with the last link's z axis when
// `with_axis`) on `cases` random chains; counts the cases reached to 1 mm (and 1e-3 rad) and
// checks every q against the limits.
ChainRate RandomChainRate(int cases, bool with_axis) {
  std::mt19937 rng(2024);
  ChainRate out;
  out.cases = cases;
  for (int c = 0; c < cases; ++c) {
    int n = 0;
    const std::string xml = RandomChainUrdf(&rng, &n);
    const Robot robot = ParseRobot(xml, "random_chain_" + std::to_string(c) + ".urdf", "");
    EXPECT_EQ(num_dofs(robot), n);
    Eigen::VectorXd q(n);
    for (int k = 0; k < n; ++k) {
      const JointLimits& l = robot.joints[robot.dof_joints[k]].limits;
      out.excluding_zero += (l.lower > 0.0 || l.upper < 0.0) ? 1 : 0;
      q[k] = l.lower + base::UniformUnit(&rng) * (l.upper - l.lower);
    }
    const Eigen::Vector3d offset(0.2 * base::UniformUnit(&rng), 0.1, 0.0);
    const int tip = static_cast<int>(robot.links.size()) - 1;
    IkProblem problem;
    problem.targets.push_back(TargetAt(robot, q, tip, offset));
    if (with_axis) {
      KinematicsData kin(robot);
      ForwardKinematics(robot, q, &kin);
      problem.targets[0].axis =
          IkAxis{Eigen::Vector3d::UnitZ(), kin.world_from_link[tip].linear().col(2)};
    }
    IkData data(robot);
    const IkResult r = SolveIk(robot, problem, IkOptions{}, &data);
    ExpectInLimits(robot, r.q);
    out.iterations += r.iterations;
    if (r.status == IkStatus::kSolved && r.position_error < 1e-3 && r.axis_error < 1e-3) {
      ++out.reached;
      out.first_start += r.start == 0 ? 1 : 0;
    }
  }
  std::printf(
      "random chains%s: %d of %d reached (%.1f %%; %d from the first start), %d joints "
      "with limits excluding zero, %.1f iterations per case\n",
      with_axis ? " (position + axis)" : "", out.reached, cases, 100.0 * out.reached / cases,
      out.first_start, out.excluding_zero, static_cast<double>(out.iterations) / cases);
  return out;
}

// (b) + (c): a reachable random target (FK of a random in-limit q, a random point on the last
// link) is reached to 1 mm in >= 95 % of 300 random chains; every q is inside the limits.
TEST(Ik, RandomChainsReachFkTargets) {
  const ChainRate r = RandomChainRate(300, false);
  EXPECT_GT(r.excluding_zero, r.cases / 2);
  EXPECT_GE(r.reached, 0.95 * r.cases);
}

// The same with the last link's z axis as an approach axis (6 constraints on 5–8 joints).
TEST(Ik, RandomChainsReachFkPoses) {
  const ChainRate r = RandomChainRate(300, true);
  EXPECT_GE(r.reached, 0.9 * r.cases);
}

const Robot& Lwr() {
  static const Robot robot = [] {
    RobotLoadOptions load;
    load.load_meshes = false;
    return LoadRobot(AssetFile("robots/lwr4_sdh.urdf"), load);
  }();
  return robot;
}

// (d): position + approach axis targets from FK are reached to 1 mm and 1e-3 rad.
TEST(Ik, AxisTargetsReached) {
  const Robot& robot = Lwr();
  const int palm = FindLink(robot, "sdh_palm");
  IkData data(robot);
  KinematicsData kin(robot);
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    const Eigen::VectorXd q = RandomQ(robot, &rng);
    IkTarget t = TargetAt(robot, q, palm, Eigen::Vector3d(0, 0, 0.1));
    ForwardKinematics(robot, q, &kin);
    t.axis = IkAxis{Eigen::Vector3d::UnitZ(), kin.world_from_link[palm].linear().col(2)};
    IkProblem problem;
    problem.targets = {t};
    const IkResult r = SolveIk(robot, problem, IkOptions{}, &data);
    EXPECT_EQ(r.status, IkStatus::kSolved) << i;
    EXPECT_LT(r.position_error, 1e-3);
    EXPECT_LT(r.axis_error, 1e-3);
    ExpectInLimits(robot, r.q);
    double pos = 0, axis = 0;
    IkErrors(robot, problem, r.q, &kin, &pos, &axis);
    EXPECT_NEAR(pos, r.position_error, 1e-12);
    EXPECT_NEAR(axis, r.axis_error, 1e-12);
  }
}

// (e): frozen dofs keep the seed value exactly; the others still reach the target.
TEST(Ik, FrozenJointsUnchanged) {
  const Robot& robot = Lwr();
  const std::vector<int> frozen = DofIndices(robot, {"lwr_joint_3", "sdh_knuckle_joint"});
  std::mt19937 rng(5);
  IkData data(robot);
  for (int i = 0; i < 10; ++i) {
    Eigen::VectorXd seed = RandomQ(robot, &rng) * 0.3;
    Eigen::VectorXd q = RandomQ(robot, &rng);
    for (int k : frozen) q[k] = seed[k];
    IkProblem problem;
    problem.targets.push_back(
        TargetAt(robot, q, FindLink(robot, "sdh_finger_1_tip"), Eigen::Vector3d::Zero()));
    problem.seed = seed;
    problem.frozen_dofs = frozen;
    const IkResult r = SolveIk(robot, problem, IkOptions{}, &data);
    EXPECT_EQ(r.status, IkStatus::kSolved) << i;
    for (int k : frozen) EXPECT_EQ(r.q[k], seed[k]);
  }
}

// (f): a target out of reach: kNotReached with the best error found (the arm stretched towards
// it: the distance minus the reach), inside the limits.
TEST(Ik, UnreachableTargetReportsBestError) {
  const Robot& robot = Lwr();
  IkProblem problem;
  IkTarget t;
  t.link = FindLink(robot, "lwr_link_7");
  t.position = Eigen::Vector3d(3.0, 0.0, 0.31);  // shoulder at z = 0.31, reach 0.8685 m
  problem.targets.push_back(t);
  IkData data(robot);
  IkOptions options;
  options.starts = 3;
  const IkResult r = SolveIk(robot, problem, options, &data);
  EXPECT_EQ(r.status, IkStatus::kNotReached);
  EXPECT_EQ(r.starts, 3);
  EXPECT_NEAR(r.position_error, 3.0 - 0.8685, 2e-3);
  ExpectInLimits(robot, r.q);
  // Deterministic: the same inputs give the same q.
  const IkResult again = SolveIk(robot, problem, options, &data);
  EXPECT_EQ(again.q, r.q);
  EXPECT_EQ(again.iterations, r.iterations);
}

// A mimic joint's limits bound its master: j2 = 2·j1 with j2 in [−0.6, 0.6] keeps j1 in
// [−0.3, 0.3] though j1's own limits are ±1.5; a target that needs j1 = 1 is missed at j1 = 0.3.
TEST(Ik, MimicLimitsBoundTheMaster) {
  const Robot robot = ParseRobot(R"(<robot name="mimic2">
  <link name="base"/><link name="a"/><link name="b"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="1 0 0"/><axis xyz="0 0 1"/><mimic joint="j1" multiplier="2" offset="0"/>
    <limit lower="-0.6" upper="0.6" effort="1" velocity="1"/></joint>
</robot>)",
                                 "mimic2", ".");
  ASSERT_EQ(num_dofs(robot), 1);
  const IkData data(robot);
  EXPECT_DOUBLE_EQ(data.lower[0], -0.3);
  EXPECT_DOUBLE_EQ(data.upper[0], 0.3);
  IkProblem problem;
  problem.targets.push_back(TargetAt(robot, Eigen::VectorXd::Constant(1, 1.0), FindLink(robot, "b"),
                                     Eigen::Vector3d(0.5, 0, 0)));
  IkData work(robot);
  IkOptions options;
  options.starts = 4;
  const IkResult r = SolveIk(robot, problem, options, &work);
  EXPECT_EQ(r.status, IkStatus::kNotReached);
  EXPECT_NEAR(r.q[0], 0.3, 1e-6);
}

// is_valid: a reached q it refuses sends the solver to the next start; refusing all gives
// kInvalid with the first reached q.
TEST(Ik, ValidityRejection) {
  const Robot& robot = Lwr();
  std::mt19937 rng(11);
  IkProblem problem;
  problem.targets.push_back(
      TargetAt(robot, RandomQ(robot, &rng), FindLink(robot, "sdh_palm"), Eigen::Vector3d::Zero()));
  IkData data(robot);
  IkOptions options;
  int calls = 0;
  options.is_valid = [&calls](const Eigen::VectorXd&) { return ++calls >= 2; };
  IkResult r = SolveIk(robot, problem, options, &data);
  EXPECT_EQ(r.status, IkStatus::kSolved);
  EXPECT_EQ(r.rejected, 1);
  EXPECT_GE(r.start, 1);
  options.is_valid = [](const Eigen::VectorXd&) { return false; };
  r = SolveIk(robot, problem, options, &data);
  EXPECT_EQ(r.status, IkStatus::kInvalid);
  EXPECT_EQ(r.rejected, options.starts);
  EXPECT_LT(r.position_error, 1e-3);
}

// (g): bad input throws std::invalid_argument.
TEST(Ik, BadInputThrows) {
  const Robot& robot = Lwr();
  IkData data(robot);
  const auto solve = [&](IkProblem p, IkOptions o = {}) { return SolveIk(robot, p, o, &data); };
  IkTarget good;
  good.link = FindLink(robot, "sdh_palm");
  good.position = Eigen::Vector3d(0.3, 0.2, 0.8);
  IkProblem p;
  EXPECT_THROW(solve(p), std::invalid_argument);  // no targets
  p.targets = {good};
  EXPECT_NO_THROW(solve(p));
  IkProblem bad = p;
  bad.targets[0].link = 999;
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad = p;
  bad.targets[0].position.x() = std::nan("");
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad = p;
  bad.targets[0].axis = IkAxis{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad = p;
  bad.seed = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad.seed = Eigen::VectorXd::Zero(num_dofs(robot));
  bad.seed[2] = std::nan("");
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad = p;
  bad.frozen_dofs = {99};
  EXPECT_THROW(solve(bad), std::invalid_argument);
  bad.seed = Eigen::VectorXd::Zero(num_dofs(robot));
  bad.seed[0] = 10.0;  // outside lwr_joint_1's limits
  bad.frozen_dofs = {0};
  EXPECT_THROW(solve(bad), std::invalid_argument);
  IkOptions o;
  o.starts = 0;
  EXPECT_THROW(solve(p, o), std::invalid_argument);
  o = {};
  o.position_tolerance = std::nan("");
  EXPECT_THROW(solve(p, o), std::invalid_argument);
  EXPECT_THROW(FindLink(robot, "no_such_link"), std::invalid_argument);
  EXPECT_THROW(DofIndices(robot, {"no_such_joint"}), std::invalid_argument);
  EXPECT_THROW(DofIndices(robot, {"sdh_finger_2_knuckle_joint"}), std::invalid_argument);  // mimic
  const Robot tiny = LoadRobot(AssetFile("robots/tinyarm/urdf/tinyarm.urdf"));
  EXPECT_THROW(SolveIk(tiny, p, {}, &data), std::invalid_argument);  // data of another robot
}

// The iterations allocate nothing: a run of 40 iterations makes as many mallocs as one of 2.
TEST(Ik, NoAllocationPerIteration) {
  const Robot& robot = Lwr();
  IkProblem problem;
  IkTarget t;
  t.link = FindLink(robot, "sdh_palm");
  t.position = Eigen::Vector3d(3.0, 0.0, 0.5);  // unreachable: runs every iteration
  t.axis = IkAxis{};
  problem.targets = {t};
  IkData data(robot);
  IkOptions options;
  options.starts = 1;
  long counts[2];
  int iterations[2];
  const int max_iterations[2] = {2, 40};
  SolveIk(robot, problem, options, &data);  // sizes the workspace
  for (int i = 0; i < 2; ++i) {
    options.max_iterations = max_iterations[i];
    const long before = g_mallocs.load();
    iterations[i] = SolveIk(robot, problem, options, &data).iterations;
    counts[i] = g_mallocs.load() - before;
  }
  EXPECT_LT(iterations[0], iterations[1]);
  EXPECT_GT(counts[0], 0);  // the counter works (SolveIk copies the targets)
  EXPECT_EQ(counts[0], counts[1]);
}

}  // namespace
}  // namespace planning
