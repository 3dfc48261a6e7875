#include "planning/motion/planner.h"

#include <cassert>
#include <chrono>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>

#include "base/enum_names.h"
#include "planning/collision/collision.h"
#include "planning/motion/internal/ompl_planners.h"
#include "planning/motion/internal/start_coil.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario_goal_region.h"
#include "planning/robot/kinematics.h"
#include "topology/winding.h"

namespace planning {

inline constexpr base::EnumName<Planner> kPlannerNames[] = {
    {Planner::kAico, "aico"},
    {Planner::kRrt, "rrt"},
    {Planner::kBiRrt, "birrt"},
    {Planner::kOmplRrt, "ompl-rrt"},
    {Planner::kOmplRrtConnect, "ompl-rrtconnect"},
    {Planner::kAicoGoal, "aico-goal"},
    {Planner::kRrtRegion, "rrt-region"},
    {Planner::kBiRrtRegion, "birrt-region"},
    {Planner::kOmplRrtRegion, "ompl-rrt-region"},
    {Planner::kOmplRrtConnectRegion, "ompl-rrtconnect-region"},
};
constexpr std::span<const base::EnumName<Planner>> EnumNames(Planner) { return kPlannerNames; }

namespace {

// RRT iterations between two polls (about 20 validity checks each at most).
constexpr std::int64_t kRrtPollIterations = 16;

bool NeedsOmpl(Planner p) {
  return p == Planner::kOmplRrt || p == Planner::kOmplRrtConnect || p == Planner::kOmplRrtRegion ||
         p == Planner::kOmplRrtConnectRegion;
}

}  // namespace

bool IsAico(Planner planner) { return planner == Planner::kAico || planner == Planner::kAicoGoal; }

void DisableTasks(const std::vector<std::string>& names, MotionProblem* problem) {
  for (const std::string& name : names) {
    bool found = false;
    for (Task& task : problem->tasks) {
      if (task.name != name) continue;
      task.precision.setZero();
      task.max_jump = 0.0;
      found = true;
    }
    if (!found) {
      std::string known;
      for (const Task& task : problem->tasks)
        known.append(known.empty() ? "" : ", ").append(task.name);
      throw std::invalid_argument("no task '" + name + "' to switch off (tasks: " + known + ")");
    }
  }
}

std::vector<std::string> WritheTaskNames(const MotionProblem& problem) {
  std::vector<std::string> out;
  for (const Task& task : problem.tasks) {
    // "writhe" (the matrix) or "writhe_total" (its sum).
    if (task.feature && task.feature->name().rfind("writhe", 0) == 0) out.push_back(task.name);
  }
  return out;
}

ValidityFn ValidityChecker(const Scenario& s, CollisionData* coll, KinematicsData* kin) {
  const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
  return [&s, coll, kin, lo, hi](const Eigen::VectorXd& q) {
    for (Eigen::Index k = 0; k < q.size(); ++k) {
      if (q[k] < lo[k] || q[k] > hi[k]) return false;
    }
    ForwardKinematics(s.robot, q, kin);
    return !InCollision(s.robot, *kin, coll);
  };
}

RrtProblem ScenarioRrtProblem(const Scenario& s) {
  RrtProblem rp;
  rp.lower = LowerLimits(s.robot);
  rp.upper = UpperLimits(s.robot);
  for (Eigen::Index k = 0; k < rp.lower.size(); ++k) {  // continuous joints: one turn
    if (!std::isfinite(rp.lower[k])) rp.lower[k] = s.initial.problem.q0[k] - M_PI;
    if (!std::isfinite(rp.upper[k])) rp.upper[k] = s.initial.problem.q0[k] + M_PI;
  }
  rp.start = s.initial.problem.q0;
  rp.goal = s.goal_q;
  return rp;
}

std::vector<Planner> AvailablePlanners() {
  std::vector<Planner> out;
  for (const base::EnumName<Planner>& e : kPlannerNames) {
    if (!NeedsOmpl(e.value) || OmplAvailable()) out.push_back(e.value);
  }
  return out;
}

Planner ParsePlanner(const std::string& name) {
  const Planner p = base::ParseEnum<Planner>(name, "planner");
  if (NeedsOmpl(p) && !OmplAvailable()) {
    throw std::invalid_argument("planner '" + name +
                                "': topoplan was built without OMPL (apt-get install "
                                "libompl-dev, then re-run cmake)");
  }
  return p;
}

std::vector<Planner> DefaultPlanners() {
  std::vector<Planner> out;
  for (const Planner p : AvailablePlanners()) {
    if (p != Planner::kOmplRrtRegion && p != Planner::kOmplRrtConnectRegion) out.push_back(p);
  }
  return out;
}

bool OmplAvailable() {
#ifdef TOPOPLAN_HAVE_OMPL
  return true;
#else
  return false;
#endif
}

const char* PlannerName(Planner planner) { return base::ToName(planner); }

PlanResult RunPlanner(const Scenario& s, Planner planner, unsigned seed,
                      const AicoCallback& callback, const PollFn& poll) {
  PlanRequest request;
  request.planner = planner;
  request.seed = seed;
  request.callback = callback;
  request.poll = poll;
  return RunPlanner(s, request);
}

PlanResult RunPlanner(const Scenario& s, const PlanRequest& request) {
  const ScenarioState& w = request.state != nullptr ? *request.state : s.initial;
  const Planner planner = request.planner;
  const unsigned seed = request.seed;
  const PollFn& poll = request.poll;
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = CpuSeconds();
  const auto elapsed = [&t0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  if (IsAico(planner)) {
    std::vector<std::string> off = request.disabled_tasks;
    if (planner == Planner::kAicoGoal) {
      for (const std::string& name : WritheTaskNames(w.problem)) off.push_back(name);
    }
    PlanResult out = RunAicoAttempts(s, w, request.aico ? *request.aico : s.aico, request.callback,
                                     request.budget, off, request.aico_retry);
    out.report.time_s = elapsed();
    out.report.cpu_time_s = CpuSeconds() - cpu0;
    FinishReport(s, w, out.trajectory.num_points() > 0, /*judged=*/true, &out);
    EnforceBudget(request.budget, &out.report);
    out.report.planner = PlannerName(planner);
    return out;
  }
  CollisionData coll(s.robot, w.env, s.collision);
  KinematicsData kin(s.robot);
  const ValidityFn valid = ValidityChecker(s, &coll, &kin);
  const RrtProblem rp = ScenarioRrtProblem(s);
  RrtOptions options = s.rrt;
  if (request.budget.unit == Budget::Unit::kQueries) {
    options.max_checks = static_cast<std::int64_t>(request.budget.value);
  }
  // Time and pair-test budgets are polled (queries: max_checks above).
  const auto out_of_time = [&] {
    switch (request.budget.unit) {
      case Budget::Unit::kCpuTime:
        return CpuSeconds() - cpu0 >= request.budget.value;
      case Budget::Unit::kPairTests:
        return static_cast<double>(Counts(coll).pair_tests()) >= request.budget.value;
      case Budget::Unit::kQueries:
      case Budget::Unit::kNone:
        break;
    }
    return false;
  };
  RrtResult r;
  GoalSamplerCost sampler;
  // A polled budget is tested after every iteration (Step(1) repeated = one Step(max)).
  const bool polled = request.budget.unit == Budget::Unit::kCpuTime ||
                      request.budget.unit == Budget::Unit::kPairTests;
  // Runs a resumable tree solver (RrtSolver, GoalRegionSolver) in chunks of iterations, polling
  // between them (the same result as one call to the end).
  const auto step_to_end = [&](auto& solver) {
    while (!solver.done()) {
      solver.Step(polled ? 1 : kRrtPollIterations);
      if (poll) poll();
      if (!solver.done() && out_of_time()) solver.RequestStop();
    }
    return solver.result();
  };
  // The goal region of the scenario (scenario_goal_region.h), its sampler's cost into `sampler`.
  const auto region_problem = [&] {
    GoalRegionProblem gp;
    gp.lower = rp.lower;
    gp.upper = rp.upper;
    gp.start = rp.start;
    gp.goal = ScenarioGoalRegion(s, w, valid, coll, &sampler);
    return gp;
  };
  const GoalRegionOptions region_options{options, s.rrt_goal.max_goal_states};
  switch (planner) {
    case Planner::kRrt:
    case Planner::kBiRrt: {
      RrtSolver solver(rp, options, valid, std::mt19937(seed), planner == Planner::kBiRrt);
      r = step_to_end(solver);
      break;
    }
    case Planner::kRrtRegion:
    case Planner::kBiRrtRegion: {
      const GoalRegionProblem gp = region_problem();
      GoalRegionSolver solver(gp, region_options, valid, seed, planner == Planner::kBiRrtRegion);
      r = step_to_end(solver);
      break;
    }
    case Planner::kOmplRrtRegion:
    case Planner::kOmplRrtConnectRegion:
#ifdef TOPOPLAN_HAVE_OMPL
      r = internal::PlanOmplRegion(planner == Planner::kOmplRrtRegion
                                       ? internal::OmplPlanner::kRrt
                                       : internal::OmplPlanner::kRrtConnect,
                                   region_problem(), region_options, valid, seed, out_of_time);
      break;
#else
      throw std::invalid_argument(std::string("planner '") + PlannerName(planner) +
                                  "': topoplan was built without OMPL");
#endif
    case Planner::kOmplRrt:
    case Planner::kOmplRrtConnect:
#ifdef TOPOPLAN_HAVE_OMPL
      r = internal::PlanOmpl(planner == Planner::kOmplRrt ? internal::OmplPlanner::kRrt
                                                          : internal::OmplPlanner::kRrtConnect,
                             rp, options, valid, seed, out_of_time);
      break;
#else
      throw std::invalid_argument(std::string("planner '") + PlannerName(planner) +
                                  "': topoplan was built without OMPL");
#endif
    case Planner::kAico:
    case Planner::kAicoGoal:
      break;
  }
  const double time_s = elapsed();
  const double cpu_s = CpuSeconds() - cpu0;
  PlanResult out = SamplingPlanResult(s, w, planner, r, coll);
  out.report.time_s = time_s;
  out.report.cpu_time_s = cpu_s;
  out.report.goal_sampler_draws = r.goal.draws;
  out.report.goal_samples = r.goal.samples;
  out.report.goal_sampler_counts = sampler.counts;
  out.report.goal_sampler_cpu_time_s = sampler.cpu_time_s;
  EnforceBudget(request.budget, &out.report);
  return out;
}

PlanResult SamplingPlanResult(const Scenario& s, const ScenarioState& w, Planner planner,
                              const RrtResult& r, const CollisionData& coll) {
  PlanResult out;
  PlanReport& rep = out.report;
  rep.planner = PlannerName(planner);
  rep.status = r.status;
  rep.iterations = r.iterations;
  rep.collision_checks = coll.queries;
  rep.narrow_phase_calls = coll.narrow_phase_calls;
  rep.counts = Counts(coll);
  out.trajectory = r.path;
  const bool found = r.status == SolveStatus::kConverged;
  // RRT paths are checked edge by edge while planning; re-check at the scenario's resolution
  // (on a separate, uncounted collision state).
  if (found && out.trajectory.num_points() > 0) {
    CollisionData recheck(s.robot, w.env, s.collision);
    KinematicsData kin(s.robot);
    rep.path_collision_free =
        PathIsValid(out.trajectory, s.check_resolution, ValidityChecker(s, &recheck, &kin));
  }
  FinishReport(s, w, found, /*judged=*/false, &out);
  return out;
}

void FinishReport(const Scenario& s, const ScenarioState& w, bool found, bool judged,
                  PlanResult* out) {
  PlanReport& rep = out->report;
  // Report quantities (not counted).
  rep.start_writhe_total = ReportWritheTotal(s, w, w.problem.q0);
  if (!judged) rep.final_writhe_total = rep.start_writhe_total;
  rep.success = false;
  if (out->trajectory.num_points() > 0) {
    if (!judged) ApplyVerdict(JudgePlan(s, w, out->trajectory), &rep);
    rep.path_length = PathLength(out->trajectory);
    if (rep.planner != PlannerName(Planner::kAico)) rep.cost = rep.path_length;
    rep.success = found && rep.path_collision_free && rep.failure_reason == FailureReason::kNone;
  } else {
    // No path: the arm stays at its start. The end quantities are those of q0 (so a failed run
    // does not report the zeros of an unwrapped arm); the failure is named below from the status.
    Trajectory start;
    start.q = w.problem.q0;
    ApplyVerdict(JudgePlan(s, w, start), &rep);
    rep.failure_reason = FailureReason::kNone;
    rep.failure_step = -1;
  }
  NameFailure(&rep);
}

void ApplyVerdict(const PlanVerdict& v, PlanReport* rep) {
  rep->final_writhe_total = v.final_writhe_total;
  rep->min_clearance_m = v.min_clearance_m;
  rep->failure_reason = v.reason;
  rep->failure_step = v.step;
  rep->reach_error_m = v.reach_error_m;
  rep->max_winding_jump_turns = v.max_winding_jump_turns;
  rep->winding_jumps = v.winding_jumps;
  rep->final_winding_turns = v.final_winding_turns;
  rep->writhe_peak_row = v.writhe_peak_row;
  rep->writhe_peak_col = v.writhe_peak_col;
  rep->writhe_peak_value = v.writhe_peak_value;
  rep->failure_detail = v.detail;
  rep->loop_checked = v.loop_checked;
  rep->passed_through = v.passed_through;
  rep->through_segment = v.through_segment;
}

namespace {

// The test of an AICO trajectory as a finished plan: the counted validation at check_resolution
// (a plan is only usable once checked), then, if `judge_invalid` or the path is valid, JudgePlan.
struct AicoPathCheck {
  bool valid = false;
  bool judged = false;
  PlanVerdict verdict;
  long queries = 0, narrow_phase_calls = 0;
  QueryCounts counts;
  bool success() const { return valid && judged && verdict.reason == FailureReason::kNone; }
};

AicoPathCheck CheckAicoPath(const Scenario& s, const ScenarioState& w, const Trajectory& path,
                            bool invalid_input, bool judge_invalid) {
  AicoPathCheck c;
  CollisionData coll(s.robot, w.env, s.collision);
  KinematicsData kin(s.robot);
  c.valid =
      !invalid_input && PathIsValid(path, s.check_resolution, ValidityChecker(s, &coll, &kin));
  c.queries = coll.queries;
  c.narrow_phase_calls = coll.narrow_phase_calls;
  c.counts = Counts(coll);
  if (c.valid || judge_invalid) {
    c.verdict = JudgePlan(s, w, path);
    c.judged = true;
  }
  return c;
}

bool FoldAicoAttempt(const AicoResult& r, const AicoPathCheck& check, PlanResult* out) {
  assert(check.judged);
  PlanReport& rep = out->report;
  rep.status = r.status;
  rep.iterations += r.iterations;
  rep.cost = r.cost;
  rep.cost_history = r.cost_history;
  rep.collision_checks += r.collision_queries + check.queries;
  rep.narrow_phase_calls += r.narrow_phase_calls + check.narrow_phase_calls;
  rep.counts += r.counts + check.counts;
  out->trajectory = r.trajectory;
  rep.path_collision_free = check.valid;
  ApplyVerdict(check.verdict, &rep);
  rep.path_length = PathLength(out->trajectory);
  rep.success = rep.path_collision_free && rep.failure_reason == FailureReason::kNone;
  return rep.success;
}

}  // namespace

bool AddAicoAttempt(const Scenario& s, const AicoResult& r, PlanResult* out) {
  return AddAicoAttempt(s, s.initial, r, out);
}

bool AddAicoAttempt(const Scenario& s, const ScenarioState& w, const AicoResult& r,
                    PlanResult* out) {
  const bool invalid_input = r.status == SolveStatus::kInvalidInput;
  return FoldAicoAttempt(r, CheckAicoPath(s, w, r.trajectory, invalid_input, true), out);
}

PlanResult RunAicoAttempts(const Scenario& s, const AicoCallback& callback) {
  return RunAicoAttempts(s, s.initial, s.aico, callback);
}

PlanResult RunAicoAttempts(const Scenario& s, const ScenarioState& w, const AicoOptions& aico,
                           const AicoCallback& callback, const Budget& budget,
                           const std::vector<std::string>& disabled_tasks, bool retry) {
  PlanResult out;
  PlanReport& rep = out.report;
  rep.planner = PlannerName(Planner::kAico);
  rep.attempts = 0;
  const double cpu0 = CpuSeconds();
  bool budget_spent = false;
  bool writhe_off = false;  // a writhe task is switched off (aico-goal, the no-writhe ablation)
  for (const std::string& name : WritheTaskNames(w.problem)) {
    for (const std::string& off : disabled_tasks) writhe_off = writhe_off || off == name;
  }
  // True once `c` (counts spent so far) or the CPU time since the start reach the budget.
  const auto over = [&](const QueryCounts& c) {
    using U = Budget::Unit;
    const double used = budget.unit == U::kQueries     ? static_cast<double>(c.state_queries)
                        : budget.unit == U::kPairTests ? static_cast<double>(c.pair_tests())
                        : budget.unit == U::kCpuTime   ? CpuSeconds() - cpu0
                                                       : 0.0;
    return budget.unit != U::kNone && used >= budget.value;
  };
  const int attempts = retry ? static_cast<int>(s.aico_attempts.size()) : 1;
  std::optional<Trajectory> plain_unwinding;
  const auto budget_exhausted = [&] {
    rep.status = SolveStatus::kBudgetExhausted;
    rep.failure_reason = FailureReason::kBudgetExhausted;
    rep.success = false;
  };
  for (int k = 0; k < attempts && !budget_spent; ++k) {
    const AicoInit init_kind = s.aico_attempts[k].init;
    const bool unwinding = init_kind != AicoInit::kDefault;
    if (unwinding && writhe_off) continue;
    if (k > 0 && over(rep.counts)) {  // earlier attempts spent the budget: no attempt starts
      budget_exhausted();
      break;
    }
    // Attempt 0 is the state's own problem unless terms are switched off.
    const bool own = k == 0 && disabled_tasks.empty();
    MotionProblem later = own ? MotionProblem{} : AttemptProblem(s, w, k);
    if (!own) DisableTasks(disabled_tasks, &later);
    // The unwinding init, its continuation's counts charged to the first attempt that uses it; the
    // plain path depends on q0 alone, so later attempts from it reuse it at no charge.
    Trajectory init;
    if (unwinding && init_kind == AicoInit::kUnwinding && plain_unwinding.has_value()) {
      init = *plain_unwinding;
    } else if (unwinding) {
      internal::InitCounts c;
      init = internal::UnwindingInit(s, w, w.problem.q0, init_kind, own ? w.problem : later, &c);
      if (init_kind == AicoInit::kUnwinding) plain_unwinding = init;
      rep.counts += c.units;
      rep.collision_checks += c.collision_queries;
      rep.narrow_phase_calls += c.narrow_phase_calls;
      if (over(rep.counts)) {  // the continuations spent the budget: the attempt does not start
        budget_exhausted();
        break;
      }
    }
    ++rep.attempts;
    AicoOptions options = aico;
    options.max_iterations = s.aico_attempts[k].max_iterations;
    AicoSolver solver(own ? w.problem : later, options, unwinding ? &init : nullptr);
    long probe_queries = 0, probe_narrow = 0;  // validations of trajectories that were no success
    QueryCounts probe_counts;
    // The budget spent after a sweep: this attempt's counts so far, earlier attempts' and probes'.
    const auto spent = [&] { return over(rep.counts + probe_counts + solver.counts()); };
    bool solved = false;
    while (!solver.done()) {
      const AicoStep step = solver.Step();
      if (callback) callback(step.sweep, step.cost, step.accepted, solver.trajectory());
      if (solver.done()) break;
      if (s.stop_when_solved && step.accepted) {
        const Trajectory& path = solver.trajectory();
        if (CheckEndState(s, w, path.q.col(path.num_points() - 1), false).ok()) {
          const AicoPathCheck check = CheckAicoPath(s, w, path, false, false);
          if (check.success()) {
            AicoResult r = solver.result();
            r.status = SolveStatus::kSolved;
            solved = FoldAicoAttempt(r, check, &out);
            break;
          }
          probe_queries += check.queries;
          probe_narrow += check.narrow_phase_calls;
          probe_counts += check.counts;
        }
      }
      if (spent()) {  // after the success test: a sweep that solves is kept
        budget_spent = true;
        break;
      }
    }
    if (!solved) {
      AicoResult r = solver.result();
      if (budget_spent) r.status = SolveStatus::kBudgetExhausted;
      solved = AddAicoAttempt(s, w, r, &out);
      if (budget_spent) {  // a budget is a limit: what the last sweep left is no success
        rep.failure_reason = FailureReason::kBudgetExhausted;
        rep.success = solved = false;
      }
    }
    rep.collision_checks += probe_queries;
    rep.narrow_phase_calls += probe_narrow;
    rep.counts += probe_counts;
    if (solved) break;
  }
  return out;
}

void NameFailure(PlanReport* rep) {
  if (rep->success) return;
  if (rep->status == SolveStatus::kDiverged) {
    rep->failure_reason = FailureReason::kDiverged;
  } else if (rep->status == SolveStatus::kInvalidInput) {
    rep->failure_reason = FailureReason::kInvalidInput;
  } else if (rep->status == SolveStatus::kBudgetExhausted ||
             rep->failure_reason == FailureReason::kNone) {  // kNone: no path within the limits
    rep->failure_reason = FailureReason::kBudgetExhausted;
  }
}

}  // namespace planning
