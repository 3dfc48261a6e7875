// Goal-region RRT and BiRRT (goal_region.h): a 2-D toy whose goal region is a disc behind a wall,
// determinism per seed, the sampler's counted cost; and the scenario planners rrt-region /
// birrt-region (scenario_goal_region.h) on the shipped unwrap scenario.
#include "planning/motion/goal_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/random.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_goal_region.h"
#include "planning/motion/success.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

// The unit square with a wall x ∈ [0.45, 0.55] that has a gap at y ∈ [0.8, 0.9].
bool Free(const Eigen::VectorXd& q) {
  return !(q[0] > 0.45 && q[0] < 0.55 && !(q[1] > 0.8 && q[1] < 0.9));
}

// Goal region: the disc of radius 0.08 about (0.85, 0.15) behind the wall.
const Eigen::Vector2d kCentre(0.85, 0.15);
constexpr double kRadius = 0.08;
bool InDisc(const Eigen::VectorXd& q) { return (q - kCentre).norm() <= kRadius; }

// Sampler by projection and rejection, as the scenario sampler: a uniform draw in the square,
// projected onto the circle of radius 1.5·r (half of the draws land outside the disc: rejected),
// then G.
GoalRegionProblem ToyProblem(std::int64_t* draws, std::int64_t* sampler_checks) {
  GoalRegionProblem p;
  p.lower = Eigen::Vector2d(0, 0);
  p.upper = Eigen::Vector2d(1, 1);
  p.start = Eigen::Vector2d(0.1, 0.1);
  p.goal.contains = InDisc;
  p.goal.sample = [draws](std::mt19937* rng, Eigen::VectorXd* q) {
    ++*draws;
    Eigen::Vector2d u(base::UniformUnit(rng), base::UniformUnit(rng));
    const double radius = 1.5 * kRadius * base::UniformUnit(rng);
    const Eigen::Vector2d d = u - kCentre;
    *q = kCentre + (d.norm() > 0 ? radius / d.norm() : 0.0) * d;
    return InDisc(*q);
  };
  p.goal.valid = [sampler_checks](const Eigen::VectorXd& q) {
    ++*sampler_checks;
    return Free(q);
  };
  return p;
}

RrtOptions ToyOptions() {
  RrtOptions o;
  o.range = 0.1;
  o.resolution = 0.005;
  return o;
}

class GoalRegionToyTest : public ::testing::TestWithParam<bool> {};

TEST_P(GoalRegionToyTest, ReachesTheDiscCollisionFreeAndCountsTheSampler) {
  const bool bi = GetParam();
  GoalRegionOptions options;
  options.rrt = ToyOptions();
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    std::int64_t draws = 0, sampler_checks = 0, tree_checks = 0;
    const ValidityFn valid = [&tree_checks](const Eigen::VectorXd& q) {
      ++tree_checks;
      return Free(q);
    };
    const RrtResult r =
        PlanGoalRegion(ToyProblem(&draws, &sampler_checks), options, valid, seed, bi);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << "seed " << seed;
    ASSERT_GE(r.path.num_points(), 2);
    EXPECT_TRUE(r.path.q.col(0).isApprox(Eigen::Vector2d(0.1, 0.1)));
    EXPECT_TRUE(InDisc(r.path.q.col(r.path.num_points() - 1))) << "seed " << seed;
    EXPECT_TRUE(PathIsValid(r.path, options.rrt.resolution, Free));
    for (int t = 0; t + 1 < r.path.num_points(); ++t) {
      EXPECT_LE((r.path.q.col(t + 1) - r.path.q.col(t)).norm(), options.rrt.range + 1e-12);
    }
    // The sampler's cost: drawn, counted, and part of the planner's total.
    EXPECT_EQ(r.goal.draws, draws);
    EXPECT_GT(r.goal.checks, 0);
    EXPECT_EQ(r.goal.checks, sampler_checks);
    EXPECT_EQ(r.checks, tree_checks + sampler_checks);
    EXPECT_GE(r.goal.in_region, r.goal.samples);
    EXPECT_GE(r.goal.draws, r.goal.in_region);
    EXPECT_GT(r.goal.samples, 0);
    EXPECT_LE(r.goal.samples, options.max_goal_states);
  }
}

TEST_P(GoalRegionToyTest, SameSeedSameResultAndSteppingChangesNothing) {
  const bool bi = GetParam();
  GoalRegionOptions options;
  options.rrt = ToyOptions();
  std::int64_t d1 = 0, c1 = 0, d2 = 0, c2 = 0, d3 = 0, c3 = 0;
  const RrtResult a = PlanGoalRegion(ToyProblem(&d1, &c1), options, Free, 11, bi);
  const RrtResult b = PlanGoalRegion(ToyProblem(&d2, &c2), options, Free, 11, bi);
  GoalRegionSolver stepped(ToyProblem(&d3, &c3), options, Free, 11, bi);
  while (!stepped.done()) stepped.Step(1);
  const RrtResult c = stepped.result();
  for (const RrtResult* other : {&b, &c}) {
    EXPECT_EQ(a.status, other->status);
    EXPECT_EQ(a.checks, other->checks);
    EXPECT_EQ(a.iterations, other->iterations);
    EXPECT_EQ(a.goal.draws, other->goal.draws);
    EXPECT_EQ(a.goal.samples, other->goal.samples);
    EXPECT_EQ(a.path.q, other->path.q);
  }
  EXPECT_EQ(static_cast<std::int64_t>(stepped.goal_states().size()), c.goal.samples);
  // Another seed: another run.
  std::int64_t d4 = 0, c4 = 0;
  const RrtResult other = PlanGoalRegion(ToyProblem(&d4, &c4), options, Free, 12, bi);
  EXPECT_FALSE(other.path.q.rows() == a.path.q.rows() && other.path.q.cols() == a.path.q.cols() &&
               other.path.q == a.path.q);
}

TEST_P(GoalRegionToyTest, BudgetIncludesTheSamplerAndEmptyRegionExhaustsIt) {
  const bool bi = GetParam();
  GoalRegionOptions options;
  options.rrt = ToyOptions();
  options.rrt.max_checks = 500;
  std::int64_t draws = 0, sampler_checks = 0;
  GoalRegionProblem p = ToyProblem(&draws, &sampler_checks);
  p.goal.sample = [](std::mt19937* rng, Eigen::VectorXd* q) {  // never in the region
    *q = Eigen::Vector2d(base::UniformUnit(rng), 0.5);
    return false;
  };
  const RrtResult r = PlanGoalRegion(p, options, Free, 3, bi);
  EXPECT_EQ(r.status, SolveStatus::kBudgetExhausted);
  EXPECT_EQ(r.checks, 500);
  EXPECT_EQ(r.goal.samples, 0);
  EXPECT_GT(r.goal.draws, 0);
}

INSTANTIATE_TEST_SUITE_P(UniAndBi, GoalRegionToyTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return std::string(info.param ? "BiRrt" : "Rrt");
                         });

TEST(GoalRegion, StartInTheRegionIsAOnePointPath) {
  std::int64_t draws = 0, checks = 0;
  GoalRegionProblem p = ToyProblem(&draws, &checks);
  p.start = kCentre;
  const RrtResult r = PlanGoalRegion(p, GoalRegionOptions{}, Free, 0, false);
  EXPECT_EQ(r.status, SolveStatus::kConverged);
  EXPECT_EQ(r.path.num_points(), 1);
  EXPECT_EQ(r.checks, 1);
}

TEST(GoalRegion, InvalidStartAndBadInput) {
  std::int64_t draws = 0, checks = 0;
  GoalRegionProblem p = ToyProblem(&draws, &checks);
  p.start = Eigen::Vector2d(0.5, 0.5);  // in the wall
  EXPECT_EQ(PlanGoalRegion(p, GoalRegionOptions{}, Free, 0, true).status,
            SolveStatus::kInvalidInput);
  p.start = Eigen::Vector3d(0.1, 0.1, 0.1);
  EXPECT_THROW(PlanGoalRegion(p, GoalRegionOptions{}, Free, 0, true), std::invalid_argument);
  p = ToyProblem(&draws, &checks);
  p.goal.sample = nullptr;
  EXPECT_THROW(PlanGoalRegion(p, GoalRegionOptions{}, Free, 0, true), std::invalid_argument);
  p = ToyProblem(&draws, &checks);
  GoalRegionOptions o;
  o.max_goal_states = 0;
  EXPECT_THROW(PlanGoalRegion(p, o, Free, 0, true), std::invalid_argument);
}

TEST(GoalRegionPlanners, AreRegistered) {
  EXPECT_EQ(ParsePlanner("rrt-region"), Planner::kRrtRegion);
  EXPECT_EQ(ParsePlanner("birrt-region"), Planner::kBiRrtRegion);
  EXPECT_STREQ(PlannerName(Planner::kBiRrtRegion), "birrt-region");
  EXPECT_FALSE(IsAico(Planner::kRrtRegion));
}

// The shipped unwrap scenario at 360°: birrt-region reaches the goal region; its last state meets
// the criterion's end conditions; the sampler's cost is part of the totals.
TEST(GoalRegionPlanners, BiRrtRegionUnwrapsFrom360Degrees) {
  ScenarioOverrides o;
  o.start_wrap_deg = 360.0;
  const auto s = LoadScenario(kAssets + "scenarios/unwrap.json", o);
  const PlanResult a = RunPlanner(*s, Planner::kBiRrtRegion, 0);
  const PlanReport& r = a.report;
  EXPECT_EQ(r.planner, "birrt-region");
  ASSERT_TRUE(r.success) << FailureReasonName(r.failure_reason);
  const Trajectory& path = a.trajectory;
  EXPECT_TRUE(CheckEndState(*s, path.q.col(path.num_points() - 1), true).ok());
  EXPECT_TRUE(JudgePlan(*s, path).ok());
  EXPECT_GT(r.goal_samples, 0);
  EXPECT_GE(r.goal_sampler_draws, r.goal_samples);
  EXPECT_GT(r.goal_sampler_counts.state_queries, 0);
  EXPECT_GT(r.goal_sampler_counts.pair_tests(), 0);
  EXPECT_LT(r.goal_sampler_counts.state_queries, r.counts.state_queries);
  EXPECT_LE(r.goal_sampler_counts.bool_pair_tests, r.counts.bool_pair_tests);
  EXPECT_GT(r.goal_sampler_cpu_time_s, 0.0);
  EXPECT_LE(r.goal_sampler_cpu_time_s, r.cpu_time_s);
  EXPECT_EQ(r.counts.state_queries, r.collision_checks);
  // Deterministic per seed (the cost counts; times are measured).
  const PlanReport again = RunPlanner(*s, Planner::kBiRrtRegion, 0).report;
  EXPECT_EQ(again.counts, r.counts);
  EXPECT_EQ(again.goal_sampler_counts, r.goal_sampler_counts);
  EXPECT_EQ(again.goal_samples, r.goal_samples);
}

// The shipped unwrap.json at 360° with `rrt_keys` (", \"key\": value" ...) added to its rrt object
// (after max_checks, which `max_checks` replaces), written next to the tests with absolute asset
// paths.
std::unique_ptr<Scenario> UnwrapWithRrtKeys(const std::string& name, const std::string& max_checks,
                                            const std::string& rrt_keys) {
  std::ifstream in(kAssets + "scenarios/unwrap.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string from = "\"max_checks\": 100000}";
  const size_t at = json.find(from);
  if (at == std::string::npos) throw std::runtime_error("unwrap.json: no rrt.max_checks");
  json.replace(at, from.size(), "\"max_checks\": " + max_checks + rrt_keys + "}");
  for (const std::string dir : {"robots", "objects"}) {
    for (size_t p; (p = json.find("\"../" + dir + "/")) != std::string::npos;) {
      json.replace(p, dir.size() + 5, "\"" + kAssets + dir + "/");
    }
  }
  const std::filesystem::path path =
      std::filesystem::path(TOPOPLAN_BINARY_DIR) / ("goal_region_test_" + name + ".json");
  std::ofstream(path) << json;
  ScenarioOverrides o;
  o.start_wrap_deg = 360.0;
  return LoadScenario(path.string(), o);
}

// rrt.goal_states in the scenario file caps the goal states of every goal-region tree that keeps a
// pool or a goal forest (rrt-region, birrt-region, ompl-rrt-region): with 1, each run keeps one,
// where the shipped 32 lets birrt-region root more at 360°.
TEST(GoalRegionPlanners, ScenarioGoalStatesCapsTheGoalStates) {
  const auto one = UnwrapWithRrtKeys("goal_states_1", "100000", ", \"goal_states\": 1");
  ScenarioOverrides o;
  o.start_wrap_deg = 360.0;
  const auto shipped = LoadScenario(kAssets + "scenarios/unwrap.json", o);
  ASSERT_EQ(one->rrt_goal.max_goal_states, 1);
  ASSERT_EQ(shipped->rrt_goal.max_goal_states, 32);
  EXPECT_GT(RunPlanner(*shipped, Planner::kBiRrtRegion, 0).report.goal_samples, 1);
  std::vector<Planner> planners = {Planner::kRrtRegion, Planner::kBiRrtRegion};
  if (OmplAvailable()) planners.push_back(Planner::kOmplRrtRegion);
  for (Planner planner : planners) {
    SCOPED_TRACE(PlannerName(planner));
    const PlanReport r = RunPlanner(*one, planner, 0).report;
    EXPECT_EQ(r.goal_samples, 1);
    EXPECT_GT(r.goal_sampler_draws, 0);
  }
}

// rrt.goal_ik_iterations and rrt.goal_ik_starts set the sampler's effort: with one IK iteration a
// uniform start never comes within the reach tolerance, so no draw is a goal state; with 8 starts
// per draw more of the same number of draws are in the region than with the shipped 1.
TEST(GoalRegionPlanners, ScenarioIkKeysSetTheSamplersEffort) {
  const auto one_iteration =
      UnwrapWithRrtKeys("goal_ik_iterations_1", "3000", ", \"goal_ik_iterations\": 1");
  ASSERT_EQ(one_iteration->rrt_goal.ik_iterations, 1);
  ASSERT_EQ(one_iteration->rrt_goal.ik_starts, 1);
  for (Planner planner : {Planner::kRrtRegion, Planner::kBiRrtRegion}) {
    SCOPED_TRACE(PlannerName(planner));
    const PlanReport r = RunPlanner(*one_iteration, planner, 0).report;
    EXPECT_FALSE(r.success);
    EXPECT_GT(r.goal_sampler_draws, 0);
    EXPECT_EQ(r.goal_samples, 0);
  }
  const auto shipped = UnwrapWithRrtKeys("goal_ik_shipped", "3000", "");
  const auto eight = UnwrapWithRrtKeys("goal_ik_starts_8", "3000", ", \"goal_ik_starts\": 8");
  ASSERT_EQ(shipped->rrt_goal.ik_iterations, 200);
  ASSERT_EQ(eight->rrt_goal.ik_starts, 8);
  const auto in_region = [](const Scenario& s) {
    CollisionData coll(s.robot, s.initial.env, s.collision);
    GoalSamplerCost cost;
    const GoalRegion region = ScenarioGoalRegion(
        s, s.initial, [](const Eigen::VectorXd&) { return true; }, coll, &cost);
    std::mt19937 rng(7);
    Eigen::VectorXd q;
    int in = 0;
    for (int k = 0; k < 12; ++k) {
      const bool drawn_in = region.sample(&rng, &q);
      EXPECT_EQ(drawn_in, region.contains(q));
      in += drawn_in ? 1 : 0;
    }
    return in;
  };
  const int in_one = in_region(*shipped), in_eight = in_region(*eight);
  EXPECT_GT(in_eight, in_one) << in_one << " vs " << in_eight;
  EXPECT_GE(in_eight, 6);
}

}  // namespace
}  // namespace planning
