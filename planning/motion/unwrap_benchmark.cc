#include "planning/motion/unwrap_benchmark.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "base/random.h"

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

UnwrapBenchmarkResult RunUnwrapBenchmark(const UnwrapBenchmarkOptions& options) {
  if (options.angles_deg.empty()) throw std::invalid_argument("unwrap benchmark: no angles");
  if (options.planners.empty()) throw std::invalid_argument("unwrap benchmark: no planners");
  if (options.seeds < 1) throw std::invalid_argument("unwrap benchmark: seeds must be >= 1");
  if (!(options.perturb_m >= 0.0) || !std::isfinite(options.perturb_m)) {
    throw std::invalid_argument("unwrap benchmark: perturb must be a finite number >= 0");
  }
  UnwrapBenchmarkResult result;
  result.angles_deg = options.angles_deg;
  result.planners = options.planners;
  result.seeds = options.seeds;
  const int total =
      static_cast<int>(options.angles_deg.size() * options.planners.size()) * options.seeds;
  ScenarioSpec spec = ParseScenarioSpec(options.scenario_path, options.search_roots);
  // The run's options go into the spec: a set-up scenario is not changed.
  if (options.rrt_budget > 0) spec.rrt.max_checks = options.rrt_budget;
  if (options.aico_stop_when_solved) spec.aico_stop_when_solved = *options.aico_stop_when_solved;
  // Seed offsets of the pole (perpendicular to its line), and which object it is.
  const UnwrapPerturbation perturbation =
      MakeUnwrapPerturbation(spec, options.angles_deg.front(), options.seeds, options.perturb_m);
  const std::vector<Eigen::Vector3d>& offsets = perturbation.offsets;
  for (double angle : options.angles_deg) {
    std::unique_ptr<const Scenario> shared;  // unperturbed: one set-up per angle
    for (int seed = 0; seed < options.seeds; ++seed) {
      std::unique_ptr<const Scenario> own;
      if (perturbation.object >= 0) {
        own = SetUpScenario(PerturbedUnwrapSpec(spec, perturbation, seed), angle);
      } else if (!shared) {
        shared = SetUpScenario(spec, angle);
      }
      const Scenario& scenario = own ? *own : *shared;
      for (Planner planner : options.planners) {
        UnwrapRun run;
        run.angle_deg = angle;
        run.planner = planner;
        run.seed = seed;
        run.pole_offset = offsets[seed];
        run.report = RunPlanner(scenario, planner, static_cast<unsigned>(seed)).report;
        result.runs.push_back(std::move(run));
        if (options.progress) {
          options.progress(static_cast<int>(result.runs.size()), total, result.runs.back());
        }
      }
    }
  }
  // Runs are produced seed-major within an angle; order them planner-major (the documented order).
  std::stable_sort(
      result.runs.begin(), result.runs.end(), [&](const UnwrapRun& a, const UnwrapRun& b) {
        const auto idx = [&](const UnwrapRun& r) {
          const auto a_it =
              std::find(options.angles_deg.begin(), options.angles_deg.end(), r.angle_deg);
          const auto p_it = std::find(options.planners.begin(), options.planners.end(), r.planner);
          return ((a_it - options.angles_deg.begin()) * static_cast<long>(options.planners.size()) +
                  (p_it - options.planners.begin())) *
                     options.seeds +
                 r.seed;
        };
        return idx(a) < idx(b);
      });
  result.summary = SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  return result;
}

}  // namespace planning
