// RrtSolver: Step(1) repeated equals one run to the end and PlanRrt / PlanBiRrt, bit for bit
// (paths, checks, iterations, trees, generator state); the trees are readable between steps and
// RequestStop ends a run.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "planning/motion/rrt.h"

namespace planning {
namespace {

// The unit square with a wall at x ∈ [0.45, 0.55] open only at y ∈ [0.8, 0.9].
bool Free(const Eigen::VectorXd& q) {
  return !(q[0] > 0.45 && q[0] < 0.55 && !(q[1] > 0.8 && q[1] < 0.9));
}

RrtProblem Square() {
  RrtProblem p;
  p.lower = Eigen::Vector2d(0, 0);
  p.upper = Eigen::Vector2d(1, 1);
  p.start = Eigen::Vector2d(0.1, 0.2);
  p.goal = Eigen::Vector2d(0.9, 0.2);
  return p;
}

RrtOptions Options() {
  RrtOptions o;
  o.range = 0.08;
  o.resolution = 0.004;
  return o;
}

void ExpectSameTrees(const RrtSolver& a, const RrtSolver& b) {
  ASSERT_EQ(a.num_trees(), b.num_trees());
  for (int i = 0; i < a.num_trees(); ++i) {
    ASSERT_EQ(a.tree(i).size(), b.tree(i).size());
    for (size_t k = 0; k < a.tree(i).size(); ++k) {
      EXPECT_TRUE(a.tree(i)[k].q == b.tree(i)[k].q);
      EXPECT_EQ(a.tree(i)[k].parent, b.tree(i)[k].parent);
    }
  }
}

void ExpectSameResult(const RrtResult& a, const RrtResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.checks, b.checks);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.tree_size, b.tree_size);
  EXPECT_TRUE(a.path.q == b.path.q);
}

class RrtStepTest : public ::testing::TestWithParam<bool> {};

TEST_P(RrtStepTest, StepOneEqualsOneShot) {
  const bool bi = GetParam();
  RrtOptions options = Options();
  for (std::uint64_t seed : {0u, 1u, 7u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(static_cast<std::mt19937::result_type>(seed));
    const RrtResult planned =
        bi ? PlanBiRrt(Square(), options, Free, &rng) : PlanRrt(Square(), options, Free, &rng);
    EXPECT_EQ(planned.status, SolveStatus::kConverged);

    RrtSolver whole(Square(), options, Free, seed, bi);
    EXPECT_EQ(whole.num_trees(), bi ? 2 : 1);
    whole.Step(options.max_iterations);
    EXPECT_TRUE(whole.done());
    ExpectSameResult(whole.result(), planned);
    EXPECT_TRUE(whole.rng() == rng);  // the generator advanced alike

    RrtSolver stepped(Square(), options, Free, seed, bi);
    std::int64_t steps = 0;
    size_t nodes = 1;
    while (!stepped.done()) {
      const std::int64_t k = stepped.Step(1);
      EXPECT_LE(k, 1);
      steps += k;
      EXPECT_EQ(stepped.iterations(), steps);
      size_t now = 0;
      for (int i = 0; i < stepped.num_trees(); ++i) {
        now += stepped.tree(i).size();
        for (const RrtNode& node : stepped.tree(i)) {
          EXPECT_LT(node.parent, static_cast<int>(stepped.tree(i).size()));
        }
      }
      EXPECT_GE(now, nodes);  // trees only grow
      nodes = now;
      if (!stepped.done()) {
        EXPECT_EQ(stepped.status(), SolveStatus::kBudgetExhausted);
      }
    }
    EXPECT_EQ(stepped.Step(5), 0);  // no-op once done
    ExpectSameResult(stepped.result(), planned);
    EXPECT_EQ(stepped.checks(), planned.checks);
    ExpectSameTrees(stepped, whole);
  }
}

TEST_P(RrtStepTest, BudgetAndStop) {
  const bool bi = GetParam();
  // A closed wall: no path; the budget ends the run, in chunks as in one go.
  const ValidityFn closed = [](const Eigen::VectorXd& q) { return !(q[0] > 0.45 && q[0] < 0.55); };
  RrtOptions options = Options();
  options.max_checks = 3000;
  std::mt19937 rng(3);
  const RrtResult planned =
      bi ? PlanBiRrt(Square(), options, closed, &rng) : PlanRrt(Square(), options, closed, &rng);
  EXPECT_EQ(planned.status, SolveStatus::kBudgetExhausted);
  RrtSolver chunked(Square(), options, closed, std::uint64_t{3}, bi);
  while (!chunked.done()) chunked.Step(17);
  ExpectSameResult(chunked.result(), planned);

  RrtSolver stopped(Square(), options, closed, std::uint64_t{3}, bi);
  EXPECT_EQ(stopped.Step(10), 10);
  stopped.RequestStop();
  EXPECT_TRUE(stopped.stop_requested());
  EXPECT_TRUE(stopped.done());
  EXPECT_EQ(stopped.Step(10), 0);
  EXPECT_EQ(stopped.iterations(), 10);
  EXPECT_EQ(stopped.status(), SolveStatus::kBudgetExhausted);
  EXPECT_THROW(stopped.tree(2), std::invalid_argument);
}

TEST_P(RrtStepTest, InvalidStartIsDoneAtOnce) {
  RrtProblem p = Square();
  p.start = Eigen::Vector2d(0.5, 0.2);  // in the wall
  RrtSolver solver(p, Options(), Free, std::uint64_t{0}, GetParam());
  EXPECT_TRUE(solver.done());
  EXPECT_EQ(solver.status(), SolveStatus::kInvalidInput);
  EXPECT_EQ(solver.Step(1), 0);
  EXPECT_EQ(solver.result().tree_size, 0);
}

INSTANTIATE_TEST_SUITE_P(UniAndBi, RrtStepTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("BiRrt") : std::string("Rrt");
                         });

}  // namespace
}  // namespace planning
