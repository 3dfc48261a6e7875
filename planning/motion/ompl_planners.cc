// The only translation unit that includes OMPL (and, through it, Boost): see
// planning/motion/internal/ompl_planners.h.
#include "planning/motion/internal/ompl_planners.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/str_cat.h"

namespace planning::internal {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

void CheckOmplProblem(const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                      const Eigen::VectorXd& upper) {
  const Eigen::Index n = start.size();
  if (n == 0 || lower.size() != n || upper.size() != n) {
    throw std::invalid_argument("OMPL: start, goal, lower, upper must have the same non-zero size");
  }
  if (!start.allFinite() || !lower.allFinite() || !upper.allFinite()) {
    throw std::invalid_argument("OMPL: non-finite start, goal or bounds");
  }
  if ((upper - lower).minCoeff() < 0.0) {
    throw std::invalid_argument("OMPL: a lower bound exceeds its upper bound");
  }
}

// One OMPL run: the space, the counted checker and the planner of the RRT peers, around a goal
// set by `set_goal` (a state or a region).
class OmplRun {
 public:
  OmplRun(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const RrtOptions& options,
          const ValidityFn& valid, unsigned seed)
      : n_(static_cast<unsigned>(lower.size())), options_(options), q_(lower.size()) {
    const double diag = (upper - lower).norm();
    range_ = options.range > 0 ? options.range : 0.2 * diag;
    const double resolution = options.resolution > 0 ? options.resolution : 0.01 * diag;
    // Global OMPL state: quiet, and the seed generator reset before any RNG of this run exists.
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed) + 1u);
    space_ = std::make_shared<ob::RealVectorStateSpace>(n_);
    ob::RealVectorBounds bounds(n_);
    for (unsigned i = 0; i < n_; ++i) {
      bounds.low[i] = lower[i];
      bounds.high[i] = upper[i];
    }
    space_->setBounds(bounds);
    si_ = std::make_shared<ob::SpaceInformation>(space_);
    si_->setStateValidityChecker([this, valid](const ob::State* state) {
      // The check of a goal sample (MarkGoalCheck) goes through the region's checker, which
      // answers the same and books its cost to the goal sampler.
      const bool goal_check = goal_check_pending_ && goal_valid_;
      goal_check_pending_ = false;
      if (checks_ >= options_.max_checks) return false;  // budget spent: not a query any more
      ++checks_;
      Read(state, &q_);  // q_ is reused by every check: no allocation per state
      return goal_check ? goal_valid_(q_) : valid(q_);
    });
    // The discrete motion validator checks ⌈d / (fraction · extent)⌉ − 1 interior states after
    // the end state; the extent of a box is its diagonal.
    si_->setStateValidityCheckingResolution(resolution / space_->getMaximumExtent());
    si_->setup();
    pdef_ = std::make_shared<ob::ProblemDefinition>(si_);
  }

  const ob::SpaceInformationPtr& si() const { return si_; }
  // The checker for goal samples, and the mark that the next check is one (RRTConnect's
  // PlannerInputStates::nextGoal checks a sample right after sampleGoal writes it).
  void SetGoalValidity(ValidityFn goal_valid) { goal_valid_ = std::move(goal_valid); }
  void MarkGoalCheck() { goal_check_pending_ = true; }
  // One goal candidate drawn; the run ends (budget) after options.max_checks draws.
  void CountGoalDraw() { ++goal_draws_; }
  std::int64_t goal_draws() const { return goal_draws_; }
  const ob::ProblemDefinitionPtr& pdef() const { return pdef_; }
  void Read(const ob::State* state, Eigen::VectorXd* q) const {
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (unsigned i = 0; i < n_; ++i) (*q)[i] = v[i];
  }
  static void Write(const Eigen::VectorXd& q, ob::State* state) {
    double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (Eigen::Index i = 0; i < q.size(); ++i) v[i] = q[i];
  }
  void SetStart(const Eigen::VectorXd& q) {
    ob::ScopedState<ob::RealVectorStateSpace> start(space_);
    for (unsigned i = 0; i < n_; ++i) start[i] = q[i];
    pdef_->addStartState(start);
  }

  // Runs `planner` (RRT with the options' goal bias, or RRTConnect) to a solution, the budget,
  // max_iterations or `stop`.
  RrtResult Solve(OmplPlanner planner, const std::function<bool()>& stop) {
    ob::PlannerPtr p;
    if (planner == OmplPlanner::kRrt) {
      auto rrt = std::make_shared<og::RRT>(si_);
      rrt->setGoalBias(options_.goal_bias);
      rrt->setRange(range_);
      p = rrt;
    } else {
      auto connect = std::make_shared<og::RRTConnect>(si_);
      connect->setRange(range_);
      p = connect;
    }
    p->setProblemDefinition(pdef_);
    p->setup();
    std::int64_t evaluations = 0;
    const ob::PlannerTerminationCondition ptc([&] {
      ++evaluations;
      // The draw cap: OMPL's nextGoal keeps sampling while no goal tree exists, and a candidate
      // outside G costs no check, so without it a region the sampler cannot hit never ends.
      return checks_ >= options_.max_checks || goal_draws_ >= options_.max_checks ||
             evaluations > options_.max_iterations || (stop && stop());
    });
    const ob::PlannerStatus status = p->solve(ptc);
    RrtResult result;
    result.checks = checks_;
    result.iterations = evaluations;
    if (status == ob::PlannerStatus::EXACT_SOLUTION && pdef_->hasExactSolution()) {
      const auto* path = pdef_->getSolutionPath()->as<og::PathGeometric>();
      const auto count = static_cast<Eigen::Index>(path->getStateCount());
      result.path.q.resize(n_, count);
      Eigen::VectorXd q(n_);
      for (Eigen::Index t = 0; t < count; ++t) {
        Read(path->getState(static_cast<unsigned>(t)), &q);
        result.path.q.col(t) = q;
      }
      result.status = SolveStatus::kConverged;
    } else if (status == ob::PlannerStatus::INVALID_START ||
               status == ob::PlannerStatus::INVALID_GOAL) {
      result.status = SolveStatus::kInvalidInput;
    } else {
      result.status = SolveStatus::kBudgetExhausted;
    }
    return result;
  }

 private:
  const unsigned n_;
  const RrtOptions options_;
  double range_ = 0.0;
  std::int64_t checks_ = 0;
  std::int64_t goal_draws_ = 0;
  Eigen::VectorXd q_;
  ValidityFn goal_valid_;
  bool goal_check_pending_ = false;
  std::shared_ptr<ob::RealVectorStateSpace> space_;
  ob::SpaceInformationPtr si_;
  ob::ProblemDefinitionPtr pdef_;
};

// The goal region as OMPL sees it (see PlanOmplRegion in the header).
class RegionGoal : public ob::GoalSampleableRegion {
 public:
  RegionGoal(OmplRun& run, const GoalRegionProblem& problem, size_t max_goal_states, unsigned seed,
             bool out_of_box_on_failure)
      : ob::GoalSampleableRegion(run.si()),
        run_(run),
        problem_(problem),
        max_goal_states_(max_goal_states),
        rng_(seed),
        out_of_box_(out_of_box_on_failure),
        q_(problem.start.size()) {
    setThreshold(0.5);  // distanceGoal is 0 inside G, 1 outside
  }

  double distanceGoal(const ob::State* state) const override {
    run_.Read(state, &q_);
    return problem_.goal.contains(q_) ? 0.0 : 1.0;
  }

  void sampleGoal(ob::State* state) const override {
    if (!out_of_box_) {
      // RRT: goal states found lazily and kept, handed out in turn (OMPL's GoalLazySamples, whose
      // GoalStates::sampleGoal cycles through the states found so far), one draw per call while
      // fewer than max_goal_states_ are kept; a candidate in G is kept if the counted checker
      // accepts it. With none kept yet, a uniform state of the box.
      if (pool_.size() < max_goal_states_) {
        run_.CountGoalDraw();
        if (problem_.goal.sample(&rng_, &q_)) {
          ++stats_.in_region;
          OmplRun::Write(q_, state);
          run_.MarkGoalCheck();
          if (run_.si()->isValid(state)) {
            ++stats_.samples;
            pool_.push_back(q_);
          }
        }
      }
      if (!pool_.empty()) {
        OmplRun::Write(pool_[next_++ % pool_.size()], state);
        return;
      }
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (Eigen::Index i = 0; i < q_.size(); ++i) {
        q_[i] = problem_.lower[i] + u(rng_) * (problem_.upper[i] - problem_.lower[i]);
      }
      OmplRun::Write(q_, state);
      return;
    }
    // RRTConnect: fresh candidates; nextGoal checks the one written (counted) and roots a goal
    // tree at it when valid.
    for (int k = 0; k < kOmplGoalDraws; ++k) {
      run_.CountGoalDraw();
      if (problem_.goal.sample(&rng_, &q_)) {
        ++stats_.in_region;
        ++stats_.samples;
        OmplRun::Write(q_, state);
        run_.MarkGoalCheck();  // nextGoal checks it next
        return;
      }
    }
    OmplRun::Write(problem_.lower.array() - 1.0, state);  // nextGoal skips it: out of bounds
  }

  unsigned int maxSampleCount() const override { return std::numeric_limits<unsigned>::max(); }
  // draws: counted by the run (its budget), not here.
  const GoalSamplerStats& stats() const { return stats_; }

 private:
  OmplRun& run_;
  const GoalRegionProblem& problem_;
  const size_t max_goal_states_;  // RRT's pool
  mutable std::mt19937 rng_;
  const bool out_of_box_;
  mutable Eigen::VectorXd q_;
  mutable GoalSamplerStats stats_;
  mutable std::vector<Eigen::VectorXd> pool_;  // RRT's goal states
  mutable size_t next_ = 0;
};

}  // namespace

RrtResult PlanOmpl(OmplPlanner planner, const RrtProblem& problem, const RrtOptions& options,
                   const ValidityFn& valid, unsigned seed, const std::function<bool()>& stop) {
  CheckOmplProblem(problem.start, problem.lower, problem.upper);
  if (problem.goal.size() != problem.start.size()) {
    throw std::invalid_argument("OMPL: start, goal, lower, upper must have the same non-zero size");
  }
  if (!problem.goal.allFinite())
    throw std::invalid_argument("OMPL: non-finite start, goal or bounds");
  OmplRun run(problem.lower, problem.upper, options, valid, seed);
  run.SetStart(problem.start);
  ob::ScopedState<ob::RealVectorStateSpace> goal(run.si()->getStateSpace());
  for (Eigen::Index i = 0; i < problem.goal.size(); ++i)
    goal[static_cast<unsigned>(i)] = problem.goal[i];
  run.pdef()->setGoalState(goal, 1e-9);
  return run.Solve(planner, stop);
}

RrtResult PlanOmplRegion(OmplPlanner planner, const GoalRegionProblem& problem,
                         const GoalRegionOptions& options, const ValidityFn& valid, unsigned seed,
                         const std::function<bool()>& stop) {
  CheckOmplProblem(problem.start, problem.lower, problem.upper);
  if (!problem.goal.contains || !problem.goal.sample) {
    throw std::invalid_argument("OMPL: the goal region needs contains and sample");
  }
  if (options.max_goal_states < 1) {
    throw std::invalid_argument(base::StrCat("OMPL: max_goal_states must be >= 1, got ",
                                             std::to_string(options.max_goal_states)));
  }
  OmplRun run(problem.lower, problem.upper, options.rrt, valid, seed);
  run.SetStart(problem.start);
  run.SetGoalValidity(problem.goal.valid);
  auto goal =
      std::make_shared<RegionGoal>(run, problem, static_cast<size_t>(options.max_goal_states), seed,
                                   planner == OmplPlanner::kRrtConnect);
  run.pdef()->setGoal(goal);
  RrtResult r = run.Solve(planner, stop);
  r.goal = goal->stats();
  r.goal.draws = run.goal_draws();
  return r;
}

}  // namespace planning::internal
