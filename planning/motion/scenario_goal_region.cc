#include "planning/motion/scenario_goal_region.h"

#include <memory>
#include <stdexcept>
#include <utility>

#include "planning/features/position_feature.h"
#include "planning/motion/internal/rrt_tree.h"
#include "planning/motion/planner.h"
#include "planning/motion/success.h"
#include "planning/robot/ik.h"

namespace planning {
namespace {

// The IK problem of the sampler: one target per end condition with a point (position task: its
// final target; box task: the box centre).
IkProblem ProjectionProblem(const Scenario& s, const ScenarioState& w) {
  IkProblem ik;
  const SuccessCriteria& c = s.success;
  if (c.position_task >= 0) {
    const Task& task = w.problem.tasks.at(static_cast<size_t>(c.position_task));
    const auto* position = dynamic_cast<const PositionFeature*>(task.feature.get());
    if (position != nullptr) {
      IkTarget t;
      t.link = position->link();
      t.offset = position->offset();
      t.position = task.target.col(w.problem.num_steps).head<3>();
      ik.targets.push_back(t);
    }
  }
  if (c.box_task >= 0) {
    const FeatureSpec& f = w.tasks.at(static_cast<size_t>(c.box_task)).feature;
    IkTarget t;
    t.link = FindLink(s.robot, f.link.name);
    t.offset = f.offset;
    t.position = f.center;
    ik.targets.push_back(t);
  }
  return ik;
}

// The sampler's state: one IK workspace and its buffers, made once per region.
struct Sampler {
  Sampler(const Scenario& s, const ScenarioState& w)
      : scenario(s), state(w), problem(ProjectionProblem(s, w)), data(s.robot) {
    const RrtProblem box = ScenarioRrtProblem(s);
    lower = box.lower;
    upper = box.upper;
    options.starts = 1;
    options.max_iterations = s.rrt_goal.ik_iterations;
    options.position_tolerance = kIkToleranceFraction * s.success.position_tolerance;
    problem.seed.resize(lower.size());
  }

  bool Draw(std::mt19937* rng, Eigen::VectorXd* q) {
    for (int k = 0; k < scenario.rrt_goal.ik_starts; ++k) {
      internal::SampleUniform(lower, upper, rng, &problem.seed);
      if (problem.targets.empty()) {
        *q = problem.seed;
      } else {
        *q = SolveIk(scenario.robot, problem, options, &data).q;
      }
      if (CheckEndState(scenario, state, *q, false).ok()) return true;
    }
    return false;
  }

  const Scenario& scenario;
  const ScenarioState& state;
  IkProblem problem;
  IkOptions options;
  IkData data;
  Eigen::VectorXd lower, upper;
};

}  // namespace

GoalRegion ScenarioGoalRegion(const Scenario& s, const ScenarioState& w, const ValidityFn& valid,
                              const CollisionData& coll, GoalSamplerCost* cost) {
  const SuccessCriteria& c = s.success;
  if (c.position_task < 0 && c.box_task < 0 && c.writhe_total_below < 0.0 &&
      c.winding_final_below <= 0.0) {
    throw std::invalid_argument(
        "goal-region planners: the scenario's success criterion has no end condition to sample");
  }
  auto sampler = std::make_shared<Sampler>(s, w);
  GoalRegion region;
  region.contains = [&s, &w](const Eigen::VectorXd& q) {
    return CheckEndState(s, w, q, false).ok();
  };
  region.sample = [sampler, cost](std::mt19937* rng, Eigen::VectorXd* q) {
    const double t0 = CpuSeconds();
    const bool in = sampler->Draw(rng, q);
    cost->cpu_time_s += CpuSeconds() - t0;
    return in;
  };
  region.valid = [&valid, &coll, cost](const Eigen::VectorXd& q) {
    const double t0 = CpuSeconds();
    const QueryCounts before = Counts(coll);
    const bool ok = valid(q);
    cost->counts += Counts(coll) - before;
    cost->cpu_time_s += CpuSeconds() - t0;
    return ok;
  };
  return region;
}

}  // namespace planning
