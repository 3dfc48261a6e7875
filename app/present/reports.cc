#include "app/present/reports.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <sstream>

#include "app/figures.h"
#include "app/cli/io.h"
#include "app/scene_builder.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/robot/kinematics.h"
#include "render/heatmap.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"
#include "topology/writhe.h"

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
  // A wrap angle means something only for a coil start (unwrap), not e.g. for the ring.
  if (s.spec.start.kind == planning::StartKind::kCoil) j["start_wrap_deg"] = s.start_wrap_deg;
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
  // The start wrap means something only for a coil start (unwrap); other starts name no angle.
  char wrap[64] = "";
  if (s.spec.start.kind == planning::StartKind::kCoil) {
    std::snprintf(wrap, sizeof(wrap), " (start wrap %.1f deg)", s.start_wrap_deg);
  }
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s on %s%s: %s [%s, %s], %ld collision checks, %ld "
                "iterations, %.3f s, writhe %+.3f -> %+.3f, min clearance %.3f m",
                r.planner.c_str(), s.name.c_str(), wrap, r.success ? "success" : "FAILED",
                planning::StatusName(r.status), planning::FailureReasonName(r.failure_reason),
                r.collision_checks, r.iterations, r.time_s, r.start_writhe_total,
                r.final_writhe_total, r.min_clearance_m);
  return line;
}

double PlanHeatmapLimit(const std::vector<Eigen::MatrixXd>& matrices, double clim) {
  return clim > 0.0 ? clim : render::SequenceLimit(matrices);
}

namespace {

// "arm" -> "Arm segment".
std::string SegmentLabel(std::string chain) {
  if (chain.empty()) return "Segment";
  chain[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(chain[0])));
  return chain + " segment";
}

}  // namespace

render::Figure PlanHeatmapFigure(const planning::Scenario& s, const Eigen::MatrixXd& w,
                                 double time_s, double limit) {
  WritheFigureOptions f;
  f.width = 480;
  f.height = 480;
  f.limit = limit;
  f.mark_peak = true;
  f.title = "Writhe matrix at t = " + render::FormatNumber(time_s, 2) + " s (total " +
            render::FormatNumber(w.sum(), 3, /*plus=*/true) + ")";
  if (s.spec.writhe_report) {
    f.row_label = SegmentLabel(s.spec.writhe_report->chain.name);
    f.col_label = SegmentLabel(s.spec.writhe_report->object.name);
  }
  return WritheFigure(w, "robot chain", "object chain", f);
}

render::Figure WritheCostFigure(const std::string& scenario_name, const std::vector<double>& time_s,
                                const std::vector<double>& writhe,
                                const std::vector<double>& cost) {
  render::PlotPanel top, bottom;
  render::PlotSeries ws("", time_s, writhe);
  ws.marker = render::Marker::kNone;
  top.series = {ws};
  top.axes.y_label = "Total writhe (turns)";
  top.axes.legend = render::LegendPosition::kNone;
  render::PlotSeries cs("", time_s, cost);
  cs.marker = render::Marker::kNone;
  cs.rgba = {214, 39, 40, 255};
  bottom.series = {cs};
  bottom.axes.x_label = "Time (s)";
  bottom.axes.y_label = "Task cost";
  bottom.axes.legend = render::LegendPosition::kNone;
  bottom.axes.y_min = 0.0;
  if (!time_s.empty()) {  // both panels on the same time axis
    for (render::PlotPanel* p : {&top, &bottom}) {
      p->axes.x_min = time_s.front();
      p->axes.x_max = std::max(time_s.back(), time_s.front() + 1e-9);
    }
  }
  render::PanelLayout layout;
  layout.width = 640;
  layout.height = 560;
  layout.title = scenario_name + ": total writhe and task cost over the trajectory";
  return render::PanelsFigure({top, bottom}, layout);
}

PlanFrames WritePlanFrames(
    const planning::Scenario& s, const planning::Trajectory& tr, const std::string& dir,
    const std::function<void(const render::Image& frame, const render::Image* heatmap)>& on_frame,
    const MovingObjectFrames* moving, const PlanFrameOptions& frame_opts) {
  planning::Trajectory frames = tr;
  if (moving != nullptr &&
      (moving->object < 0 || moving->object >= static_cast<int>(s.objects.objects.size()) ||
       moving->positions.size() != static_cast<size_t>(tr.num_points()) || tr.dt == 0.0)) {
    throw std::invalid_argument("WritePlanFrames: moving object positions do not match the frames");
  }
  planning::Environment moved;  // with `moving`: the objects, the moving one placed per frame
  if (moving) moved = s.objects;
  Eigen::Vector3d home = Eigen::Vector3d::Zero();
  if (moving) home = s.objects.objects[moving->object].world_from_object.translation();
  const bool moving_report =
      moving && s.spec.writhe_report &&
      s.spec.writhe_report->object.name == s.objects.objects[moving->object].name;
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
  std::vector<double> x, writhe, cost;  // x: time (s)
  std::vector<Eigen::MatrixXd> matrices;
  for (int t = 0; t < frames.num_points(); ++t) {
    Eigen::MatrixXd W;
    if (moving_report) {
      planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
      Eigen::Matrix3Xd P;
      planning::ChainPoints(s.robot, kin, s.report_chain, &P);
      W = topology::WritheMatrix(P,
                                 s.report_object_chain.colwise() + (moving->positions[t] - home));
      writhe.push_back(W.sum());
    } else {
      writhe.push_back(planning::ReportWritheTotal(s, frames.q.col(t), &W));
    }
    matrices.push_back(W);
    // Task cost at the matching time slice (RRT frames are mapped onto 0..T); time τ · slice.
    const double slice_t = frames.num_points() > 1 ? static_cast<double>(t) * s.problem.num_steps /
                                                         (frames.num_points() - 1)
                                                   : 0.0;
    const int slice = static_cast<int>(std::lround(slice_t));
    x.push_back(slice_t * planning::tau(s.problem));
    planning::EvaluateTasks(s.problem, slice, frames.q.col(t), true, &ws);
    cost.push_back(planning::TaskCost(s.problem, slice, Eigen::VectorXd(), ws));
  }
  // One camera for the whole trajectory: it fits the robot's swept volume and the box regions.
  constexpr int kWidth = 640, kHeight = 480;
  render::Scene swept;
  SceneBuildOptions swept_options = options;
  swept_options.objects = false;
  swept_options.grid = false;
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    render::Scene robot = BuildRobotScene(s.robot, kin, s.objects, swept_options, &cache);
    std::move(robot.shapes.begin(), robot.shapes.end(), std::back_inserter(swept.shapes));
    std::move(robot.tubes.begin(), robot.tubes.end(), std::back_inserter(swept.tubes));
  }
  AddTaskBoxes(s.spec, &swept);
  camera = FitSceneCamera(swept, Eigen::Vector3f(1.0f, -1.3f, 0.8f), 35.0f,
                          static_cast<float>(kWidth) / kHeight);
  swept = render::Scene();
  // Time stamps: the time slices' times, or the share of the path length without time (RRTs).
  PlanFrames out;
  const double length = planning::PathLength(frames);
  double walked = 0.0;
  for (int t = 0; t < frames.num_points(); ++t) {
    char stamp[64];
    if (frames.dt > 0.0) {
      std::snprintf(stamp, sizeof stamp, "t = %.2f s", t * frames.dt);
    } else {
      if (t > 0) walked += (frames.q.col(t) - frames.q.col(t - 1)).norm();
      std::snprintf(stamp, sizeof stamp, "path %.0f%%", length > 0 ? 100.0 * walked / length : 0.0);
    }
    out.labels.push_back(stamp);
  }
  // Numbered PNGs plus a contact sheet each, and an MP4 of the frames when ffmpeg exists.
  render::FrameWriterOptions frame_options;
  frame_options.prefix = "frame_";
  render::FrameWriter frame_writer((fs::path(dir) / "frames").string(), frame_options);
  render::FrameWriterOptions heatmap_options;
  heatmap_options.prefix = "heatmap_";
  heatmap_options.video = false;
  render::FrameWriter heatmap_writer((fs::path(dir) / "heatmaps").string(), heatmap_options);
  const double heatmap_limit = PlanHeatmapLimit(matrices);  // one colour range for the sequence
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    if (moving)
      moved.objects[moving->object].world_from_object.translation() = moving->positions[t];
    render::Scene scene =
        BuildRobotScene(s.robot, kin, moving ? moved : s.objects, options, &cache);
    AddTaskBoxes(s.spec, &scene);
    render::Image frame = renderer.Render(scene, camera, kWidth, kHeight, {});
    if (frame_opts.stamp) render::DrawStamp(&frame, {s.name, out.labels[t]});
    frame_writer.Add(frame, out.labels[t]);
    std::optional<render::Image> heatmap;
    if (matrices[t].size() > 0) {
      const render::Figure figure = PlanHeatmapFigure(s, matrices[t], x[t], heatmap_limit);
      heatmap = figure.Raster();
      WriteVectorFormats(heatmap_writer.Add(*heatmap, out.labels[t]), figure, frame_opts.formats);
    }
    if (on_frame) on_frame(frame, heatmap ? &*heatmap : nullptr);
    Progress("frames %d/%d", t + 1, frames.num_points());
  }
  EndProgress();
  out.frames = frame_writer.Finish();
  out.heatmaps = heatmap_writer.Finish();
  if (!out.frames.video.empty()) std::fprintf(stderr, "wrote %s\n", out.frames.video.c_str());
  const render::Figure plot = WritheCostFigure(s.name, x, writhe, cost);
  render::WriteFigure((fs::path(dir) / "writhe_cost.png").string(), plot);
  WriteVectorFormats((fs::path(dir) / "writhe_cost.png").string(), plot, frame_opts.formats);
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

namespace {

// Quantile q in [0, 1] of `v` (sorted in place), linear between order statistics.
double Quantile(std::vector<double>* v, double q) {
  std::sort(v->begin(), v->end());
  const double pos = q * static_cast<double>(v->size() - 1);
  const size_t k = static_cast<size_t>(pos);
  if (k + 1 >= v->size()) return v->back();
  return (*v)[k] + (pos - static_cast<double>(k)) * ((*v)[k + 1] - (*v)[k]);
}

}  // namespace

std::optional<render::Figure> UnwrapFigure(const planning::UnwrapBenchmarkResult& result) {
  if (result.runs.empty()) return std::nullopt;
  struct Measure {
    const char* title;
    const char* y_label;
    double (*value)(const planning::PlanReport&);
  };
  const Measure measures[3] = {
      {"Collision checks", "Collision checks",
       [](const planning::PlanReport& r) { return static_cast<double>(r.collision_checks); }},
      {"Narrow-phase calls", "Narrow-phase calls",
       [](const planning::PlanReport& r) { return static_cast<double>(r.narrow_phase_calls); }},
      {"Wall time", "Wall time (s)", [](const planning::PlanReport& r) { return r.time_s; }}};
  int seeds = 0;
  for (const planning::UnwrapRun& r : result.runs) seeds = std::max(seeds, r.seed + 1);
  // Failure crosses are staggered vertically by planner (factors 1.25^k about the run's value, k
  // centred on the planner list) so that the failures of several planners at one budget stay
  // visible; on the log axes that is 0.1 decade between neighbouring planners.
  const double planners = static_cast<double>(result.planners.size());
  const auto stagger = [&](size_t p) {
    return std::pow(1.25, static_cast<double>(p) - 0.5 * (planners - 1.0));
  };
  std::vector<render::PlotPanel> panels;
  for (const Measure& m : measures) {
    render::PlotPanel panel;
    for (size_t p = 0; p < result.planners.size(); ++p) {
      render::PlotSeries ser;
      ser.label = planning::PlannerName(result.planners[p]);
      bool any_band = false;
      for (double angle : result.angles_deg) {
        std::vector<double> solved;
        for (const planning::UnwrapRun& r : result.runs) {
          if (r.planner != result.planners[p] || r.angle_deg != angle) continue;
          // Zero cannot be drawn on a log axis: a run with no count sits at 1 (the axis floor).
          const double v = std::max(m.value(r.report), m.value == measures[2].value ? 1e-4 : 1.0);
          if (r.report.success) {
            solved.push_back(v);
          } else {
            ser.failure_x.push_back(angle);
            ser.failure_y.push_back(v * stagger(p));
          }
        }
        const double nan = std::numeric_limits<double>::quiet_NaN();
        ser.x.push_back(angle);
        ser.y.push_back(solved.empty() ? nan : Quantile(&solved, 0.5));
        ser.y_lo.push_back(solved.size() >= 2 ? Quantile(&solved, 0.25) : nan);
        ser.y_hi.push_back(solved.size() >= 2 ? Quantile(&solved, 0.75) : nan);
        any_band |= solved.size() >= 2;
      }
      if (!any_band) ser.y_lo.clear(), ser.y_hi.clear();
      panel.series.push_back(ser);
    }
    panel.axes.title = m.title;
    panel.axes.x_label = "Angle to unwrap (deg)";
    panel.axes.y_label = m.y_label;
    panel.axes.log_y = true;
    panel.axes.legend =
        panels.empty() ? render::LegendPosition::kTopLeft : render::LegendPosition::kNone;
    // Headroom above the data (a third of the decades shown) for the legend and the failure
    // markers at the budget.
    double y_top = 0.0, y_bottom = std::numeric_limits<double>::infinity();
    for (const auto& ser : panel.series) {
      for (const std::vector<double>* v : {&ser.y, &ser.y_lo, &ser.y_hi, &ser.failure_y}) {
        for (double y : *v) {
          if (std::isfinite(y) && y > 0.0) {
            y_top = std::max(y_top, y);
            y_bottom = std::min(y_bottom, y);
          }
        }
      }
    }
    if (y_top > 0.0) {
      const double lo = std::floor(std::log10(y_bottom)), hi = std::log10(y_top);
      panel.axes.y_min = std::pow(10.0, lo);
      panel.axes.y_max = std::pow(10.0, std::ceil(hi + 0.5 * std::max(1.0, hi - lo)));
    }
    panels.push_back(panel);
  }
  render::PanelLayout layout;
  layout.width = 1380;
  layout.height = 480;
  layout.columns = 3;
  layout.title = "Unwrapping (Fig. 4.5): median over the solved runs of " + std::to_string(seeds) +
                 (seeds == 1 ? " seed" : " seeds") +
                 (seeds >= 2 ? ", band: interquartile range" : "") +
                 "; \u2715 failed run (staggered by planner)";
  return render::PanelsFigure(panels, layout);
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

namespace {

// {trials, stable, rate, ci95: [lo, hi]} (Wilson 95 %) of perturbed repetitions.
nlohmann::json PerturbedJson(int trials, int stable) {
  nlohmann::json j = {{"trials", trials}, {"stable", stable}};
  if (trials > 0) {
    const Eigen::Vector2d ci = planning::WilsonInterval(stable, trials);
    j["rate"] = Round(static_cast<double>(stable) / trials, 1e4);
    j["ci95"] = {Round(ci[0], 1e4), Round(ci[1], 1e4)};
  }
  return j;
}

// "5/8 (0.31-0.86)": count and Wilson 95 % interval.
std::string RateText(int stable, int trials, const Eigen::Vector2d& ci) {
  char buf[64];
  if (trials > 0) {
    std::snprintf(buf, sizeof buf, "%d/%d (%.2f-%.2f)", stable, trials, ci[0], ci[1]);
  } else {
    std::snprintf(buf, sizeof buf, "0/0");
  }
  return buf;
}

// Spearman's rank correlation of ε against the ODE outcome over every trial of the run (each
// grasp × method, and each perturbed repetition): {trials, spearman_stable,
// spearman_directions}; a correlation is null when undefined (e.g. every trial stable).
nlohmann::json EpsilonOutcomeJson(const phys::GraspTrialsResult& result) {
  std::vector<double> eps, stable, directions;
  for (const std::vector<phys::GraspTrial>& row : result.trials) {
    for (const phys::GraspTrial& trial : row) {
      eps.push_back(trial.epsilon_quality);
      stable.push_back(trial.stability.stable ? 1.0 : 0.0);
      directions.push_back(trial.stability.directions_passed);
      for (const phys::PerturbedTrial& p : trial.perturbed) {
        eps.push_back(p.epsilon_quality);
        stable.push_back(p.stable ? 1.0 : 0.0);
        directions.push_back(p.directions_passed);
      }
    }
  }
  auto value = [](const std::optional<double>& r) {
    return r ? nlohmann::json(Round(*r, 1e4)) : nlohmann::json(nullptr);
  };
  return {{"trials", eps.size()},
          {"spearman_stable", value(planning::SpearmanCorrelation(eps, stable))},
          {"spearman_directions", value(planning::SpearmanCorrelation(eps, directions))}};
}

}  // namespace

nlohmann::json GraspReportJson(const phys::GraspTrialsResult& result) {
  const phys::StabilityOptions& stab = result.stability;
  nlohmann::json report;
  report["mu"] = stab.sim.mu;
  report["protocol"] = {{"close_time_s", stab.close_time},
                        {"trial_time_s", stab.trial_time},
                        {"dt_s", stab.sim.dt},
                        {"contact_patch_radius_m", stab.sim.contact_patch_radius},
                        {"close_by_rad", result.close_by},
                        {"max_slip_m", stab.max_slip},
                        {"max_rotation_deg", stab.max_rotation_deg},
                        {"min_contact_links", stab.min_contact_links}};
  // ODE's constraint solver, the same for every hand and method.
  report["protocol"]["stepper"] = planning::ToName(stab.sim.stepper);
  if (stab.sim.stepper == phys::Stepper::kQuickStep) {
    report["protocol"]["quickstep_iterations"] = stab.sim.quickstep_iterations;
  }
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
      // Per extra reference curve of the object (objects.json "extra_references"), stacked: the
      // opposition pair (max, min over the fingers) asked for and reached; [] without such curves.
      j["target_extra_winding"] = VecJson(t.target_extra_winding);
      j["robot_extra_winding"] = VecJson(t.robot_extra_winding);
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
      if (result.perturb > 0) {
        j["perturbed"] =
            PerturbedJson(static_cast<int>(trial.perturbed.size()), trial.perturbed_stable);
        // Each repetition: outcome, ε and how far the object was moved and turned from the
        // grasp's pose.
        nlohmann::json reps = nlohmann::json::array();
        for (const phys::PerturbedTrial& p : trial.perturbed) {
          const Eigen::Isometry3d delta = g.world_from_object.inverse() * p.world_from_object;
          reps.push_back({{"stable", p.stable},
                          {"directions_passed", p.directions_passed},
                          {"epsilon_quality", Round(p.epsilon_quality)},
                          {"offset_m", VecJson(p.world_from_object.translation() -
                                               g.world_from_object.translation())},
                          {"rotation_deg",
                           Round(Eigen::AngleAxisd(delta.linear()).angle() * 180.0 / M_PI, 1e3)}});
        }
        j["perturbed"]["repetitions"] = reps;
      }
      mj[planning::ToString(result.methods[mi])] = j;
    }
    gj["methods"] = mj;
    report["grasps"].push_back(gj);
  }
  nlohmann::json summary = nlohmann::json::object();
  for (const phys::GraspMethodSummary& s : result.summary) {
    nlohmann::json sj = {{"stable", s.stable},
                         {"grasps", s.grasps},
                         {"success_rate", Round(s.rate, 1e4)},
                         {"ci95", {Round(s.ci95[0], 1e4), Round(s.ci95[1], 1e4)}}};
    if (result.perturb > 0) sj["perturbed"] = PerturbedJson(s.perturbed_trials, s.perturbed_stable);
    summary[planning::ToString(s.method)] = sj;
  }
  report["summary"] = summary;
  report["epsilon_vs_outcome"] = EpsilonOutcomeJson(result);
  if (result.perturb > 0) {
    report["perturb"] = {{"repetitions", result.perturb},
                         {"seed", result.seed},
                         {"max_translation_m", result.perturb_translation},
                         {"max_rotation_deg", result.perturb_rotation_deg}};
  }
  return report;
}

std::string GraspSummaryMarkdown(const phys::GraspTrialsResult& result) {
  std::ostringstream md;
  md << "# Grasp transfer to the SDH: ODE stability (mu = " << result.stability.sim.mu
     << ", soft-finger contact patch " << result.stability.sim.contact_patch_radius * 1e3
     << " mm, flexion set-points " << result.close_by << " rad past the grasp)\n\n"
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
         << (trial.stability.stable ? " stable" : "");
      if (result.perturb > 0) {
        md << ", perturbed " << trial.perturbed_stable << "/" << trial.perturbed.size();
      }
      md << " |";
    }
    for (const phys::GraspTrial& trial : result.trials[gi]) {
      char eps[32];
      std::snprintf(eps, sizeof eps, " %.4f |", trial.epsilon_quality);
      md << eps;
    }
    md << "\n";
  }
  md << "| **success rate (95 % CI)** |";
  for (const phys::GraspMethodSummary& s : result.summary) {
    md << " " << RateText(s.stable, s.grasps, s.ci95) << " |";
  }
  for (size_t i = 0; i < result.summary.size(); ++i) md << " |";
  md << "\n";
  if (result.perturb > 0) {
    md << "| **perturbed (95 % CI)** |";
    for (const phys::GraspMethodSummary& s : result.summary) {
      md << " " << RateText(s.perturbed_stable, s.perturbed_trials, s.perturbed_ci95) << " |";
    }
    for (size_t i = 0; i < result.summary.size(); ++i) md << " |";
    md << "\n\nperturbed: " << result.perturb << " repetitions per grasp and method, object moved "
       << "by up to " << result.perturb_translation * 1e3 << " mm per axis and turned by up to "
       << result.perturb_rotation_deg << " deg (seed " << result.seed
       << "); intervals: Wilson 95 %.\n";
  }
  const nlohmann::json rank = EpsilonOutcomeJson(result);
  auto text = [](const nlohmann::json& r) {
    char buf[32];
    if (r.is_null()) return std::string("undefined (one outcome only)");
    std::snprintf(buf, sizeof buf, "%.2f", r.get<double>());
    return std::string(buf);
  };
  md << "\nRank correlation (Spearman) of eps with the outcome over all "
     << rank["trials"].get<size_t>() << " trials"
     << (result.perturb > 0 ? " (incl. perturbed)" : "") << ": " << text(rank["spearman_stable"])
     << " against stable, " << text(rank["spearman_directions"]) << " against directions held.\n";
  return md.str();
}

GraspSummaryData GraspSummaryDataOf(const phys::GraspTrialsResult& result) {
  GraspSummaryData d;
  // The grip travel is named only when it is not the protocol's.
  std::string mu = render::FormatNumber(result.stability.sim.mu, 2);
  if (result.close_by != phys::HandBuildOptions{}.close_by) {
    mu += ", grip \u03b4 = " + render::FormatNumber(result.close_by, 2) + " rad";
  }
  const bool perturbed = result.perturb > 0;
  if (perturbed) {
    d.title = "Stable fraction of " + std::to_string(result.perturb) +
              " perturbed poses, \u03bc = " + mu + " (Wilson 95 %)";
    d.y_label = "Stable fraction of perturbed repetitions";
    d.y_max = 1.0;
  } else {
    d.title = "Gravity directions held, \u03bc = " + mu + " (legend: stable, Wilson 95 %)";
    d.y_label = "Gravity directions held (of 6)";
    d.y_max = 6.0;
  }
  for (const planning::HumanGrasp& g : result.grasps) d.grasps.push_back(g.name);
  for (size_t mi = 0; mi < result.methods.size(); ++mi) {
    const phys::GraspMethodSummary& s = result.summary[mi];
    // The legend carries each method's rate with its Wilson 95 % interval: over the grasps
    // (stable = all six directions held) and, with perturbations, over every repetition.
    std::string label =
        std::string(planning::ToString(s.method)) + ": " + RateText(s.stable, s.grasps, s.ci95);
    if (perturbed) {
      label += ", perturbed " + RateText(s.perturbed_stable, s.perturbed_trials, s.perturbed_ci95);
    }
    d.methods.push_back(label);
    d.value.emplace_back();
    if (perturbed) {
      d.lo.emplace_back();
      d.hi.emplace_back();
    }
    for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
      const phys::GraspTrial& trial = result.trials[gi][mi];
      if (!perturbed) {
        d.value.back().push_back(trial.stability.directions_passed);
        continue;
      }
      const int n = static_cast<int>(trial.perturbed.size());
      const Eigen::Vector2d ci =
          n > 0 ? planning::WilsonInterval(trial.perturbed_stable, n) : Eigen::Vector2d(0, 1);
      d.value.back().push_back(n > 0 ? static_cast<double>(trial.perturbed_stable) / n : 0.0);
      d.lo.back().push_back(ci[0]);
      d.hi.back().push_back(ci[1]);
    }
  }
  return d;
}

std::string WriteGraspOutputs(const phys::GraspTrialsResult& result, const std::string& dir,
                              const std::vector<render::FigureFormat>& formats) {
  return WriteGraspOutputs(result, dir, GraspReportJson(result), formats);
}

render::Figure GraspSummaryFigure(const GraspSummaryData& d) {
  render::BarChart chart;
  chart.categories = d.grasps;
  for (size_t m = 0; m < d.methods.size(); ++m) {
    render::BarSeries b;
    b.label = d.methods[m];
    b.values = d.value.at(m);
    if (!d.lo.empty()) {
      b.lo = d.lo.at(m);
      b.hi = d.hi.at(m);
    }
    chart.series.push_back(b);
  }
  render::PlotOptions po;
  po.width = 1280;  // room for the legend's rates with their intervals
  po.height = 560;
  po.title = d.title;
  po.x_label = "Grasp";
  po.y_label = d.y_label;
  po.y_min = 0.0;
  po.y_max = d.y_max;
  po.legend = render::LegendPosition::kOutsideRight;
  return render::BarChartFigure(chart, po);
}

std::string WriteGraspOutputs(const phys::GraspTrialsResult& result, const std::string& dir,
                              const nlohmann::json& report,
                              const std::vector<render::FigureFormat>& formats) {
  fs::create_directories(dir);
  const std::string text = report.dump(1) + "\n";
  WriteFileAtomic((fs::path(dir) / "report.json").string(), text);
  WriteFileAtomic((fs::path(dir) / "summary.md").string(), GraspSummaryMarkdown(result));
  if (!result.grasps.empty()) {  // a run stopped before its first grasp has nothing to plot
    const render::Figure figure = GraspSummaryFigure(GraspSummaryDataOf(result));
    const std::string png = (fs::path(dir) / "summary.png").string();
    render::WriteFigure(png, figure);
    WriteVectorFormats(png, figure, formats);
  }
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
  t << "<tr><td><b>success rate (95 % CI)</b></td>";
  for (const phys::GraspMethodSummary& s : result.summary) {
    t << "<td>" << RateText(s.stable, s.grasps, s.ci95) << "</td>";
  }
  t << "</tr></table>\n";
  return t.str();
}

std::string HtmlEscape(const std::string& s) { return render::XmlEscape(s); }

}  // namespace app
