// RRT and BiRRT on a 2-D toy world: the unit square with a wall at x ∈ [0.45, 0.55] that has a
// gap at y ∈ [0.8, 0.9] (or no gap), plus a disc obstacle.
#include "planning/motion/rrt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/random.h"
#include "planning/motion/unwrap_benchmark.h"

namespace planning {
namespace {

bool FreeWithGap(const Eigen::VectorXd& q) {
  const bool in_wall = q[0] > 0.45 && q[0] < 0.55 && !(q[1] > 0.8 && q[1] < 0.9);
  const bool in_disc = (q - Eigen::Vector2d(0.2, 0.5)).norm() < 0.1;
  return !in_wall && !in_disc;
}

bool FreeClosedWall(const Eigen::VectorXd& q) { return !(q[0] > 0.45 && q[0] < 0.55); }

RrtProblem Toy() {
  RrtProblem p;
  p.lower = Eigen::Vector2d(0, 0);
  p.upper = Eigen::Vector2d(1, 1);
  p.start = Eigen::Vector2d(0.1, 0.1);
  p.goal = Eigen::Vector2d(0.9, 0.1);
  return p;
}

using Planner = RrtResult (*)(const RrtProblem&, const RrtOptions&, const ValidityFn&,
                              std::mt19937*);

class RrtToyTest : public ::testing::TestWithParam<int> {
 protected:
  Planner planner() const { return GetParam() == 0 ? &PlanRrt : &PlanBiRrt; }
};

TEST_P(RrtToyTest, FindsCollisionFreePathThroughGap) {
  RrtOptions options;
  options.range = 0.1;
  options.resolution = 0.005;
  std::int64_t counted = 0;
  const ValidityFn valid = [&counted](const Eigen::VectorXd& q) {
    ++counted;
    return FreeWithGap(q);
  };
  for (unsigned seed = 0; seed < 5; ++seed) {
    std::mt19937 rng(seed);
    counted = 0;
    const RrtResult r = planner()(Toy(), options, valid, &rng);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << "seed " << seed;
    EXPECT_EQ(r.checks, counted);
    ASSERT_GE(r.path.num_points(), 2);
    EXPECT_TRUE(r.path.q.col(0).isApprox(Toy().start));
    EXPECT_TRUE(r.path.q.col(r.path.num_points() - 1).isApprox(Toy().goal));
    // Collision-free at the edge resolution, and no edge longer than the range.
    EXPECT_TRUE(PathIsValid(r.path, options.resolution, FreeWithGap));
    for (int t = 0; t + 1 < r.path.num_points(); ++t) {
      EXPECT_LE((r.path.q.col(t + 1) - r.path.q.col(t)).norm(), options.range + 1e-12);
    }
    // The path must go through the gap.
    bool through_gap = false;
    const Trajectory dense = Densify(r.path, 0.005);
    for (int t = 0; t < dense.num_points(); ++t) {
      if (dense.q(0, t) > 0.46 && dense.q(0, t) < 0.54) through_gap |= dense.q(1, t) > 0.79;
    }
    EXPECT_TRUE(through_gap);
  }
}

TEST_P(RrtToyTest, SameSeedSameResult) {
  RrtOptions options;
  options.range = 0.1;
  options.resolution = 0.01;
  std::mt19937 rng1(7), rng2(7);
  const RrtResult a = planner()(Toy(), options, FreeWithGap, &rng1);
  const RrtResult b = planner()(Toy(), options, FreeWithGap, &rng2);
  EXPECT_EQ(a.checks, b.checks);
  EXPECT_EQ(a.iterations, b.iterations);
  ASSERT_EQ(a.path.q.cols(), b.path.q.cols());
  EXPECT_EQ(a.path.q, b.path.q);
}

TEST_P(RrtToyTest, BudgetExhaustedWhenNoPathExists) {
  RrtOptions options;
  options.range = 0.1;
  options.resolution = 0.01;
  options.max_checks = 3000;
  std::mt19937 rng(1);
  const RrtResult r = planner()(Toy(), options, FreeClosedWall, &rng);
  EXPECT_EQ(r.status, SolveStatus::kBudgetExhausted);
  EXPECT_EQ(r.checks, options.max_checks);
  EXPECT_EQ(r.path.num_points(), 0);
}

TEST_P(RrtToyTest, InvalidStartIsAStatus) {
  RrtProblem p = Toy();
  p.start = Eigen::Vector2d(0.5, 0.5);
  std::mt19937 rng(0);
  EXPECT_EQ(planner()(p, RrtOptions{}, FreeWithGap, &rng).status, SolveStatus::kInvalidInput);
}

TEST_P(RrtToyTest, BadSizesThrow) {
  RrtProblem p = Toy();
  p.goal = Eigen::Vector3d(1, 1, 1);
  std::mt19937 rng(0);
  EXPECT_THROW(planner()(p, RrtOptions{}, FreeWithGap, &rng), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(UniAndBi, RrtToyTest, ::testing::Values(0, 1),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return info.param == 0 ? std::string("Rrt") : std::string("BiRrt");
                         });

TEST(PathIsValid, DetectsCollisionInsideAnEdge) {
  Trajectory path;
  path.q.resize(2, 2);
  path.q << 0.1, 0.9, 0.5, 0.5;  // straight through the wall
  std::int64_t checks = 0;
  EXPECT_FALSE(PathIsValid(path, 0.01, FreeClosedWall, &checks));
  EXPECT_GT(checks, 2);
}

// The portable mapping of planning/random.h: the first values for seed 42 are pinned (UniformUnit
// equals genrand_res53 of the reference MT19937, e.g. numpy's RandomState(42).random_sample()).
TEST(PortableRandom, FirstValuesArePinned) {
  std::mt19937 rng(42);
  EXPECT_EQ(base::UniformUnit(&rng), 0.37454011884736249);
  EXPECT_EQ(base::UniformUnit(&rng), 0.95071430640991617);
  EXPECT_EQ(base::UniformUnit(&rng), 0.73199394181140509);
  std::mt19937 pick(42);
  const std::uint32_t expected[] = {3, 7, 9, 1, 7, 7};
  for (std::uint32_t e : expected) EXPECT_EQ(base::UniformIndex(&pick, 10), e);
}

// The unwrap benchmark's pole offsets use the same mapping: r = M·√u1, φ = 2π·u2 in the plane
// (e1, e2) = (ŷ, −x̂) perpendicular to ẑ. Expected values computed independently from numpy's
// RandomState(seed).random_sample(2) (the same genrand_res53 draws).
TEST(PortableRandom, UnwrapPoleOffsetsArePinned) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d expected[] = {{0.021695097565054264, -0.004822332960027625, 0.0},
                                      {0.01903738196154783, -0.003591363568681098, 0.0},
                                      {-0.0032126156720750938, 0.01954672638759086, 0.0}};
  for (int seed = 0; seed < 3; ++seed) {
    const Eigen::Vector3d offset = UnwrapPoleOffset(seed, 0.03, z);
    EXPECT_NEAR((offset - expected[seed]).norm(), 0.0, 1e-15) << "seed " << seed;
    EXPECT_LE(offset.norm(), 0.03);
  }
  EXPECT_EQ(UnwrapPoleOffset(5, 0.0, z), Eigen::Vector3d::Zero());
}

TEST(PortableRandom, IndexStaysInRangeAndCoversIt) {
  std::mt19937 rng(1);
  int seen[7] = {};
  for (int i = 0; i < 7000; ++i) {
    const std::uint32_t k = base::UniformIndex(&rng, 7);
    ASSERT_LT(k, 7u);
    ++seen[k];
  }
  for (int c : seen) EXPECT_GT(c, 850);
  EXPECT_EQ(base::UniformIndex(&rng, 1), 0u);
  EXPECT_THROW(base::UniformIndex(&rng, 0), std::invalid_argument);
}

// A resolution so fine that the step count would overflow is refused, never silently fewer checks.
TEST(EdgeSteps, TinyResolutionIsRefused) {
  EXPECT_EQ(EdgeSteps(1.0, 0.1), 10);
  EXPECT_EQ(EdgeSteps(0.0, 0.1), 1);
  EXPECT_THROW(EdgeSteps(1.0, 1e-300), std::invalid_argument);
  EXPECT_THROW(EdgeSteps(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(EdgeSteps(1.0, std::nan("")), std::invalid_argument);
  Trajectory path;
  path.q.resize(2, 2);
  path.q << 0.1, 0.9, 0.1, 0.1;
  EXPECT_THROW(PathIsValid(path, 1e-12, FreeClosedWall), std::invalid_argument);
  EXPECT_THROW(Densify(path, 1e-12), std::invalid_argument);
  RrtOptions options;
  options.resolution = 1e-300;
  std::mt19937 rng(0);
  EXPECT_THROW(PlanBiRrt(Toy(), options, FreeWithGap, &rng), std::invalid_argument);
}

}  // namespace
}  // namespace planning
