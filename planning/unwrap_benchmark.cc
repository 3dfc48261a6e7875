#include "planning/unwrap_benchmark.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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

UnwrapBenchmarkResult RunUnwrapBenchmark(const UnwrapBenchmarkOptions& options) {
  if (options.angles_deg.empty()) throw std::invalid_argument("unwrap benchmark: no angles");
  if (options.planners.empty()) throw std::invalid_argument("unwrap benchmark: no planners");
  if (options.seeds < 1) throw std::invalid_argument("unwrap benchmark: seeds must be >= 1");
  UnwrapBenchmarkResult result;
  result.angles_deg = options.angles_deg;
  result.planners = options.planners;
  result.seeds = options.seeds;
  const int total =
      static_cast<int>(options.angles_deg.size() * options.planners.size()) * options.seeds;
  for (double angle : options.angles_deg) {
    ScenarioOverrides overrides;
    overrides.start_wrap_deg = angle;
    overrides.search_roots = options.search_roots;
    const auto scenario = LoadScenario(options.scenario_path, overrides);
    if (options.rrt_budget > 0) scenario->rrt.max_checks = options.rrt_budget;
    for (Planner planner : options.planners) {
      for (int seed = 0; seed < options.seeds; ++seed) {
        UnwrapRun run;
        run.angle_deg = angle;
        run.planner = planner;
        run.seed = seed;
        run.report = RunPlanner(*scenario, planner, static_cast<unsigned>(seed)).report;
        result.runs.push_back(std::move(run));
        if (options.progress) {
          options.progress(static_cast<int>(result.runs.size()), total, result.runs.back());
        }
      }
    }
  }
  result.summary = SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  return result;
}

}  // namespace planning
