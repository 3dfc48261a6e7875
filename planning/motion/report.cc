#include "planning/motion/report.h"

#include <cmath>
#include <cstdio>
#include <locale>
#include <sstream>

#include "base/numbers.h"
#include "planning/robot/kinematics.h"

namespace planning {

nlohmann::json PlanReportJson(const Scenario& s, const PlanReport& r, unsigned seed) {
  nlohmann::json j;
  j["scenario"] = s.name;
  j["planner"] = r.planner;
  j["seed"] = seed;
  j["success"] = r.success;
  j["status"] = StatusName(r.status);
  j["collision_checks"] = r.collision_checks;
  j["narrow_phase_calls"] = r.narrow_phase_calls;
  j["state_queries"] = r.counts.state_queries;  // the common cost units (collision.h)
  j["bool_pair_tests"] = r.counts.bool_pair_tests;
  j["distance_pair_tests"] = r.counts.distance_pair_tests;
  j["cpu_time_s"] = r.cpu_time_s;
  // The goal sampler's share of those (goal-region planners; 0 for the others).
  j["goal_sampler_draws"] = r.goal_sampler_draws;
  j["goal_samples"] = r.goal_samples;
  j["goal_sampler_state_queries"] = r.goal_sampler_counts.state_queries;
  j["goal_sampler_bool_pair_tests"] = r.goal_sampler_counts.bool_pair_tests;
  j["goal_sampler_distance_pair_tests"] = r.goal_sampler_counts.distance_pair_tests;
  j["goal_sampler_cpu_time_s"] = r.goal_sampler_cpu_time_s;
  j["iterations"] = r.iterations;
  j["attempts"] = r.attempts;
  j["cost"] = r.cost;
  j["path_length"] = r.path_length;
  j["time_s"] = r.time_s;
  // A wrap angle means something only for a coil start (unwrap), not e.g. for the ring.
  if (s.spec.start.kind == StartKind::kCoil) j["start_wrap_deg"] = s.start_wrap_deg;
  j["start_writhe_total"] = r.start_writhe_total;
  j["final_writhe_total"] = r.final_writhe_total;
  j["min_clearance_m"] = r.min_clearance_m;
  j["path_collision_free"] = r.path_collision_free;
  j["cost_history"] = r.cost_history;
  j["failure_reason"] = FailureReasonName(r.failure_reason);
  j["failure_step"] = r.failure_step;
  j["reach_error_m"] = r.reach_error_m;
  j["max_winding_jump_turns"] = r.max_winding_jump_turns;
  j["winding_jumps"] = {{"through_object", r.winding_jumps.through_object},
                        {"beyond_ends", r.winding_jumps.beyond_ends},
                        {"unlocated", r.winding_jumps.unlocated}};
  j["final_winding_turns"] = r.final_winding_turns;
  j["failure_detail"] = r.failure_detail;
  if (!s.frozen.empty()) {
    nlohmann::json frozen = nlohmann::json::object();
    for (const auto& [name, value] : s.frozen) frozen[name] = value;
    j["frozen_joints"] = std::move(frozen);
  }
  if (r.writhe_peak_row >= 0) {
    j["writhe_peak"] = {
        {"row", r.writhe_peak_row}, {"col", r.writhe_peak_col}, {"value", r.writhe_peak_value}};
  }
  if (r.loop_checked) {
    j["through_loop"] = {
        {"passed", r.passed_through},
        {"segment", r.through_segment >= 0 ? nlohmann::json(r.through_segment) : nlohmann::json()}};
  }
  return j;
}

std::string TrajectoryCsv(const Scenario& s, const Trajectory& tr) {
  std::ostringstream out;
  out.imbue(std::locale::classic());  // "0.5" whatever the global locale
  out.precision(17);
  out << "step,time_s";
  for (const std::string& name : DofNames(s.robot)) out << "," << name;
  out << "\n";
  for (int t = 0; t < tr.num_points(); ++t) {
    out << t << "," << t * tr.dt;
    for (int k = 0; k < tr.num_dofs(); ++k) out << "," << tr.q(k, t);
    out << "\n";
  }
  return out.str();
}

std::string PlanSummaryLine(const Scenario& s, const PlanReport& r) {
  // The start wrap means something only for a coil start (unwrap); other starts name no angle.
  char wrap[64] = "";
  if (s.spec.start.kind == StartKind::kCoil) {
    std::snprintf(wrap, sizeof(wrap), " (start wrap %s deg)",
                  base::FormatFixed(s.start_wrap_deg, 1).c_str());
  }
  const auto sign = [](double v) {
    std::string t = v >= 0 ? "+" : "";
    return t.append(base::FormatFixed(v, 3));
  };
  return r.planner + " on " + s.name + wrap + ": " + (r.success ? "success" : "FAILED") + " [" +
         StatusName(r.status) + ", " + FailureReasonName(r.failure_reason) + "], " +
         std::to_string(r.collision_checks) + " collision checks, " + std::to_string(r.iterations) +
         " iterations, " + base::FormatFixed(r.time_s, 3) + " s, writhe " +
         sign(r.start_writhe_total) + " -> " + sign(r.final_writhe_total) + ", min clearance " +
         base::FormatFixed(r.min_clearance_m, 3) + " m";
}

std::string UnwrapCsv(const UnwrapBenchmarkResult& result) {
  std::ostringstream csv;
  csv.imbue(std::locale::classic());  // "0.5" whatever the global locale
  csv << "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
         "time_s,path_length,reach_error_m,pole_offset_m,state_queries,bool_pair_tests,"
         "distance_pair_tests,cpu_time_s,setup_time_s,goal_samples,goal_sampler_state_queries,"
         "goal_sampler_pair_tests,goal_sampler_cpu_time_s\n";
  for (const UnwrapRun& r : result.runs) {
    const PlanReport& p = r.report;
    csv << r.angle_deg << "," << p.planner << "," << r.seed << "," << (p.success ? 1 : 0) << ","
        << FailureReasonName(p.failure_reason) << "," << p.collision_checks << ","
        << p.narrow_phase_calls << "," << p.time_s << "," << p.path_length << "," << p.reach_error_m
        << "," << r.pole_offset.norm() << "," << p.counts.state_queries << ","
        << p.counts.bool_pair_tests << "," << p.counts.distance_pair_tests << "," << p.cpu_time_s
        << "," << p.setup_time_s << "," << p.goal_samples << ","
        << p.goal_sampler_counts.state_queries << "," << p.goal_sampler_counts.pair_tests() << ","
        << p.goal_sampler_cpu_time_s << "\n";
  }
  return csv.str();
}

}  // namespace planning
