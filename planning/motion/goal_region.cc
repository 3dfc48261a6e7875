#include "planning/motion/goal_region.h"

#include <atomic>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/random.h"
#include "base/str_cat.h"
#include "planning/motion/internal/rrt_tree.h"

namespace planning {

using internal::BranchPath;
using internal::CheckEdge;
using internal::Checker;
using internal::EdgeResult;
using internal::Nearest;
using internal::Steer;

struct GoalRegionSolver::Impl {
  Impl(const GoalRegionProblem& p, const GoalRegionOptions& o, ValidityFn v, std::uint64_t seed,
       bool bi)
      : problem(p),
        options(o),
        valid(std::move(v)),
        goal_valid(p.goal.valid ? p.goal.valid : valid),
        rng(static_cast<std::mt19937::result_type>(seed)),
        bidirectional(bi),
        check{valid, o.rrt.max_checks},
        goal_check{goal_valid, std::numeric_limits<std::int64_t>::max()} {}

  std::int64_t checks() const { return check.count + goal_check.count; }
  bool exhausted() const { return checks() >= options.rrt.max_checks; }
  void Finish(SolveStatus s) {
    status = s;
    done = true;
  }
  // At most one draw of the sampler when the goal states are below the lazy rule for a tree of
  // `feed_nodes` nodes (goal_region.h); a valid candidate becomes a goal state. Returns whether a
  // goal state was added; false with done set when the budget ran out.
  bool MaybeAddGoal(int feed_nodes);
  // A tree edge toward q_rand from the nearest node of `tree` (*near) to q_new.
  EdgeResult Extend(const std::vector<RrtNode>& tree, int* near);
  void IterateRrt();
  void IterateBiRrt();

  const GoalRegionProblem problem;
  const GoalRegionOptions options;
  const ValidityFn valid;
  const ValidityFn goal_valid;
  std::mt19937 rng;
  const bool bidirectional;
  Checker check;       // tree edges (and the start)
  Checker goal_check;  // sampled candidates (no limit of its own: the budget is on the sum)
  double range = 0.0, resolution = 0.0;
  Eigen::VectorXd q_rand{}, q_new{}, tmp{}, candidate{};
  std::vector<RrtNode> trees[2];
  std::vector<Eigen::VectorXd> goals;
  GoalSamplerStats stats;
  int grow = 0;
  std::int64_t iterations = 0;
  SolveStatus status = SolveStatus::kBudgetExhausted;
  bool done = false;
  std::atomic<bool> stop{false};
  Trajectory path;
};

bool GoalRegionSolver::Impl::MaybeAddGoal(int feed_nodes) {
  const int m = static_cast<int>(goals.size());
  if (m >= options.max_goal_states || (m > 0 && m >= feed_nodes / 2)) return false;
  ++stats.draws;
  if (!problem.goal.sample(&rng, &candidate)) return false;
  ++stats.in_region;
  if (exhausted()) {
    Finish(SolveStatus::kBudgetExhausted);
    return false;
  }
  ++stats.checks;
  if (!goal_check(candidate)) return false;
  ++stats.samples;
  goals.push_back(candidate);
  return true;
}

EdgeResult GoalRegionSolver::Impl::Extend(const std::vector<RrtNode>& tree, int* near) {
  *near = Nearest(tree, q_rand);
  Steer(tree[*near].q, q_rand, range, &q_new);
  // The edge checker stops at the budget left after the sampler's checks.
  check.max_checks = options.rrt.max_checks - goal_check.count;
  return CheckEdge(tree[*near].q, q_new, resolution, &check, &tmp);
}

void GoalRegionSolver::Impl::IterateRrt() {
  std::vector<RrtNode>& tree = trees[0];
  ++iterations;
  bool to_goal = base::UniformUnit(&rng) < options.rrt.goal_bias;
  if (to_goal) {
    MaybeAddGoal(static_cast<int>(tree.size()));
    if (done) return;
    to_goal = !goals.empty();
  }
  if (to_goal) {
    q_rand = goals[base::UniformIndex(&rng, static_cast<std::uint32_t>(goals.size()))];
  } else {
    internal::SampleUniform(problem.lower, problem.upper, &rng, &q_rand);
  }
  int near = 0;
  const EdgeResult edge = Extend(tree, &near);
  if (edge == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
  if (edge == EdgeResult::kInvalid) return;
  tree.push_back({q_new, near});
  ++stats.region_tests;
  if (problem.goal.contains(q_new)) {
    path = BranchPath(tree, static_cast<int>(tree.size()) - 1, nullptr, -1);
    Finish(SolveStatus::kConverged);
  }
}

void GoalRegionSolver::Impl::IterateBiRrt() {
  ++iterations;
  if (MaybeAddGoal(static_cast<int>(trees[1].size()))) trees[1].push_back({goals.back(), -1});
  if (done) return;
  if (trees[1].empty()) grow = 0;  // no goal state yet: only the start tree grows
  std::vector<RrtNode>& a = trees[grow];
  std::vector<RrtNode>& b = trees[1 - grow];
  if (!b.empty() && base::UniformUnit(&rng) < options.rrt.goal_bias) {
    q_rand = b[base::UniformIndex(&rng, static_cast<std::uint32_t>(b.size()))].q;
  } else {
    internal::SampleUniform(problem.lower, problem.upper, &rng, &q_rand);
  }
  int near = 0;
  const EdgeResult edge = Extend(a, &near);
  if (edge == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
  if (edge == EdgeResult::kValid) {
    a.push_back({q_new, near});
    const int added = static_cast<int>(a.size()) - 1;
    // Join through the other tree's nearest node (none yet: no goal state).
    const int other = b.empty() ? -1 : Nearest(b, q_new);
    if (other >= 0 && (b[other].q - q_new).norm() <= range) {
      check.max_checks = options.rrt.max_checks - goal_check.count;
      const EdgeResult join = CheckEdge(q_new, b[other].q, resolution, &check, &tmp);
      if (join == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
      if (join == EdgeResult::kValid) {
        const int start_end = grow == 0 ? added : other;
        const int goal_end = grow == 0 ? other : added;
        path = BranchPath(trees[0], start_end, &trees[1], goal_end);
        return Finish(SolveStatus::kConverged);
      }
    }
  }
  grow = 1 - grow;
}

GoalRegionSolver::GoalRegionSolver(const GoalRegionProblem& problem,
                                   const GoalRegionOptions& options, ValidityFn valid,
                                   std::uint64_t seed, bool bidirectional) {
  internal::CheckBox("goal-region RRT", problem.lower, problem.upper, problem.start, nullptr);
  if (!problem.goal.contains || !problem.goal.sample) {
    throw std::invalid_argument("goal-region RRT: the goal region needs contains and sample");
  }
  if (options.max_goal_states < 1) {
    throw std::invalid_argument(base::StrCat("goal-region RRT: max_goal_states must be >= 1, got ",
                                             std::to_string(options.max_goal_states)));
  }
  if (!valid) throw std::invalid_argument("goal-region RRT: no validity function");
  impl_ = std::make_unique<Impl>(problem, options, std::move(valid), seed, bidirectional);
  Impl& m = *impl_;
  internal::RangeAndResolution(options.rrt, problem.lower, problem.upper, &m.range, &m.resolution);
  const Eigen::Index n = problem.start.size();
  m.q_rand.resize(n);
  m.q_new.resize(n);
  m.tmp.resize(n);
  m.candidate.resize(n);
  if (m.exhausted() || !m.check(problem.start)) {
    m.Finish(SolveStatus::kInvalidInput);
    return;
  }
  m.trees[0].push_back({problem.start, -1});
  ++m.stats.region_tests;
  if (problem.goal.contains(problem.start)) {
    m.path = BranchPath(m.trees[0], 0, nullptr, -1);
    m.Finish(SolveStatus::kConverged);
  }
}

GoalRegionSolver::~GoalRegionSolver() = default;

std::int64_t GoalRegionSolver::Step(std::int64_t k) {
  Impl& m = *impl_;
  std::int64_t done_now = 0;
  for (; done_now < k && !m.done; ++done_now) {
    if (m.stop.load(std::memory_order_relaxed) || m.exhausted() ||
        m.iterations >= m.options.rrt.max_iterations) {
      m.Finish(SolveStatus::kBudgetExhausted);
      break;
    }
    if (m.bidirectional) {
      m.IterateBiRrt();
    } else {
      m.IterateRrt();
    }
  }
  return done_now;
}

void GoalRegionSolver::RequestStop() { impl_->stop.store(true); }
bool GoalRegionSolver::done() const { return impl_->done || impl_->stop.load(); }
SolveStatus GoalRegionSolver::status() const { return impl_->status; }
int GoalRegionSolver::num_trees() const { return impl_->bidirectional ? 2 : 1; }

const std::vector<RrtNode>& GoalRegionSolver::tree(int i) const {
  if (i < 0 || i >= num_trees()) {
    throw std::invalid_argument(base::StrCat("GoalRegionSolver::tree: index ", std::to_string(i),
                                             " of ", std::to_string(num_trees()), " trees"));
  }
  return impl_->trees[i];
}

const std::vector<Eigen::VectorXd>& GoalRegionSolver::goal_states() const { return impl_->goals; }

RrtResult GoalRegionSolver::result() const {
  RrtResult r;
  r.status = impl_->status;
  r.path = impl_->path;
  r.checks = impl_->checks();
  r.iterations = impl_->iterations;
  r.tree_size = static_cast<int>(impl_->trees[0].size() + impl_->trees[1].size());
  r.goal = impl_->stats;
  return r;
}

RrtResult PlanGoalRegion(const GoalRegionProblem& problem, const GoalRegionOptions& options,
                         const ValidityFn& valid, std::uint64_t seed, bool bidirectional) {
  GoalRegionSolver solver(problem, options, valid, seed, bidirectional);
  while (!solver.done()) solver.Step(std::numeric_limits<std::int64_t>::max());
  return solver.result();
}

}  // namespace planning
