// The only translation unit that includes OMPL (and, through it, Boost): see
// planning/motion/internal/ompl_planners.h.
#include "planning/motion/internal/ompl_planners.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace planning::internal {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

void CheckOmplProblem(const RrtProblem& p) {
  const Eigen::Index n = p.start.size();
  if (n == 0 || p.goal.size() != n || p.lower.size() != n || p.upper.size() != n) {
    throw std::invalid_argument("OMPL: start, goal, lower, upper must have the same non-zero size");
  }
  if (!p.start.allFinite() || !p.goal.allFinite() || !p.lower.allFinite() || !p.upper.allFinite()) {
    throw std::invalid_argument("OMPL: non-finite start, goal or bounds");
  }
  if ((p.upper - p.lower).minCoeff() < 0.0) {
    throw std::invalid_argument("OMPL: a lower bound exceeds its upper bound");
  }
}

}  // namespace

RrtResult PlanOmpl(OmplPlanner planner, const RrtProblem& problem, const RrtOptions& options,
                   const ValidityFn& valid, unsigned seed, const std::function<bool()>& stop) {
  CheckOmplProblem(problem);
  const unsigned n = static_cast<unsigned>(problem.start.size());
  const double diag = (problem.upper - problem.lower).norm();
  const double range = options.range > 0 ? options.range : 0.2 * diag;
  const double resolution = options.resolution > 0 ? options.resolution : 0.01 * diag;

  // Global OMPL state: quiet, and the seed generator reset before any RNG of this run exists.
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed) + 1u);

  auto space = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (unsigned i = 0; i < n; ++i) {
    bounds.low[i] = problem.lower[i];
    bounds.high[i] = problem.upper[i];
  }
  space->setBounds(bounds);

  auto si = std::make_shared<ob::SpaceInformation>(space);
  std::int64_t checks = 0;
  std::int64_t evaluations = 0;
  Eigen::VectorXd q(n);  // reused by every check: no allocation per state
  si->setStateValidityChecker([&](const ob::State* state) {
    if (checks >= options.max_checks) return false;  // budget spent: not a query any more
    ++checks;
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (unsigned i = 0; i < n; ++i) q[i] = v[i];
    return valid(q);
  });
  // The discrete motion validator checks ⌈d / (fraction · extent)⌉ − 1 interior states after the
  // end state; the extent of a box is its diagonal.
  si->setStateValidityCheckingResolution(resolution / space->getMaximumExtent());
  si->setup();

  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
  for (unsigned i = 0; i < n; ++i) {
    start[i] = problem.start[i];
    goal[i] = problem.goal[i];
  }
  pdef->setStartAndGoalStates(start, goal, 1e-9);

  ob::PlannerPtr p;
  if (planner == OmplPlanner::kRrt) {
    auto rrt = std::make_shared<og::RRT>(si);
    rrt->setGoalBias(options.goal_bias);
    rrt->setRange(range);
    p = rrt;
  } else {
    auto connect = std::make_shared<og::RRTConnect>(si);
    connect->setRange(range);
    p = connect;
  }
  p->setProblemDefinition(pdef);
  p->setup();

  const ob::PlannerTerminationCondition ptc([&] {
    ++evaluations;
    return checks >= options.max_checks || evaluations > options.max_iterations || (stop && stop());
  });
  const ob::PlannerStatus status = p->solve(ptc);

  RrtResult result;
  result.checks = checks;
  result.iterations = evaluations;
  if (status == ob::PlannerStatus::EXACT_SOLUTION && pdef->hasExactSolution()) {
    const auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
    const auto count = static_cast<Eigen::Index>(path->getStateCount());
    result.path.q.resize(n, count);
    for (Eigen::Index t = 0; t < count; ++t) {
      const double* v = path->getState(static_cast<unsigned>(t))
                            ->as<ob::RealVectorStateSpace::StateType>()
                            ->values;
      for (unsigned i = 0; i < n; ++i) result.path.q(i, t) = v[i];
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

}  // namespace planning::internal
