// AICO on a planar 2-link arm: the end pose must match the analytic inverse kinematics, and
// accepted sweeps never raise the cost.
#include "planning/motion/aico.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planning/robot/robot_io.h"

namespace planning {
namespace {

constexpr double kL1 = 1.0, kL2 = 0.8;

constexpr char kPlanar2Link[] = R"(<?xml version="1.0"?>
<robot name="planar2">
  <link name="base"/>
  <link name="link1"/>
  <link name="link2"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="link1"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="revolute">
    <parent link="link1"/><child link="link2"/>
    <origin xyz="1.0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/>
  </joint>
</robot>)";

// Elbow-up/down solution with the sign of q2 given.
Eigen::Vector2d AnalyticIk(const Eigen::Vector2d& p, double elbow_sign) {
  const double c2 = (p.squaredNorm() - kL1 * kL1 - kL2 * kL2) / (2 * kL1 * kL2);
  const double q2 = elbow_sign * std::acos(c2);
  const double q1 =
      std::atan2(p.y(), p.x()) - std::atan2(kL2 * std::sin(q2), kL1 + kL2 * std::cos(q2));
  return {q1, q2};
}

MotionProblem ReachProblem(const Robot& robot, bool dynamic, const Eigen::Vector3d& goal) {
  MotionProblem p;
  p.robot = &robot;
  p.q0 = Eigen::Vector2d(0.3, 0.6);
  p.num_steps = 20;
  p.duration = 1.0;
  p.dynamic = dynamic;
  Task reach;
  reach.name = "reach";
  reach.feature = MakePositionFeature(robot, FindLink(robot, "link2"), Eigen::Vector3d(kL2, 0, 0));
  SetConstantTarget(&reach, goal, 0.0, p.num_steps);
  reach.precision[p.num_steps] = 1e4;
  p.tasks.push_back(std::move(reach));
  return p;
}

class AicoPlanarTest : public ::testing::TestWithParam<bool> {};

TEST_P(AicoPlanarTest, ReachesAnalyticIkSolution) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  const Eigen::Vector3d goal(0.4, 1.2, 0.0);
  MotionProblem problem = ReachProblem(robot, GetParam(), goal);
  AicoWorkspace ws(problem);
  AicoOptions options;
  options.max_iterations = 100;
  options.tolerance = 1e-4;
  const AicoResult r = SolveAico(problem, options, &ws);
  EXPECT_EQ(r.status, SolveStatus::kConverged) << StatusName(r.status);
  const Eigen::Vector2d q_end = r.trajectory.q.col(problem.num_steps);
  const Eigen::Vector2d ik = AnalyticIk(goal.head<2>(), q_end[1] >= 0 ? 1.0 : -1.0);
  EXPECT_NEAR(q_end[0], ik[0], 2e-3);
  EXPECT_NEAR(q_end[1], ik[1], 2e-3);
  // The start is fixed.
  EXPECT_TRUE(r.trajectory.q.col(0).isApprox(problem.q0, 1e-9));
  // Accepted sweeps never raise the cost.
  ASSERT_GE(r.cost_history.size(), 2u);
  for (size_t k = 1; k < r.cost_history.size(); ++k) {
    EXPECT_LE(r.cost_history[k], r.cost_history[k - 1] + 1e-12) << "sweep " << k;
  }
  EXPECT_LT(r.cost_history.back(), 0.05 * r.cost_history.front());
}

TEST_P(AicoPlanarTest, CallbackSeesEverySweepAndRejectionsRestore) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  MotionProblem problem = ReachProblem(robot, GetParam(), Eigen::Vector3d(-1.2, 0.6, 0));
  AicoWorkspace ws(problem);
  AicoOptions options;
  options.damping = 1e-3;  // small damping: large first steps, rejections likely
  options.max_iterations = 40;
  options.tolerance = 1e-5;
  int calls = 0, rejected = 0;
  double last_accepted = 1e300;
  const AicoResult r = SolveAico(problem, options, &ws,
                                 [&](int sweep, double cost, bool accepted, const Trajectory& tr) {
                                   EXPECT_EQ(sweep, calls);
                                   ++calls;
                                   EXPECT_EQ(tr.num_points(), problem.num_steps + 1);
                                   if (accepted) {
                                     EXPECT_LE(cost, last_accepted);
                                     last_accepted = cost;
                                   } else {
                                     ++rejected;
                                   }
                                 });
  EXPECT_EQ(calls, r.iterations);
  EXPECT_EQ(rejected, r.rejected);
  for (size_t k = 1; k < r.cost_history.size(); ++k) {
    EXPECT_LE(r.cost_history[k], r.cost_history[k - 1]);
  }
  EXPECT_GT(r.task_evaluations, problem.num_steps);
}

INSTANTIATE_TEST_SUITE_P(KinematicAndDynamic, AicoPlanarTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("Dynamic") : std::string("Kinematic");
                         });

// A task seen between the slices (Task::between): AICO's task message at slice t, linearised with
// the neighbours held at their estimates, has the gradient 2 (R_t q̂_t − r_t) of the whole task
// cost (slice and between terms, task.h) with respect to q_t; and the per-slice costs add up to
// TrajectoryCost's task part.
TEST_P(AicoPlanarTest, BetweenTaskMessageIsTheCostGradient) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  MotionProblem problem = ReachProblem(robot, GetParam(), Eigen::Vector3d(0.4, 1.2, 0.0));
  Task via;
  via.name = "via";
  via.feature = MakePositionFeature(robot, FindLink(robot, "link2"), Eigen::Vector3d(kL2, 0, 0));
  via.between = 3;
  SetConstantTarget(&via, Eigen::Vector3d(1.0, 0.9, 0.0), 2.0, problem.num_steps);
  problem.tasks.push_back(std::move(via));
  const int T = problem.num_steps;
  Trajectory init;
  init.dt = tau(problem);
  init.q.resize(2, T + 1);
  for (int t = 0; t <= T; ++t) {
    init.q.col(t) = problem.q0 + Eigen::Vector2d(0.9 * std::sin(0.4 * t), 0.05 * t);
  }
  AicoOptions options;
  options.max_iterations = 1;
  const AicoSolver solver(problem, options, &init);
  const AicoState& st = solver.state();
  Eigen::MatrixXd q(2, T + 1), qdot(2, T + 1);
  for (int t = 0; t <= T; ++t) {
    q.col(t) = st.xhat[t].head(2);
    qdot.col(t) = st.xhat[t].tail(2);
  }
  TaskWorkspace tw(problem);
  double task_cost = 0.0;
  TrajectoryCost(problem, q, qdot, &tw, &task_cost);
  double sum = 0.0;
  for (int t = 0; t <= T; ++t) sum += st.task_cost[t];
  EXPECT_NEAR(sum, task_cost, 1e-9 * std::max(1.0, task_cost));
  const double h = 1e-6;
  for (int t : {1, 7, T - 1, T}) {
    const Eigen::Vector2d grad = 2.0 * (st.R[t] * st.xhat[t] - st.r[t]).head(2);
    for (int k = 0; k < 2; ++k) {
      Eigen::MatrixXd qp = q, qm = q;
      qp(k, t) += h;
      qm(k, t) -= h;
      double cp = 0.0, cm = 0.0;
      TrajectoryCost(problem, qp, qdot, &tw, &cp);
      TrajectoryCost(problem, qm, qdot, &tw, &cm);
      EXPECT_NEAR(grad[k], (cp - cm) / (2 * h), 1e-5 * std::max(1.0, std::abs(grad[k])))
          << "slice " << t << " dof " << k;
    }
  }
}

// y = q_0 (dim 1): a feature whose jumps are easy to place.
class FirstJoint : public Feature {
 public:
  int dim() const override { return 1; }
  std::string name() const override { return "first_joint"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData*,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    y[0] = kin.q[0];
    if (J != nullptr) {
      J->setZero(1, num_dofs(robot));
      (*J)(0, 0) = 1.0;
    }
  }
};

TEST(Aico, CountJumpsSeesTheStatesBetweenSlices) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  MotionProblem problem = ReachProblem(robot, false, Eigen::Vector3d(0.4, 1.2, 0.0));
  problem.num_steps = 2;
  problem.tasks.clear();
  Task guard;
  guard.name = "guard";
  guard.feature = std::make_unique<FirstJoint>();
  SetConstantTarget(&guard, Eigen::VectorXd::Zero(1), 0.0, problem.num_steps);
  guard.between = 1;  // halves each step
  guard.max_jump = 0.4;
  problem.tasks.push_back(std::move(guard));
  ValidateProblem(problem);
  Eigen::MatrixXd q(2, 3);
  q << 0.0, 0.1, 1.0,  //
      0.0, 0.0, 0.0;
  TaskWorkspace ws(problem);
  EXPECT_EQ(CountJumps(problem, q, &ws), 2);  // 0.9 in two halves of 0.45
  problem.tasks[0].max_jump = 0.5;
  EXPECT_EQ(CountJumps(problem, q, &ws), 0);
  problem.tasks[0].between = 0;
  EXPECT_EQ(CountJumps(problem, q, &ws), 1);  // the whole step
  // Only order-0 tasks of dim 1.
  problem.tasks[0].feature = MakeJointPositionFeature(robot);
  problem.tasks[0].target.setZero(2, 3);
  EXPECT_THROW(ValidateProblem(problem), std::invalid_argument);
}

TEST(Aico, InvalidProblemThrows) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  MotionProblem problem = ReachProblem(robot, true, Eigen::Vector3d(0.4, 1.2, 0));
  AicoWorkspace ws(problem);
  problem.tasks[0].target.resize(2, problem.num_steps + 1);
  EXPECT_THROW(SolveAico(problem, AicoOptions{}, &ws), std::invalid_argument);
  MotionProblem velocity = ReachProblem(robot, true, Eigen::Vector3d(0.4, 1.2, 0));
  velocity.tasks[0].order = 1;
  velocity.tasks[0].between = 2;  // only order-0 tasks are seen between slices
  EXPECT_THROW(ValidateProblem(velocity), std::invalid_argument);
  const MotionProblem ok = ReachProblem(robot, true, Eigen::Vector3d(0.4, 1.2, 0));
  AicoWorkspace ws_ok(ok);
  for (double bad : {0.0, -0.5, 1.5, std::nan("")}) {
    AicoOptions o;
    o.relocation_damping = bad;
    EXPECT_THROW(SolveAico(ok, o, &ws_ok), std::invalid_argument) << bad;
  }
  AicoOptions none;
  none.max_relocations = 0;
  EXPECT_THROW(SolveAico(ok, none, &ws_ok), std::invalid_argument);
}

// Damped repeated relocations still solve the local problem: every relocation_damping in (0, 1]
// reaches the same optimum of the 2-link reach (local Gauss–Newton sweeps).
TEST(Aico, RelocationDampingKeepsTheOptimum) {
  const Robot robot = ParseRobot(kPlanar2Link, "planar2", ".");
  const MotionProblem problem = ReachProblem(robot, true, Eigen::Vector3d(0.4, 1.2, 0));
  AicoWorkspace ws(problem);
  Eigen::VectorXd reference;
  for (double damping : {1.0, 0.5, 0.3, 0.1}) {
    AicoOptions o;
    o.sweep_mode = SweepMode::kLocalGaussNewton;
    o.relocation_damping = damping;
    o.max_iterations = 200;
    o.tolerance = 1e-3;
    const AicoResult r = SolveAico(problem, o, &ws);
    EXPECT_EQ(r.status, SolveStatus::kConverged) << damping << ": " << StatusName(r.status);
    const Eigen::VectorXd q_end = r.trajectory.q.col(problem.num_steps);
    if (reference.size() == 0) reference = q_end;
    EXPECT_LT((q_end - reference).cwiseAbs().maxCoeff(), 1e-3) << damping;
  }
}

}  // namespace
}  // namespace planning
