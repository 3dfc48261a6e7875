#include "app/reports.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/figures.h"
#include "app/io.h"
#include "app/scene_builder.h"
#include "planning/kinematics.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"

namespace app {
namespace {

namespace fs = std::filesystem;
namespace phys = planning::physics;

nlohmann::json VecJson(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(std::round(v[i] * 1e6) / 1e6);
  return a;
}

double Round(double v, double scale = 1e6) { return std::round(v * scale) / scale; }

}  // namespace

// --- plan ---------------------------------------------------------------------------------------

nlohmann::json PlanReportJson(const planning::Scenario& s, const planning::PlanReport& r,
                              unsigned seed) {
  nlohmann::json j;
  j["scenario"] = s.name;
  j["planner"] = r.planner;
  j["seed"] = seed;
  j["success"] = r.success;
  j["status"] = planning::StatusName(r.status);
  j["collision_checks"] = r.collision_checks;
  j["narrow_phase_calls"] = r.narrow_phase_calls;
  j["iterations"] = r.iterations;
  j["attempts"] = r.attempts;
  j["cost"] = r.cost;
  j["path_length"] = r.path_length;
  j["time_s"] = r.time_s;
  j["start_wrap_deg"] = s.start_wrap_deg;
  j["start_writhe_total"] = r.start_writhe_total;
  j["final_writhe_total"] = r.final_writhe_total;
  j["min_clearance_m"] = r.min_clearance_m;
  j["path_collision_free"] = r.path_collision_free;
  j["cost_history"] = r.cost_history;
  j["failure_reason"] = planning::FailureReasonName(r.failure_reason);
  j["failure_step"] = r.failure_step;
  j["reach_error_m"] = r.reach_error_m;
  j["max_winding_jump_turns"] = r.max_winding_jump_turns;
  j["final_winding_turns"] = r.final_winding_turns;
  if (r.writhe_peak_row >= 0) {
    j["writhe_peak"] = {
        {"row", r.writhe_peak_row}, {"col", r.writhe_peak_col}, {"value", r.writhe_peak_value}};
  }
  return j;
}

std::string TrajectoryCsv(const planning::Scenario& s, const planning::Trajectory& tr) {
  std::ostringstream out;
  out.precision(17);
  out << "step,time_s";
  for (const std::string& name : planning::DofNames(s.robot)) out << "," << name;
  out << "\n";
  for (int t = 0; t < tr.num_points(); ++t) {
    out << t << "," << t * tr.dt;
    for (int k = 0; k < tr.num_dofs(); ++k) out << "," << tr.q(k, t);
    out << "\n";
  }
  return out.str();
}

nlohmann::json WritePlanOutputs(const planning::Scenario& s, const planning::PlanResult& result,
                                unsigned seed, const std::string& dir) {
  const nlohmann::json report = PlanReportJson(s, result.report, seed);
  WriteFileAtomic((fs::path(dir) / "trajectory.csv").string(), TrajectoryCsv(s, result.trajectory));
  WriteFileAtomic((fs::path(dir) / "report.json").string(), report.dump(2) + "\n");
  return report;
}

nlohmann::json StoppedReportJson(const StopRequested& stop, nlohmann::json fields) {
  fields["success"] = false;
  fields["status"] = stop.timeout ? "timeout" : "interrupted";
  return fields;
}

std::string PlanSummaryLine(const planning::Scenario& s, const planning::PlanReport& r) {
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s on %s (start wrap %.1f deg): %s [%s, %s], %ld collision checks, %ld "
                "iterations, %.3f s, writhe %+.3f -> %+.3f, min clearance %.3f m",
                r.planner.c_str(), s.name.c_str(), s.start_wrap_deg,
                r.success ? "success" : "FAILED", planning::StatusName(r.status),
                planning::FailureReasonName(r.failure_reason), r.collision_checks, r.iterations,
                r.time_s, r.start_writhe_total, r.final_writhe_total, r.min_clearance_m);
  return line;
}

PlanFrames WritePlanFrames(
    const planning::Scenario& s, const planning::Trajectory& tr, const std::string& dir,
    const std::function<void(const render::Image& frame, const render::Image* heatmap)>& on_frame) {
  planning::Trajectory frames = tr;
  if (tr.dt == 0.0 && tr.num_points() > 1) {
    frames = planning::Densify(tr, std::max(planning::PathLength(tr) / 100.0, 1e-6));
  }
  render::OffscreenContext context;
  render::Renderer renderer(context.proc_loader());
  planning::KinematicsData kin(s.robot);
  SceneMeshCache cache;
  SceneBuildOptions options;
  render::Camera camera;
  planning::TaskWorkspace ws(s.problem);
  std::vector<double> x, writhe, cost;
  double max_abs_w = 1e-9;
  std::vector<Eigen::MatrixXd> matrices;
  for (int t = 0; t < frames.num_points(); ++t) {
    Eigen::MatrixXd W;
    writhe.push_back(planning::ReportWritheTotal(s, frames.q.col(t), &W));
    if (W.size() > 0) max_abs_w = std::max(max_abs_w, W.cwiseAbs().maxCoeff());
    matrices.push_back(W);
    x.push_back(t);
    // Task cost at the matching time slice (RRT frames are mapped onto 0..T).
    const int slice =
        frames.num_points() > 1
            ? static_cast<int>(std::lround(static_cast<double>(t) * s.problem.num_steps /
                                           (frames.num_points() - 1)))
            : 0;
    planning::EvaluateTasks(s.problem, slice, frames.q.col(t), true, &ws);
    cost.push_back(planning::TaskCost(s.problem, slice, Eigen::VectorXd(), ws));
  }
  // Numbered PNGs plus a contact sheet each, and an MP4 of the frames when ffmpeg exists.
  render::FrameWriterOptions frame_options;
  frame_options.prefix = "frame_";
  render::FrameWriter frame_writer((fs::path(dir) / "frames").string(), frame_options);
  render::FrameWriterOptions heatmap_options;
  heatmap_options.prefix = "heatmap_";
  heatmap_options.video = false;
  render::FrameWriter heatmap_writer((fs::path(dir) / "heatmaps").string(), heatmap_options);
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    const render::Scene scene = BuildRobotScene(s.robot, kin, s.objects, options, &cache);
    if (t == 0) camera = FrameSceneCamera(scene);
    const render::Image frame = renderer.Render(scene, camera, 640, 480, {});
    frame_writer.Add(frame);
    std::optional<render::Image> heatmap;
    if (matrices[t].size() > 0) {
      char title[128];
      std::snprintf(title, sizeof(title), "Writhe matrix, frame %d (total %+.3f)", t, writhe[t]);
      heatmap = WritheHeatmapFigure(matrices[t], "robot chain", "object chain", 480, 480, title);
      heatmap_writer.Add(*heatmap);
    }
    if (on_frame) on_frame(frame, heatmap ? &*heatmap : nullptr);
    std::fprintf(stderr, "\rframes %d/%d", t + 1, frames.num_points());
  }
  std::fprintf(stderr, "\n");
  PlanFrames out;
  out.frames = frame_writer.Finish();
  out.heatmaps = heatmap_writer.Finish();
  if (!out.frames.video.empty()) std::fprintf(stderr, "wrote %s\n", out.frames.video.c_str());
  const double max_cost = std::max(1e-12, *std::max_element(cost.begin(), cost.end()));
  std::vector<double> cost_norm;
  for (double c : cost) cost_norm.push_back(c / max_cost);
  render::PlotSeries ws_series;
  ws_series.label = "total writhe";
  ws_series.x = x;
  ws_series.y = writhe;
  ws_series.marker = render::Marker::kNone;
  render::PlotSeries cost_series;
  cost_series.label = "task cost / max";
  cost_series.x = x;
  cost_series.y = cost_norm;
  cost_series.marker = render::Marker::kNone;
  render::PlotOptions po;
  po.title = s.name + ": total writhe and task cost over the trajectory";
  po.x_label = "frame";
  po.y_label = "value";
  po.legend = render::LegendPosition::kTopRight;
  render::WritePng((fs::path(dir) / "writhe_cost.png").string(),
                   render::RenderPlot({ws_series, cost_series}, po));
  return out;
}

std::string PlanReportHtml(const nlohmann::json& r) {
  if (!r.is_object()) return "<p><em>no report</em></p>";
  std::ostringstream t;
  t << "<table>";
  for (const char* key :
       {"planner", "success", "status", "collision_checks", "iterations", "cost", "start_wrap_deg",
        "start_writhe_total", "final_writhe_total", "min_clearance_m"}) {
    if (r.contains(key)) {
      t << "<tr><th>" << key << "</th><td>" << HtmlEscape(r[key].dump()) << "</td></tr>";
    }
  }
  t << "</table>\n";
  return t.str();
}

// --- bench unwrap -------------------------------------------------------------------------------

std::string UnwrapCsv(const planning::UnwrapBenchmarkResult& result) {
  std::ostringstream csv;
  csv << "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
         "time_s,path_length,reach_error_m,pole_offset_m\n";
  for (const planning::UnwrapRun& r : result.runs) {
    const planning::PlanReport& p = r.report;
    csv << r.angle_deg << "," << p.planner << "," << r.seed << "," << (p.success ? 1 : 0) << ","
        << planning::FailureReasonName(p.failure_reason) << "," << p.collision_checks << ","
        << p.narrow_phase_calls << "," << p.time_s << "," << p.path_length << "," << p.reach_error_m
        << "," << r.pole_offset.norm() << "\n";
  }
  return csv.str();
}

std::optional<render::Image> UnwrapFigure(const planning::UnwrapBenchmarkResult& result) {
  std::vector<render::PlotSeries> plot;
  for (size_t p = 0; p < result.planners.size(); ++p) {
    render::PlotSeries ser;
    ser.label = planning::PlannerName(result.planners[p]);
    for (size_t a = 0; a < result.angles_deg.size(); ++a) {
      ser.x.push_back(result.angles_deg[a]);
      ser.y.push_back(planning::UnwrapSummaryCell(result, a, p).mean_checks);
    }
    for (const planning::UnwrapRun& r : result.runs) {
      if (r.planner != result.planners[p] || r.report.success) continue;
      ser.failure_x.push_back(r.angle_deg);
      ser.failure_y.push_back(static_cast<double>(std::max<long>(r.report.collision_checks, 1)));
    }
    plot.push_back(ser);
  }
  render::PlotOptions po;
  po.width = 800;
  po.height = 560;
  po.title = "Unwrapping: collision checks vs angle to unwrap (mean of successful runs)";
  po.x_label = "Angle to unwrap (degrees)";
  po.y_label = "collision checks";
  po.log_y = true;
  bool any_finite = false;
  for (const auto& ser : plot) {
    for (double y : ser.y) any_finite |= std::isfinite(y);
    any_finite |= !ser.failure_y.empty();
  }
  if (!any_finite) return std::nullopt;
  // Headroom above the largest value so failure markers (drawn at the budget) are not cut by the
  // top of the frame.
  double y_top = 0.0;
  for (const auto& ser : plot) {
    for (double y : ser.y) {
      if (std::isfinite(y)) y_top = std::max(y_top, y);
    }
    for (double y : ser.failure_y) y_top = std::max(y_top, y);
  }
  if (y_top > 0.0) po.y_max = 2.5 * y_top;
  return render::RenderPlot(plot, po);
}

std::string UnwrapHtmlTable(const planning::UnwrapBenchmarkResult& result) {
  std::ostringstream t;
  t << "<table><tr><th>angle to unwrap</th>";
  for (planning::Planner p : result.planners) {
    t << "<th>" << planning::PlannerName(p) << ": solved, mean checks of solved runs</th>";
  }
  t << "</tr>\n";
  for (size_t a = 0; a < result.angles_deg.size(); ++a) {
    t << "<tr><td>" << result.angles_deg[a] << "&deg;</td>";
    for (size_t p = 0; p < result.planners.size(); ++p) {
      const planning::UnwrapCell& c = planning::UnwrapSummaryCell(result, a, p);
      char buf[96];
      if (std::isfinite(c.mean_checks)) {
        std::snprintf(buf, sizeof buf, "<td>%d/%d, %.0f</td>", c.successes, c.runs, c.mean_checks);
      } else {
        std::snprintf(buf, sizeof buf, "<td>%d/%d, &ndash;</td>", c.successes, c.runs);
      }
      t << buf;
    }
    t << "</tr>\n";
  }
  t << "</table>\n";
  return t.str();
}

// --- grasp transfer -----------------------------------------------------------------------------

nlohmann::json GraspReportJson(const phys::GraspTrialsResult& result) {
  const phys::StabilityOptions& stab = result.stability;
  nlohmann::json report;
  report["mu"] = stab.sim.mu;
  report["protocol"] = {{"close_time_s", stab.close_time},
                        {"trial_time_s", stab.trial_time},
                        {"dt_s", stab.sim.dt},
                        {"max_slip_m", stab.max_slip},
                        {"max_rotation_deg", stab.max_rotation_deg},
                        {"min_contact_links", stab.min_contact_links}};
  report["grasps"] = nlohmann::json::array();
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    const planning::HumanGrasp& g = result.grasps[gi];
    nlohmann::json gj;
    gj["name"] = g.name;
    gj["type"] = g.type;
    gj["object"] = g.object;
    gj["file"] = fs::path(g.source).filename().string();
    nlohmann::json mj = nlohmann::json::object();
    for (size_t mi = 0; mi < result.methods.size(); ++mi) {
      const phys::GraspTrial& trial = result.trials[gi][mi];
      const planning::TransferResult& t = trial.transfer;
      const phys::StabilityResult& r = trial.stability;
      if (!gj.contains("human_winding")) {
        gj["human_winding"] = VecJson(t.human_winding);
        nlohmann::json hp = nlohmann::json::array();
        for (const Eigen::VectorXd& v : t.human_phalanx_winding) hp.push_back(VecJson(v));
        gj["human_phalanx_winding"] = hp;
      }
      nlohmann::json j;
      j["target_winding"] = VecJson(t.target_winding);
      j["robot_winding"] = VecJson(t.robot_winding);
      nlohmann::json ph = nlohmann::json::array();
      for (const Eigen::VectorXd& v : t.robot_phalanx_winding) ph.push_back(VecJson(v));
      j["robot_phalanx_winding"] = ph;
      j["winding_error"] = Round(trial.winding_error);
      j["epsilon_quality"] = Round(trial.epsilon_quality);
      j["min_clearance_m"] = Round(t.min_clearance);
      j["solver"] = t.solver;
      j["solver_iterations"] = t.iterations;
      j["q"] = VecJson(t.q);
      j["status"] = phys::ToString(r.status);
      j["message"] = r.message;
      j["closure_contact_links"] = r.closure_contact_links;
      j["directions_passed"] = r.directions_passed;
      j["max_slip_m"] = Round(r.max_slip_m);
      j["max_rotation_deg"] = Round(r.max_rotation_deg, 1e3);
      j["stable"] = r.stable;
      nlohmann::json dirs = nlohmann::json::array();
      for (const auto& d : r.directions) {
        dirs.push_back({{"gravity", d.label},
                        {"passed", d.passed},
                        {"slip_m", Round(d.slip_m)},
                        {"rotation_deg", Round(d.rotation_deg, 1e3)},
                        {"contact_links", d.contact_links},
                        {"blown_up", d.blown_up}});
      }
      j["directions"] = dirs;
      mj[planning::ToString(result.methods[mi])] = j;
    }
    gj["methods"] = mj;
    report["grasps"].push_back(gj);
  }
  nlohmann::json summary = nlohmann::json::object();
  for (const phys::GraspMethodSummary& s : result.summary) {
    summary[planning::ToString(s.method)] = {
        {"stable", s.stable}, {"grasps", s.grasps}, {"success_rate", Round(s.rate, 1e4)}};
  }
  report["summary"] = summary;
  return report;
}

std::string GraspSummaryMarkdown(const phys::GraspTrialsResult& result) {
  std::ostringstream md;
  md << "# Grasp transfer to the SDH: ODE stability (mu = " << result.stability.sim.mu << ")\n\n"
     << "Directions passed out of 6 (gravity along +-x, +-y, +-z of the palm, 2 s each at 1 kHz); "
        "a grasp is stable when it passes all 6. eps: Ferrari-Canny epsilon of the contacts at "
        "the end of closing.\n\n| grasp |";
  for (planning::TransferMethod m : result.methods) md << " " << planning::ToString(m) << " |";
  for (planning::TransferMethod m : result.methods) md << " eps " << planning::ToString(m) << " |";
  md << "\n|---|";
  for (size_t i = 0; i < 2 * result.methods.size(); ++i) md << "---|";
  md << "\n";
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    md << "| " << result.grasps[gi].name << " |";
    for (const phys::GraspTrial& trial : result.trials[gi]) {
      md << " " << trial.stability.directions_passed << "/6"
         << (trial.stability.stable ? " stable" : "") << " |";
    }
    for (const phys::GraspTrial& trial : result.trials[gi]) {
      char eps[32];
      std::snprintf(eps, sizeof eps, " %.4f |", trial.epsilon_quality);
      md << eps;
    }
    md << "\n";
  }
  md << "| **success rate** |";
  for (const phys::GraspMethodSummary& s : result.summary) {
    md << " " << s.stable << "/" << s.grasps << " |";
  }
  for (size_t i = 0; i < result.summary.size(); ++i) md << " |";
  md << "\n";
  return md.str();
}

render::Image GraspSummaryFigure(const phys::GraspTrialsResult& result) {
  std::vector<render::PlotSeries> series;
  const render::Marker markers[4] = {render::Marker::kCircle, render::Marker::kSquare,
                                     render::Marker::kTriangle, render::Marker::kDiamond};
  const size_t n = result.grasps.size();
  // Methods side by side within ±0.36 of the grasp (0.12 apart for up to 6 methods).
  const double methods = static_cast<double>(result.methods.size());
  const double spacing = std::min(0.12, 0.72 / std::max(1.0, methods));
  for (size_t mi = 0; mi < result.methods.size(); ++mi) {
    const phys::GraspMethodSummary& s = result.summary[mi];
    render::PlotSeries ps;
    std::ostringstream label;
    label << planning::ToString(s.method) << " (" << s.stable << "/" << n << " stable)";
    ps.label = label.str();
    for (size_t gi = 0; gi < n; ++gi) {
      ps.x.push_back(static_cast<double>(gi + 1) +
                     spacing * (static_cast<double>(mi) - (methods - 1.0) / 2.0));
      ps.y.push_back(result.trials[gi][mi].stability.directions_passed);
    }
    ps.line = false;
    ps.marker = markers[mi % 4];
    series.push_back(ps);
  }
  render::PlotOptions po;
  po.width = 900;
  po.height = 560;
  po.title = "SDH grasp transfer: gravity directions held (mu " +
             std::to_string(result.stability.sim.mu).substr(0, 4) + ")";
  po.x_label = "grasp (row of summary.md)";
  po.y_label = "directions held";
  po.x_min = 0.5;
  po.x_max = n + 0.5;
  po.y_min = -0.5;
  po.y_max = 7.5;
  po.legend = render::LegendPosition::kTopLeft;
  return render::RenderPlot(series, po);
}

std::string WriteGraspOutputs(const phys::GraspTrialsResult& result, const std::string& dir) {
  fs::create_directories(dir);
  const std::string text = GraspReportJson(result).dump(1) + "\n";
  WriteFileAtomic((fs::path(dir) / "report.json").string(), text);
  WriteFileAtomic((fs::path(dir) / "summary.md").string(), GraspSummaryMarkdown(result));
  render::WriteFileAtomically((fs::path(dir) / "summary.png").string(),
                              render::EncodePng(GraspSummaryFigure(result)));
  return text;
}

std::string GraspHtmlTable(const phys::GraspTrialsResult& result) {
  std::ostringstream t;
  t << "<table><tr><th>grasp</th>";
  for (planning::TransferMethod m : result.methods) {
    t << "<th>" << planning::ToString(m) << "</th>";
  }
  t << "</tr>\n";
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    t << "<tr><td>" << HtmlEscape(result.grasps[gi].name) << "</td>";
    for (const phys::GraspTrial& trial : result.trials[gi]) {
      t << "<td>" << trial.stability.directions_passed << "/6"
        << (trial.stability.stable ? " stable" : "") << "</td>";
    }
    t << "</tr>\n";
  }
  t << "<tr><td><b>success rate</b></td>";
  for (const phys::GraspMethodSummary& s : result.summary) {
    t << "<td>" << s.stable << "/" << s.grasps << "</td>";
  }
  t << "</tr></table>\n";
  return t.str();
}

std::string HtmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace app
