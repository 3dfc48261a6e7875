// OMPL benchmark logs of `bench unwrap` (see ompl_log.h).
#include "app/present/ompl_log.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace app {
namespace {

// A number as the log stores it: 12 significant digits, "nan" for anything not finite.
std::string Num(double v) {
  if (!std::isfinite(v)) return "nan";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::string AngleText(double angle_deg) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", angle_deg);
  return buf;
}

// Run properties in the order OMPL writes them (sorted by name).
constexpr const char* kRunProperties[] = {"bool pair tests INTEGER",
                                          "collision checks INTEGER",
                                          "cpu time REAL",
                                          "distance pair tests INTEGER",
                                          "failure reason ENUM",
                                          "iterations INTEGER",
                                          "narrow phase calls INTEGER",
                                          "path length REAL",
                                          "pole offset REAL",
                                          "reach error REAL",
                                          "seed INTEGER",
                                          "setup time REAL",
                                          "solved BOOLEAN",
                                          "state queries INTEGER",
                                          "time REAL"};

std::string RunLine(const planning::UnwrapRun& run) {
  const planning::PlanReport& r = run.report;
  const std::string values[] = {std::to_string(r.counts.bool_pair_tests),
                                std::to_string(r.collision_checks),
                                Num(r.cpu_time_s),
                                std::to_string(r.counts.distance_pair_tests),
                                std::to_string(static_cast<int>(r.failure_reason)),
                                std::to_string(r.iterations),
                                std::to_string(r.narrow_phase_calls),
                                Num(r.path_length),
                                Num(run.pole_offset.norm()),
                                Num(r.reach_error_m),
                                std::to_string(run.seed),
                                Num(r.setup_time_s),
                                r.success ? "1" : "0",
                                std::to_string(r.counts.state_queries),
                                Num(r.time_s)};
  static_assert(std::size(values) == std::size(kRunProperties));
  std::string line;
  for (const std::string& v : values) line += v + "; ";
  return line;
}

}  // namespace

std::string OmplBenchmarkLog(const planning::UnwrapBenchmarkResult& result, size_t angle,
                             const OmplLogInfo& info) {
  const size_t planners = result.planners.size(), seeds = static_cast<size_t>(result.seeds);
  if (angle >= result.angles_deg.size()) {
    throw std::invalid_argument("OMPL log: angle index " + std::to_string(angle) +
                                " out of range (" + std::to_string(result.angles_deg.size()) +
                                " angles)");
  }
  if (result.runs.size() != result.angles_deg.size() * planners * seeds) {
    throw std::invalid_argument("OMPL log: " + std::to_string(result.runs.size()) +
                                " runs do not fill angles x planners x seeds");
  }
  const double angle_deg = result.angles_deg[angle];
  double total_time = 0.0;
  for (size_t k = 0; k < planners * seeds; ++k) {
    const double t = result.runs[angle * planners * seeds + k].report.time_s;
    if (std::isfinite(t)) total_time += t;
  }
  std::ostringstream out;
  out << info.library << " version " << (info.version.empty() ? "0.0.0" : info.version) << "\n"
      << "Experiment unwrap_" << AngleText(angle_deg) << "deg\n"
      << "3 experiment properties\n"
      << "angle_deg REAL = " << Num(angle_deg) << "\n"
      << "perturb_m REAL = " << Num(info.perturb_m) << "\n"
      << "seeds INTEGER = " << result.seeds << "\n"
      << "Running on " << (info.host.empty() ? "UNKNOWN" : info.host) << "\n"
      << "Starting at " << info.start_time << "\n"
      << "<<<|\n"
      << info.setup << (info.setup.empty() || info.setup.back() == '\n' ? "" : "\n")
      << "|>>>\n"
      // No per-run time or memory limit: the RRTs stop at their collision-check budget.
      << "0 is the random seed\n"
      << "0 seconds per run\n"
      << "0 MB per run\n"
      << result.seeds << " runs per planner\n"
      << Num(total_time) << " seconds spent to collect the data\n"
      << "1 enum type\n"
      << "failure_reason";
  for (int k = 0; k <= static_cast<int>(planning::FailureReason::kInvalidInput); ++k) {
    out << "|" << planning::FailureReasonName(static_cast<planning::FailureReason>(k));
  }
  out << "\n" << planners << " planners\n";
  for (size_t p = 0; p < planners; ++p) {
    const planning::Planner planner = result.planners[p];
    out << planning::PlannerName(planner) << "\n";
    if (planning::IsAico(planner)) {
      out << "0 common properties\n";
    } else {
      out << "1 common properties\n"
          << "collision check budget = "
          << (!info.budget.empty()  ? info.budget
              : info.rrt_budget > 0 ? std::to_string(info.rrt_budget)
                                    : std::string("scenario"))
          << "\n";
    }
    out << std::size(kRunProperties) << " properties for each run\n";
    for (const char* name : kRunProperties) out << name << "\n";
    out << seeds << " runs\n";
    for (size_t s = 0; s < seeds; ++s) {
      const planning::UnwrapRun& run = result.runs[(angle * planners + p) * seeds + s];
      if (run.planner != planner || run.angle_deg != angle_deg) {
        throw std::invalid_argument("OMPL log: runs are not in angle, planner, seed order");
      }
      out << RunLine(run) << "\n";
    }
    out << ".\n";
  }
  return out.str();
}

std::string OmplLogPath(const std::string& file, double angle_deg) {
  const std::filesystem::path path(file);
  std::filesystem::path out =
      path.parent_path() /
      (path.stem().string() + "_" + AngleText(angle_deg) + "deg" + path.extension().string());
  return out.string();
}

}  // namespace app
