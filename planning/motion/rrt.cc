#include "planning/motion/rrt.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/random.h"
#include "planning/motion/internal/rrt_tree.h"

namespace planning {
namespace internal {

// What both planners set up first (Prepare, below): the counting checker, the default range (20 %
// of the joint box's diagonal) and edge resolution (1 %), the per-iteration buffers (size n).
struct RrtSetup {
  Checker check;
  int n = 0;
  double range = 0.0, resolution = 0.0;
  Eigen::VectorXd q_rand{}, q_new{}, tmp{};  // sample, extension, edge interpolation
};

}  // namespace internal

namespace {

using internal::BranchPath;
using internal::CheckEdge;
using internal::Checker;
using internal::EdgeResult;
using internal::Nearest;
using internal::Steer;

void CheckProblem(const RrtProblem& p) {
  internal::CheckBox("RRT", p.lower, p.upper, p.start, &p.goal);
}

void SampleInLimits(const RrtProblem& p, std::mt19937* rng, Eigen::VectorXd* q) {
  internal::SampleUniform(p.lower, p.upper, rng, q);
}

// Argument checks, then fills *s and checks the start and goal. Returns false (result filled with
// kInvalidInput) when start or goal is invalid.
bool Prepare(const RrtProblem& problem, const RrtOptions& options, internal::RrtSetup* s,
             RrtResult* result) {
  CheckProblem(problem);
  s->n = static_cast<int>(problem.start.size());
  internal::RangeAndResolution(options, problem.lower, problem.upper, &s->range, &s->resolution);
  s->q_rand.resize(s->n);
  s->q_new.resize(s->n);
  s->tmp.resize(s->n);
  if (!s->check(problem.start) || !s->check(problem.goal)) {
    result->status = SolveStatus::kInvalidInput;
    result->checks = s->check.count;
    return false;
  }
  return true;
}

// One extension of `tree` towards s->q_rand: from its nearest node (*near) to s->q_new, at most
// s->range away, then the validity check of that edge.
EdgeResult Extend(const std::vector<RrtNode>& tree, internal::RrtSetup* s, int* near) {
  *near = Nearest(tree, s->q_rand);
  Steer(tree[*near].q, s->q_rand, s->range, &s->q_new);
  return CheckEdge(tree[*near].q, s->q_new, s->resolution, &s->check, &s->tmp);
}

}  // namespace

struct RrtSolver::Impl {
  Impl(const RrtProblem& p, const RrtOptions& o, ValidityFn v, std::mt19937 r, bool bi)
      : problem(p),
        options(o),
        valid(std::move(v)),
        rng(r),
        bidirectional(bi),
        setup{Checker{valid, o.max_checks}} {}

  // One sampling iteration (the loop bodies of PlanRrt / PlanBiRrt); sets done on a path or on
  // the budget.
  void IterateRrt();
  void IterateBiRrt();
  void Finish(SolveStatus s) {
    status = s;
    done = true;
  }

  const RrtProblem problem;
  const RrtOptions options;
  const ValidityFn valid;
  std::mt19937 rng;
  const bool bidirectional;
  internal::RrtSetup setup;
  std::vector<RrtNode> trees[2];
  int grow = 0;  // BiRRT: index of the tree that grows this iteration
  std::int64_t iterations = 0;
  SolveStatus status = SolveStatus::kBudgetExhausted;
  bool done = false;
  std::atomic<bool> stop{false};
  Trajectory path;
};

void RrtSolver::Impl::IterateRrt() {
  std::vector<RrtNode>& tree = trees[0];
  ++iterations;
  const bool to_goal = base::UniformUnit(&rng) < options.goal_bias;
  if (to_goal) {
    setup.q_rand = problem.goal;
  } else {
    SampleInLimits(problem, &rng, &setup.q_rand);
  }
  int near = 0;
  const EdgeResult edge = Extend(tree, &setup, &near);
  if (edge == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
  if (edge == EdgeResult::kInvalid) return;
  tree.push_back({setup.q_new, near});
  if ((setup.q_new - problem.goal).norm() <= 1e-12) {
    path = BranchPath(tree, static_cast<int>(tree.size()) - 1, nullptr, -1);
    Finish(SolveStatus::kConverged);
  }
}

void RrtSolver::Impl::IterateBiRrt() {
  ++iterations;
  std::vector<RrtNode>& a = trees[grow];
  std::vector<RrtNode>& b = trees[1 - grow];
  // Target: a random node of the other tree (goal_bias) or a uniform sample.
  if (base::UniformUnit(&rng) < options.goal_bias) {
    setup.q_rand = b[base::UniformIndex(&rng, static_cast<std::uint32_t>(b.size()))].q;
  } else {
    SampleInLimits(problem, &rng, &setup.q_rand);
  }
  int near = 0;
  const EdgeResult edge = Extend(a, &setup, &near);
  if (edge == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
  if (edge == EdgeResult::kValid) {
    a.push_back({setup.q_new, near});
    const int added = static_cast<int>(a.size()) - 1;
    // Try to join the trees through the other tree's nearest node.
    const int other = Nearest(b, setup.q_new);
    if ((b[other].q - setup.q_new).norm() <= setup.range) {
      const EdgeResult join =
          CheckEdge(setup.q_new, b[other].q, setup.resolution, &setup.check, &setup.tmp);
      if (join == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
      if (join == EdgeResult::kValid) {
        // Path: start tree root .. joint, then goal tree joint .. root.
        const int start_end = grow == 0 ? added : other;
        const int goal_end = grow == 0 ? other : added;
        path = BranchPath(trees[0], start_end, &trees[1], goal_end);
        return Finish(SolveStatus::kConverged);
      }
    }
  }
  grow = 1 - grow;
}

RrtSolver::RrtSolver(const RrtProblem& problem, const RrtOptions& options, ValidityFn valid,
                     std::mt19937 rng, bool bidirectional)
    : impl_(std::make_unique<Impl>(problem, options, std::move(valid), rng, bidirectional)) {
  RrtResult unused;
  if (!Prepare(problem, options, &impl_->setup, &unused)) {
    impl_->Finish(SolveStatus::kInvalidInput);
    return;
  }
  impl_->trees[0].push_back({problem.start, -1});
  if (bidirectional) impl_->trees[1].push_back({problem.goal, -1});
}

RrtSolver::RrtSolver(const RrtProblem& problem, const RrtOptions& options, ValidityFn valid,
                     std::uint64_t seed, bool bidirectional)
    : RrtSolver(problem, options, std::move(valid), std::mt19937(seed), bidirectional) {}

RrtSolver::~RrtSolver() = default;

std::int64_t RrtSolver::Step(std::int64_t k) {
  Impl& m = *impl_;
  std::int64_t done_now = 0;
  for (; done_now < k && !m.done; ++done_now) {
    if (m.stop.load(std::memory_order_relaxed)) {
      m.Finish(SolveStatus::kBudgetExhausted);
      break;
    }
    if (m.setup.check.exhausted() || m.iterations >= m.options.max_iterations) {
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

void RrtSolver::RequestStop() { impl_->stop.store(true); }
bool RrtSolver::stop_requested() const { return impl_->stop.load(); }
bool RrtSolver::done() const { return impl_->done || impl_->stop.load(); }
SolveStatus RrtSolver::status() const { return impl_->status; }
std::int64_t RrtSolver::checks() const { return impl_->setup.check.count; }
std::int64_t RrtSolver::iterations() const { return impl_->iterations; }
int RrtSolver::num_trees() const { return impl_->bidirectional ? 2 : 1; }
const std::mt19937& RrtSolver::rng() const { return impl_->rng; }

const std::vector<RrtNode>& RrtSolver::tree(int i) const {
  if (i < 0 || i >= num_trees()) {
    throw std::invalid_argument("RrtSolver::tree: index " + std::to_string(i) + " of " +
                                std::to_string(num_trees()) + " trees");
  }
  return impl_->trees[i];
}

RrtResult RrtSolver::result() const {
  RrtResult r;
  r.status = impl_->status;
  r.path = impl_->path;
  r.checks = impl_->setup.check.count;
  r.iterations = impl_->iterations;
  r.tree_size = static_cast<int>(impl_->trees[0].size() + impl_->trees[1].size());
  return r;
}

namespace {

RrtResult RunRrtToEnd(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                      std::mt19937* rng, bool bidirectional) {
  RrtSolver solver(problem, options, valid, *rng, bidirectional);
  while (!solver.done()) solver.Step(std::numeric_limits<std::int64_t>::max());
  *rng = solver.rng();
  return solver.result();
}

}  // namespace

RrtResult PlanRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                  std::mt19937* rng) {
  return RunRrtToEnd(problem, options, valid, rng, false);
}

RrtResult PlanBiRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                    std::mt19937* rng) {
  return RunRrtToEnd(problem, options, valid, rng, true);
}

bool PathIsValid(const Trajectory& path, double resolution, const ValidityFn& valid,
                 std::int64_t* checks) {
  if (!(resolution > 0.0)) throw std::invalid_argument("PathIsValid: resolution must be > 0");
  std::int64_t states = 1;  // the number of checks is bounded before any is made
  for (int t = 0; t + 1 < path.num_points(); ++t) {
    states += EdgeSteps((path.q.col(t + 1) - path.q.col(t)).norm(), resolution);
    if (states > kMaxEdgeSteps) {
      throw std::invalid_argument("PathIsValid: resolution " + std::to_string(resolution) +
                                  " would need more than " + std::to_string(kMaxEdgeSteps) +
                                  " validity checks");
    }
  }
  Checker check{valid, std::numeric_limits<std::int64_t>::max()};
  bool ok = path.num_points() == 0 || check(path.q.col(0));
  Eigen::VectorXd tmp(path.num_dofs());
  for (int t = 0; ok && t + 1 < path.num_points(); ++t) {
    ok =
        CheckEdge(path.q.col(t), path.q.col(t + 1), resolution, &check, &tmp) == EdgeResult::kValid;
  }
  if (checks != nullptr) *checks += check.count;
  return ok;
}

}  // namespace planning
