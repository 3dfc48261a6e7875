#include "planning/motion/rrt.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/random.h"

namespace planning {
namespace {

enum class EdgeResult { kValid, kInvalid, kBudget };

// Counts validity calls and enforces the budget.
struct Checker {
  const ValidityFn& valid;
  std::int64_t max_checks;
  std::int64_t count = 0;

  bool exhausted() const { return count >= max_checks; }
  bool operator()(const Eigen::VectorXd& q) {
    ++count;
    return valid(q);
  }
};

void CheckProblem(const RrtProblem& p) {
  const Eigen::Index n = p.start.size();
  if (n == 0 || p.goal.size() != n || p.lower.size() != n || p.upper.size() != n) {
    throw std::invalid_argument(
        "RRT: start, goal, lower, upper must have the same non-zero size (" +
        std::to_string(p.start.size()) + ", " + std::to_string(p.goal.size()) + ", " +
        std::to_string(p.lower.size()) + ", " + std::to_string(p.upper.size()) + ")");
  }
  if (!p.start.allFinite() || !p.goal.allFinite() || !p.lower.allFinite() || !p.upper.allFinite()) {
    throw std::invalid_argument("RRT: non-finite start, goal or bounds");
  }
  if ((p.upper - p.lower).minCoeff() < 0.0) {
    throw std::invalid_argument("RRT: a lower bound exceeds its upper bound");
  }
}

double Diagonal(const RrtProblem& p) { return (p.upper - p.lower).norm(); }

// Edge from -> to: end state first, then the interior states in order.
EdgeResult CheckEdge(const Eigen::VectorXd& from, const Eigen::VectorXd& to, double resolution,
                     Checker* check, Eigen::VectorXd* tmp) {
  if (check->exhausted()) return EdgeResult::kBudget;
  if (!(*check)(to)) return EdgeResult::kInvalid;
  const std::int64_t steps = EdgeSteps((to - from).norm(), resolution);
  for (std::int64_t i = 1; i < steps; ++i) {
    if (check->exhausted()) return EdgeResult::kBudget;
    const double s = static_cast<double>(i) / static_cast<double>(steps);
    tmp->noalias() = (1.0 - s) * from + s * to;
    if (!(*check)(*tmp)) return EdgeResult::kInvalid;
  }
  return EdgeResult::kValid;
}

int Nearest(const std::vector<RrtNode>& tree, const Eigen::VectorXd& q) {
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(tree.size()); ++i) {
    const double d = (tree[i].q - q).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

void SampleUniform(const RrtProblem& p, std::mt19937* rng, Eigen::VectorXd* q) {
  for (Eigen::Index i = 0; i < q->size(); ++i) {
    (*q)[i] = p.lower[i] + base::UniformUnit(rng) * (p.upper[i] - p.lower[i]);
  }
}

// q_new = q_near moved toward q_target by at most `range`.
void Steer(const Eigen::VectorXd& q_near, const Eigen::VectorXd& q_target, double range,
           Eigen::VectorXd* q_new) {
  const double d = (q_target - q_near).norm();
  if (d <= range) {
    *q_new = q_target;
  } else {
    q_new->noalias() = q_near + (range / d) * (q_target - q_near);
  }
}

// Root-to-node configurations of `tree` ending at `index` (root first).
void AppendBranch(const std::vector<RrtNode>& tree, int index, bool reverse,
                  std::vector<int>* out) {
  std::vector<int> branch;
  for (int i = index; i >= 0; i = tree[i].parent) branch.push_back(i);
  if (!reverse) {
    out->insert(out->end(), branch.rbegin(), branch.rend());
  } else {
    out->insert(out->end(), branch.begin(), branch.end());
  }
}

Trajectory ToTrajectory(const std::vector<const RrtNode*>& nodes, int n) {
  Trajectory path;
  path.q.resize(n, static_cast<Eigen::Index>(nodes.size()));
  for (size_t i = 0; i < nodes.size(); ++i) path.q.col(static_cast<Eigen::Index>(i)) = nodes[i]->q;
  return path;
}

// What both planners set up first: argument checks, the default range (20 % of the joint box's
// diagonal) and edge resolution (1 %), the counting checker, the per-iteration buffers (size n),
// and the start and goal validity checks. Returns false (result filled with kInvalidInput) when
// start or goal is invalid.
struct Setup {
  Checker check;
  int n = 0;
  double range = 0.0, resolution = 0.0;
  Eigen::VectorXd q_rand{}, q_new{}, tmp{};  // sample, extension, edge interpolation
};

bool Prepare(const RrtProblem& problem, const RrtOptions& options, Setup* s, RrtResult* result) {
  CheckProblem(problem);
  const double diag = Diagonal(problem);
  s->n = static_cast<int>(problem.start.size());
  s->range = options.range > 0 ? options.range : 0.2 * diag;
  // A zero-volume box (diag = 0) has only zero-length edges: any resolution checks them.
  s->resolution = options.resolution > 0 ? options.resolution : (diag > 0 ? 0.01 * diag : 1.0);
  if (!std::isfinite(s->range) || !std::isfinite(s->resolution)) {
    throw std::invalid_argument("RRT: range and resolution must be finite");
  }
  EdgeSteps(s->range, s->resolution);  // the longest edge must be checkable (throws)
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
EdgeResult Extend(const std::vector<RrtNode>& tree, Setup* s, int* near) {
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
  Setup setup;
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
    SampleUniform(problem, &rng, &setup.q_rand);
  }
  int near = 0;
  const EdgeResult edge = Extend(tree, &setup, &near);
  if (edge == EdgeResult::kBudget) return Finish(SolveStatus::kBudgetExhausted);
  if (edge == EdgeResult::kInvalid) return;
  tree.push_back({setup.q_new, near});
  if ((setup.q_new - problem.goal).norm() <= 1e-12) {
    std::vector<int> idx;
    AppendBranch(tree, static_cast<int>(tree.size()) - 1, false, &idx);
    std::vector<const RrtNode*> nodes;
    for (int i : idx) nodes.push_back(&tree[i]);
    path = ToTrajectory(nodes, setup.n);
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
    SampleUniform(problem, &rng, &setup.q_rand);
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
        std::vector<int> from_start, from_goal;
        AppendBranch(trees[0], start_end, false, &from_start);
        AppendBranch(trees[1], goal_end, true, &from_goal);
        std::vector<const RrtNode*> nodes;
        for (int i : from_start) nodes.push_back(&trees[0][i]);
        for (int i : from_goal) nodes.push_back(&trees[1][i]);
        path = ToTrajectory(nodes, setup.n);
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

RrtResult RunToEnd(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                   std::mt19937* rng, bool bidirectional) {
  RrtSolver solver(problem, options, valid, *rng, bidirectional);
  while (!solver.done()) solver.Step(std::numeric_limits<std::int64_t>::max());
  *rng = solver.rng();
  return solver.result();
}

}  // namespace

RrtResult PlanRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                  std::mt19937* rng) {
  return RunToEnd(problem, options, valid, rng, false);
}

RrtResult PlanBiRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                    std::mt19937* rng) {
  return RunToEnd(problem, options, valid, rng, true);
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
