#include "planning/motion/unwrap_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <locale>
#include <random>
#include <sstream>
#include <stdexcept>

#include "base/random.h"
#include "planning/motion/success.h"
#include "planning/robot/kinematics.h"
#include "topology/winding.h"

namespace planning {

std::vector<UnwrapCell> SummarizeUnwrapRuns(const std::vector<UnwrapRun>& runs,
                                            const std::vector<double>& angles_deg,
                                            const std::vector<Planner>& planners) {
  std::vector<UnwrapCell> cells;
  for (double angle : angles_deg) {
    for (Planner planner : planners) {
      UnwrapCell cell;
      cell.angle_deg = angle;
      cell.planner = planner;
      std::vector<double> checks;
      for (const UnwrapRun& r : runs) {
        if (r.angle_deg != angle || r.planner != planner) continue;
        ++cell.runs;
        if (!r.report.success) continue;
        ++cell.successes;
        checks.push_back(static_cast<double>(r.report.collision_checks));
      }
      const double nan = std::numeric_limits<double>::quiet_NaN();
      cell.mean_checks = nan;
      cell.median_checks = nan;
      if (!checks.empty()) {
        double sum = 0.0;
        for (double c : checks) sum += c;
        cell.mean_checks = sum / static_cast<double>(checks.size());
        std::sort(checks.begin(), checks.end());
        const size_t n = checks.size();
        cell.median_checks = n % 2 == 1 ? checks[n / 2] : 0.5 * (checks[n / 2 - 1] + checks[n / 2]);
      }
      cells.push_back(cell);
    }
  }
  return cells;
}

const UnwrapCell& UnwrapSummaryCell(const UnwrapBenchmarkResult& result, size_t a, size_t p) {
  return result.summary.at(a * result.planners.size() + p);
}

Eigen::Vector3d UnwrapPoleOffset(int seed, double max_m, const Eigen::Vector3d& axis_direction) {
  if (!(max_m > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d d = axis_direction.normalized();
  // An orthonormal basis (e1, e2) of the plane perpendicular to d.
  const Eigen::Vector3d helper =
      std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = d.cross(helper).normalized();
  const Eigen::Vector3d e2 = d.cross(e1);
  std::mt19937 rng(static_cast<unsigned>(seed));
  const double r = max_m * std::sqrt(base::UniformUnit(&rng));  // uniform over the disc
  const double phi = 2.0 * M_PI * base::UniformUnit(&rng);
  return r * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

UnwrapPerturbation MakeUnwrapPerturbation(const ScenarioSpec& spec, double angle_deg, int seeds,
                                          double perturb_m) {
  if (seeds < 1) throw std::invalid_argument("unwrap benchmark: seeds must be >= 1");
  if (!(perturb_m >= 0.0) || !std::isfinite(perturb_m)) {
    throw std::invalid_argument("unwrap benchmark: perturb must be a finite number >= 0");
  }
  UnwrapPerturbation p;
  p.offsets.assign(seeds, Eigen::Vector3d::Zero());
  if (perturb_m == 0.0) return p;
  if (!spec.writhe_report) {
    throw std::invalid_argument("unwrap benchmark: perturb needs the scenario's writhe_report");
  }
  for (size_t i = 0; i < spec.objects.size(); ++i) {
    if (spec.objects[i].name == spec.writhe_report->object.name) p.object = static_cast<int>(i);
  }
  if (p.object >= 0) p.object_name = spec.objects[p.object].name;
  const auto base = SetUpScenario(spec, angle_deg);
  const Eigen::Vector3d axis = ReportAxis(*base).direction;
  for (int seed = 0; seed < seeds; ++seed)
    p.offsets[seed] = UnwrapPoleOffset(seed, perturb_m, axis);
  return p;
}

ScenarioSpec PerturbedUnwrapSpec(ScenarioSpec spec, const UnwrapPerturbation& perturbation,
                                 int seed) {
  if (perturbation.object >= 0)
    spec.objects.at(perturbation.object).xyz += perturbation.offsets.at(seed);
  return spec;
}

namespace {

// UnwrapRun::unwound_winding_turns of a set-up scenario.
double UnwoundWinding(const Scenario& s) {
  if (s.report_chain < 0 || s.success.position_task < 0) return 0.0;
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, s.initial.problem.q0, &kin);
  Eigen::Matrix3Xd chain;
  ChainPoints(s.robot, kin, s.report_chain, &chain);
  const Task& reach = s.initial.problem.tasks.at(static_cast<size_t>(s.success.position_task));
  Eigen::Matrix3Xd segment(3, 2);
  segment.col(0) = chain.col(0);
  segment.col(1) = reach.target.col(reach.target.cols() - 1).head<3>();
  return topology::WindingNumber(segment, ReportAxis(s));
}

// One column of a sweep: a planner, or an AICO ablation.
struct Column {
  Planner planner = Planner::kAico;
  const UnwrapAblation* ablation = nullptr;
};

void CheckBenchmarkOptions(const UnwrapBenchmarkOptions& options) {
  if (options.angles_deg.empty()) throw std::invalid_argument("unwrap benchmark: no angles");
  if (options.seeds < 1) throw std::invalid_argument("unwrap benchmark: seeds must be >= 1");
  if (!(options.perturb_m >= 0.0) || !std::isfinite(options.perturb_m)) {
    throw std::invalid_argument("unwrap benchmark: perturb must be a finite number >= 0");
  }
}

// The spec with the run's options in it (a set-up scenario is not changed).
ScenarioSpec BenchmarkSpec(const UnwrapBenchmarkOptions& options) {
  ScenarioSpec spec = ParseScenarioSpec(options.scenario_path, options.search_roots);
  if (options.geometry) ApplyUnwrapGeometry(*options.geometry, &spec);
  if (options.rrt_budget > 0) spec.rrt.max_checks = options.rrt_budget;
  if (options.aico_stop_when_solved) spec.aico_stop_when_solved = *options.aico_stop_when_solved;
  return spec;
}

// Runs every (angle, column, seed), ordered angle-major, then column, then seed.
std::vector<UnwrapRun> RunColumns(const UnwrapBenchmarkOptions& options, const ScenarioSpec& spec,
                                  const std::vector<Column>& columns) {
  const int total = static_cast<int>(options.angles_deg.size() * columns.size()) * options.seeds;
  // Seed offsets of the pole (perpendicular to its line), and which object it is.
  const UnwrapPerturbation perturbation =
      MakeUnwrapPerturbation(spec, options.angles_deg.front(), options.seeds, options.perturb_m);
  const std::vector<Eigen::Vector3d>& offsets = perturbation.offsets;
  const auto set_up = [](const ScenarioSpec& sp, double angle, double* seconds) {
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<const Scenario> s = SetUpScenario(sp, angle);
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  };
  std::vector<UnwrapRun> runs;
  std::vector<size_t> order;  // sort key of each run
  for (size_t a = 0; a < options.angles_deg.size(); ++a) {
    const double angle = options.angles_deg[a];
    std::unique_ptr<const Scenario> shared;  // unperturbed: one set-up per angle
    double shared_s = 0.0;
    for (int seed = 0; seed < options.seeds; ++seed) {
      std::unique_ptr<const Scenario> own;
      double setup_s = 0.0;
      if (perturbation.object >= 0) {
        own = set_up(PerturbedUnwrapSpec(spec, perturbation, seed), angle, &setup_s);
      } else if (!shared) {
        shared = set_up(spec, angle, &shared_s);
      }
      if (!own) setup_s = shared_s;
      const Scenario& scenario = own ? *own : *shared;
      const bool goal_ok = CheckEndState(scenario, scenario.goal_q, true).ok();
      const double unwound = UnwoundWinding(scenario);
      const double start_closed =
          360.0 * std::abs(ReportWritheTotal(scenario, scenario.initial,
                                             scenario.initial.problem.q0, nullptr, true));
      for (size_t c = 0; c < columns.size(); ++c) {
        UnwrapRun run;
        run.angle_deg = angle;
        run.planner = columns[c].planner;
        run.seed = seed;
        run.pole_offset = offsets[seed];
        run.goal_meets_end_conditions = goal_ok;
        run.unwound_winding_turns = unwound;
        run.start_closed_wrap_deg = start_closed;
        run.setup_warnings = scenario.warnings;
        PlanRequest request;
        request.planner = columns[c].planner;
        request.seed = static_cast<unsigned>(seed);
        request.budget = options.budget;
        if (const UnwrapAblation* ab = columns[c].ablation) {
          run.variant = ab->name;
          request.disabled_tasks = ab->disabled_tasks;
          request.aico_retry = !ab->no_retry;
          if (ab->no_rollout) {
            request.aico = scenario.aico;
            request.aico->rollout_init = false;
          }
        }
        run.report = RunPlanner(scenario, request).report;
        run.report.setup_time_s = setup_s;
        runs.push_back(std::move(run));
        order.push_back((a * columns.size() + c) * static_cast<size_t>(options.seeds) +
                        static_cast<size_t>(seed));
        if (options.progress) {
          options.progress(static_cast<int>(runs.size()), total, runs.back());
        }
      }
    }
  }
  // Runs are produced seed-major within an angle; order them column-major (the documented order).
  std::vector<UnwrapRun> sorted(runs.size());
  for (size_t k = 0; k < runs.size(); ++k) sorted[order[k]] = std::move(runs[k]);
  return sorted;
}

}  // namespace

UnwrapBenchmarkResult RunUnwrapBenchmark(const UnwrapBenchmarkOptions& options) {
  CheckBenchmarkOptions(options);
  if (options.planners.empty()) throw std::invalid_argument("unwrap benchmark: no planners");
  UnwrapBenchmarkResult result;
  result.angles_deg = options.angles_deg;
  result.planners = options.planners;
  result.seeds = options.seeds;
  std::vector<Column> columns;
  for (Planner p : options.planners) columns.push_back({p, nullptr});
  result.runs = RunColumns(options, BenchmarkSpec(options), columns);
  result.summary = SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  return result;
}

std::vector<double> LogBudgets(double lo, double hi, int points) {
  if (!(lo > 0.0) || !(hi > lo) || points < 2 || !std::isfinite(hi)) {
    throw std::invalid_argument("LogBudgets: need 0 < lo < hi and points >= 2");
  }
  std::vector<double> out;
  for (int k = 0; k < points; ++k) {
    out.push_back(k + 1 == points ? hi
                                  : lo * std::pow(hi / lo, static_cast<double>(k) / (points - 1)));
  }
  return out;
}

std::vector<UnwrapSurvivalPoint> UnwrapSurvival(const UnwrapBenchmarkResult& result,
                                                Budget::Unit unit,
                                                const std::vector<double>& budgets) {
  std::vector<UnwrapSurvivalPoint> out;
  for (Planner planner : result.planners) {
    for (double angle : result.angles_deg) {
      for (double b : budgets) {
        UnwrapSurvivalPoint pt;
        pt.planner = planner;
        pt.angle_deg = angle;
        pt.budget.unit = unit;
        pt.budget.value = b;
        for (const UnwrapRun& r : result.runs) {
          if (r.planner != planner || r.angle_deg != angle) continue;
          ++pt.runs;
          if (SolvedWithin(r.report, pt.budget)) ++pt.solved;
          if (r.report.success) continue;
          const bool budget = r.report.status == SolveStatus::kBudgetExhausted ||
                              r.report.failure_reason == FailureReason::kBudgetExhausted;
          ++(budget ? pt.failed_budget : pt.failed_other);
        }
        out.push_back(pt);
      }
    }
  }
  return out;
}

std::string UnwrapSurvivalCsv(const std::vector<UnwrapSurvivalPoint>& points) {
  std::ostringstream csv;
  csv.imbue(std::locale::classic());
  csv.precision(12);
  csv << "unit,budget,planner,angle_deg,runs,solved,fraction,failed_budget,failed_other\n";
  for (const UnwrapSurvivalPoint& p : points) {
    const char* unit = p.budget.unit == Budget::Unit::kCpuTime     ? "cpu_time_s"
                       : p.budget.unit == Budget::Unit::kPairTests ? "pair_tests"
                                                                   : "state_queries";
    csv << unit << "," << p.budget.value << "," << PlannerName(p.planner) << "," << p.angle_deg
        << "," << p.runs << "," << p.solved << ","
        << (p.runs > 0 ? static_cast<double>(p.solved) / p.runs : 0.0) << "," << p.failed_budget
        << "," << p.failed_other << "\n";
  }
  return csv.str();
}

std::vector<UnwrapAblation> UnwrapAblations(const ScenarioSpec& spec) {
  std::vector<UnwrapAblation> out{{"full", {}, false, false}};
  const auto tasks_where = [&](const std::string& name, auto pred) {
    UnwrapAblation ab{name, {}, false, false};
    for (const TaskSpec& t : spec.tasks) {
      if (pred(t)) ab.disabled_tasks.push_back(t.name);
    }
    if (!ab.disabled_tasks.empty()) out.push_back(ab);
  };
  tasks_where("no-writhe",
              [](const TaskSpec& t) { return t.feature.type == FeatureType::kWrithe; });
  tasks_where("no-reach", [&](const TaskSpec& t) {
    return spec.success.position_task && t.name == spec.success.position_task->name;
  });
  tasks_where("no-off-pole",
              [](const TaskSpec& t) { return t.feature.type == FeatureType::kLineClearance; });
  tasks_where("no-winding-guard", [](const TaskSpec& t) { return t.max_jump > 0.0; });
  if (spec.aico.rollout_init) out.push_back({"no-rollout", {}, true, false});
  if (spec.aico_attempts.size() > 1) out.push_back({"no-retry", {}, false, true});
  return out;
}

UnwrapBenchmarkResult RunUnwrapAblation(const UnwrapBenchmarkOptions& options,
                                        std::vector<UnwrapAblation>* ablations) {
  CheckBenchmarkOptions(options);
  const ScenarioSpec spec = BenchmarkSpec(options);
  *ablations = UnwrapAblations(spec);
  UnwrapBenchmarkResult result;
  result.angles_deg = options.angles_deg;
  result.planners = {Planner::kAico};
  result.seeds = options.seeds;
  std::vector<Column> columns;
  for (const UnwrapAblation& ab : *ablations) columns.push_back({Planner::kAico, &ab});
  result.runs = RunColumns(options, spec, columns);
  return result;
}

std::string UnwrapAblationCsv(const UnwrapBenchmarkResult& result) {
  std::ostringstream csv;
  csv.imbue(std::locale::classic());
  csv.precision(12);
  csv << "angle_deg,ablation,seed,success,failure_reason,final_writhe_total,reach_error_m,"
         "final_winding_turns,state_queries,cpu_time_s\n";
  for (const UnwrapRun& r : result.runs) {
    const PlanReport& p = r.report;
    csv << r.angle_deg << "," << r.variant << "," << r.seed << "," << (p.success ? 1 : 0) << ","
        << FailureReasonName(p.failure_reason) << "," << p.final_writhe_total << ","
        << p.reach_error_m << "," << p.final_winding_turns << "," << p.counts.state_queries << ","
        << p.cpu_time_s << "\n";
  }
  return csv.str();
}

std::string UnwrapGeometryCsv(const UnwrapGeometry& geometry, const UnwrapBenchmarkResult& result) {
  std::ostringstream csv;
  csv.imbue(std::locale::classic());
  csv.precision(12);
  csv << "geometry,split,angle_deg,planner,seed,start_wrap_deg,start_closed_wrap_deg,success,"
         "failure_reason,final_writhe_total,reach_error_m,final_winding_turns,"
         "unwound_winding_turns,goal_meets_end_conditions,state_queries,cpu_time_s,setup_time_s,"
         "jumps_through_object,jumps_beyond_ends,jumps_unlocated\n";
  for (const UnwrapRun& r : result.runs) {
    const PlanReport& p = r.report;
    csv << geometry.name << "," << geometry.split << "," << r.angle_deg << ","
        << (r.variant.empty() ? PlannerName(r.planner) : r.variant.c_str()) << "," << r.seed << ","
        << 360.0 * std::abs(p.start_writhe_total) << "," << r.start_closed_wrap_deg << ","
        << (p.success ? 1 : 0) << "," << FailureReasonName(p.failure_reason) << ","
        << p.final_writhe_total << "," << p.reach_error_m << "," << p.final_winding_turns << ","
        << r.unwound_winding_turns << "," << (r.goal_meets_end_conditions ? 1 : 0) << ","
        << p.counts.state_queries << "," << p.cpu_time_s << "," << p.setup_time_s << ","
        << p.winding_jumps.through_object << "," << p.winding_jumps.beyond_ends << ","
        << p.winding_jumps.unlocated << "\n";
  }
  return csv.str();
}

}  // namespace planning
