// `topoplan demo`: the main job. Runs every result the project produces — the same library calls
// and output formatters as the commands — and writes them with an index.html into one folder.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "app/cli/cli.h"
#include "app/cli/command.h"
#include "app/cli/demo_page.h"
#include "app/cli/figure_flags.h"
#include "app/cli/forked_jobs.h"
#include "app/cli/grasp_forked.h"
#include "app/cli/io.h"
#include "app/cli/unwrap_forked.h"
#include "app/present/grasp_frames.h"
#include "app/present/reports.h"
#include "base/assets.h"
#include "base/numbers.h"
#include "base/str_cat.h"
#include "base/version.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/motion/planner.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/physics/grasp_trials.h"
#include "render/figure.h"
#include "render/frames.h"
#include "render/image.h"
#include "topology/polyline.h"
#include "topology/writhe.h"
#include "visualize/figures.h"

namespace app {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string out_dir = "demo-out";
  bool full = false;              // the whole Figure 4.5 sweep (0..1080 deg every 15, 3 seeds)
  bool no_grasp = false;          // skip the grasp-transfer stage
  bool all_frames = false;        // frames of every grasp trial, not only those the page shows
  double timeout = 0.0;           // --timeout: seconds, 0 = none
  int jobs = 0;                   // --jobs: stages at the same time (0: the number of cores)
  std::vector<std::string> only;  // --only: these stages (writhe, unwrap, ...); empty: all
  std::vector<render::FigureFormat> formats;  // --formats: figures also as SVG/PDF
};

// Example chain pairs shipped in assets/chains/ and what their total writhe should be.
struct ChainPair {
  const char* name;
  const char* a;
  const char* b;
  const char* expected;
};
constexpr ChainPair kPairs[] = {
    {"hopf", "hopf_a.csv", "hopf_b.csv", "-1 (Hopf link, linking number)"},
    {"unlinked", "unlinked_a.csv", "unlinked_b.csv", "0 (separate rings)"},
    {"torus_2_6", "torus_2_6_a.csv", "torus_2_6_b.csv", "|3| ((2,6) torus link)"},
    {"helix_pole", "helix_3turns.csv", "pole.csv", "about 3 (3-turn helix around a pole)"},
    {"ring_arm", "ring.csv", "arm_through_ring.csv", "about -0.9 (open arm through a ring)"},
};

class Demo {
 public:
  explicit Demo(const DemoArgs& args) : args_(args), out_(args.out_dir) {}

  int Run() {
    // The whole page at once: staged inside the folder, committed at the end (a re-run replaces
    // the previous demo's files, none of them stale).
    OutputDir output(args_.out_dir, "-o", "demo");
    out_ = output.staging();
    const StopCheck stop(args_.timeout);  // the commands of each stage see the same deadline
    stop_ = &stop;
    std::printf("topoplan demo -> %s\n", fs::absolute(args_.out_dir).c_str());
    const std::vector<Part> parts = Parts();
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int requested = args_.jobs > 0 ? args_.jobs : cores;
    const int jobs = std::min(static_cast<int>(parts.size()), requested);
    // The grasp and Fig. 4.5 stages fork workers of their own, from a process that runs nothing
    // else (a stage's process, or this one when it is the only stage).
    workers_ = jobs > 1 || parts.size() == 1 ? requested : 1;
    if (jobs <= 1) {
      for (const Part& p : parts) Stage(p.title, p.body);
    } else {
      RunParallel(parts, jobs);
    }
    WriteIndex();
    output.Commit();
    Note("wrote %s", (fs::path(args_.out_dir) / "index.html").c_str());
    if (stopped_) {
      std::printf("status: %s\n", stopped_timeout_ ? "timeout" : "interrupted");
      return stopped_timeout_ ? kExitFailed : kExitInterrupted;
    }
    return worst_;
  }

 private:
  // One stage of the page: its name (--only), its title and what it runs; `cost` orders the
  // parallel schedule (the longest first, so that it does not start last).
  struct Part {
    std::string name, title;
    std::function<int()> body;
    int cost = 0;
  };

  std::vector<Part> Parts() {
    std::vector<Part> all;
    all.push_back(
        {"writhe", "writhe matrices of the example chains", [this] { return Writhe(); }, 0});
    all.push_back({"unwrap", "unwrap: AICO with a writhe target (arm coiled 720 deg around a pole)",
                   [this] { return Unwrap(); }, 3});
    all.push_back({"ring", "reach through a ring (thesis Fig. 4.4)", [this] { return Ring(); }, 1});
    all.push_back(
        {"bench",
         args_.full ? "Fig. 4.5 benchmark, full sweep" : "Fig. 4.5 benchmark, reduced sweep",
         [this] { return Bench(); }, 4});
    if (!args_.no_grasp) {
      all.push_back({"grasp", "grasp transfer human hand -> SDH, ODE stability",
                     [this] { return Grasp(); }, 5});
    }
    all.push_back(
        {"viewer", "interactive viewer, headless screenshot", [this] { return Viewer(); }, 2});
    if (args_.only.empty()) return all;
    std::vector<Part> some;
    for (Part& p : all) {
      if (std::find(args_.only.begin(), args_.only.end(), p.name) != args_.only.end()) {
        some.push_back(std::move(p));
      }
    }
    return some;
  }

  // Every part in its own forked process, `workers` at a time, the longest first. Each child
  // writes its files into the staging folder (the parts' files are disjoint) and its section of
  // the page into .demo-parts/NAME.html; its output goes to .demo-parts/NAME.log, printed as one
  // block when the part ends. The page is assembled in the parts' order, so nothing written
  // depends on the schedule.
  void RunParallel(const std::vector<Part>& parts, int workers) {
    const fs::path dir = out_ / ".demo-parts";
    fs::create_directories(dir);
    std::vector<size_t> order(parts.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return parts[a].cost > parts[b].cost; });
    std::vector<ForkedJob> jobs;
    for (size_t i : order) {
      const Part& p = parts[i];
      jobs.push_back({p.name,
                      [this, &p, dir] {
                        // Progress lines would only clutter the part's log.
                        if (GetVerbosity() == Verbosity::kNormal) SetVerbosity(Verbosity::kQuiet);
                        html_.str("");
                        const int rc = RunGuarded(base::StrCat("demo: ", p.title), p.body);
                        base::WriteFileAtomic((dir / (p.name + ".html")).string(), html_.str());
                        return rc;
                      },
                      (dir / (p.name + ".log")).string()});
    }
    const auto t0 = std::chrono::steady_clock::now();
    ForkedJobsOptions options;
    options.workers = workers;
    options.on_start = [&](size_t k) {
      std::printf("[%zu] %s: started\n", order[k] + 1, parts[order[k]].title.c_str());
    };
    options.on_done = [&](size_t k, const ForkedJobResult& r) {
      const size_t i = order[k];
      std::printf("\n[%zu] %s\n", i + 1, parts[i].title.c_str());
      std::ifstream log(dir / (parts[i].name + ".log"));
      for (std::string line; std::getline(log, line);) std::printf("%s\n", line.c_str());
      std::printf("[%zu] %s (%.1f s, %.1f s CPU)\n", i + 1, r.exit_code == 0 ? "done" : "FAILED",
                  r.wall_s, r.cpu_s);
      std::fflush(stdout);
    };
    options.should_stop = [this] {
      try {
        stop_->Poll();
        return false;
      } catch (const StopRequested& e) {
        if (!stopped_) stopped_timeout_ = e.timeout;
        stopped_ = true;
        return true;
      }
    };
    const std::vector<ForkedJobResult> results = RunForkedJobs(jobs, options);
    double cpu = 0.0;
    std::vector<const ForkedJobResult*> by_part(parts.size());
    for (size_t k = 0; k < order.size(); ++k) by_part[order[k]] = &results[k];
    for (size_t i = 0; i < parts.size(); ++i) {
      const ForkedJobResult& r = *by_part[i];
      if (!r.started) {
        stage_status_.push_back(
            {parts[i].title +
                 " (skipped: " + (stopped_timeout_ ? "time limit reached" : "interrupted") + ")",
             stopped_timeout_ ? 1 : 130});
        continue;
      }
      cpu += r.cpu_s;
      int rc = r.exit_code > 128 ? kExitInterrupted : r.exit_code;
      // Stopped by the time limit: the SIGTERM that ended the stage is the limit's (exit 1).
      if (rc == kExitInterrupted && stopped_ && stopped_timeout_) rc = kExitFailed;
      stage_status_.push_back({parts[i].title, rc});
      if (rc > worst_) worst_ = rc;
      std::ifstream fragment(dir / (parts[i].name + ".html"));
      if (fragment) {
        html_ << fragment.rdbuf();
      } else {
        html_ << "<h2>" << HtmlEscape(parts[i].title) << "</h2>\n<p>failed (exit " << rc
              << ")</p>\n";
      }
    }
    std::printf("\n%zu stages in %.1f s (%.1f s CPU, %d at a time)\n", parts.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), cpu,
                workers);
    fs::remove_all(dir);
  }

  // Runs one stage with a progress line; keeps the worst exit code (2/3 beat 1).
  template <typename F>
  void Stage(const std::string& title, F body) {
    ++stage_;
    try {
      stop_->Poll();
    } catch (const StopRequested& e) {  // the remaining stages are skipped
      stopped_ = true;
      stopped_timeout_ = e.timeout;
      stage_status_.push_back({title + " (skipped: " + e.what() + ")", e.timeout ? 1 : 130});
      return;
    }
    std::printf("\n[%d] %s\n", stage_, title.c_str());
    std::fflush(stdout);
    const auto t0 = std::chrono::steady_clock::now();
    // Exceptions become exit codes as for any command (EnvironmentError: 3, others: 2).
    const int rc = RunGuarded("demo: " + title, body);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[%d] %s (%.1f s)\n", stage_, rc == 0 ? "done" : "FAILED", s);
    if (rc > worst_) worst_ = rc;
    stage_status_.push_back({title, rc});
  }

  // `path` as the user will find it: inside the output folder, never its staging area.
  std::string Shown(const std::string& path) const {
    const std::string staging = out_.string();
    if (path.rfind(staging, 0) != 0) return path;
    return args_.out_dir + path.substr(staging.size());
  }

  // Runs `topoplan ARGS` in-process (quietly: the demo says what it writes) and shows the
  // command as a user would type it, with the output folder's name (never its staging area).
  int Sub(const std::vector<std::string>& args) {
    std::string line = "  $ topoplan";
    for (const std::string& a : args) line += " " + Shown(a);
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    std::vector<std::string> quiet{"-q"};
    quiet.insert(quiet.end(), args.begin(), args.end());
    return RunCommandLine(quiet);
  }

  int Writhe() {
    fs::create_directories(out_ / "writhe");
    std::ostringstream rows;
    int rc = 0;
    for (const ChainPair& p : kPairs) {
      const std::string a = base::AssetPath(std::string("chains/") + p.a);
      const std::string b = base::AssetPath(std::string("chains/") + p.b);
      const Eigen::MatrixXd w =
          topology::WritheMatrix(topology::ReadChainCsv(a), topology::ReadChainCsv(b));
      nlohmann::ordered_json j;
      j["rows"] = w.rows();
      j["cols"] = w.cols();
      j["total"] = w.sum();
      nlohmann::json m = nlohmann::json::array();
      for (Eigen::Index r = 0; r < w.rows(); ++r) {
        m.push_back(nlohmann::json::array());
        for (Eigen::Index c = 0; c < w.cols(); ++c) m.back().push_back(w(r, c));
      }
      j["matrix"] = std::move(m);
      base::WriteFileAtomic((out_ / "writhe" / (std::string(p.name) + ".json")).string(),
                            j.dump() + "\n");
      const std::string png = "writhe/" + std::string(p.name) + ".png";
      for (render::FigureFormat f : args_.formats) {  // PNG always (the page shows it)
        if (f == render::FigureFormat::kPng) continue;
        rc = std::max(rc,
                      Sub({"heatmap", a, b, "-o", render::PathWithFormat((out_ / png).string(), f),
                           "--size", "480x400", "--mark-peak"}));
      }
      rc = std::max(rc, Sub({"heatmap", a, b, "-o", (out_ / png).string(), "--size", "480x400",
                             "--mark-peak"}));
      char line[1024];
      std::snprintf(line, sizeof line,
                    "<tr><td>%s</td><td>%s &times; %s</td><td>%ldx%ld</td><td>%s</td>"
                    "<td>%s</td><td><a href=\"%s\"><img src=\"%s\" width=\"480\"></a>"
                    "<br><a href=\"writhe/%s.json\">json</a></td></tr>\n",
                    p.name, p.a, p.b, static_cast<long>(w.rows()), static_cast<long>(w.cols()),
                    render::FormatNumber(w.sum(), 6, /*plus=*/true).c_str(),
                    HtmlEscape(p.expected).c_str(), png.c_str(), png.c_str(), p.name);
      rows << line;
    }
    html_ << "<h2>1. Writhe matrices of example chains</h2>\n"
             "<p>Entry (i, j) is the Gauss linking integral of segment i of the first chain and "
             "segment j of the second, /4&pi;. Totals of closed chains are linking numbers.</p>\n"
             "<table><tr><th>pair</th><th>chains</th><th>size</th><th>total writhe</th>"
             "<th>expected</th><th>heatmap</th></tr>\n"
          << rows.str() << "</table>\n";
    return rc;
  }

  // `topoplan plan NAME --planner aico -o DIR --frames` as library calls: the same files, and the
  // report for the page. `on_frame` sees every rendered frame with its writhe heatmap.
  int PlanAico(
      const std::string& name, const fs::path& dir, nlohmann::json* report, PlanFrames* frames,
      const std::function<void(const render::Image&, const render::Image*)>& on_frame = {}) {
    std::printf("  plan %s with aico -> %s\n", name.c_str(), Shown(dir.string()).c_str());
    std::fflush(stdout);
    const auto scenario = planning::LoadScenarioArg(name);
    const planning::PlanResult result =
        planning::RunPlanner(*scenario, planning::Planner::kAico, /*seed=*/0);
    *report = WritePlanOutputs(*scenario, result, /*seed=*/0, dir.string());
    if (result.trajectory.num_points() > 0) {
      *frames = WritePlanFrames(*scenario, result.trajectory, dir.string(), on_frame, nullptr,
                                PlanFrameOptions{.formats = args_.formats});
    }
    std::printf("  %s\n", planning::PlanSummaryLine(*scenario, result.report).c_str());
    return result.report.success ? kExitOk : kExitFailed;
  }

  int Unwrap() {
    const fs::path dir = out_ / "unwrap";
    // One movie frame per time slice: the scene next to its writhe heatmap.
    render::FrameWriterOptions fo;
    fo.prefix = "unwrap_";
    fo.fps = 12;
    render::FrameWriter writer((dir / "movie").string(), fo);
    nlohmann::json report;
    PlanFrames frames;
    const int rc = PlanAico("unwrap", dir, &report, &frames,
                            [&](const render::Image& frame, const render::Image* heatmap) {
                              if (heatmap) writer.Add(SideBySideImages(frame, *heatmap));
                            });
    // The movie's contact sheet gives each frame's time, as the frames themselves do.
    if (writer.size() == static_cast<int>(frames.labels.size())) {
      for (int i = 0; i < writer.size(); ++i) writer.SetLabel(i, frames.labels[i]);
    }
    const render::FrameSequence seq = writer.Finish();
    std::printf("  movie: %zu frames%s\n", seq.frames.size(),
                seq.video.empty() ? " (no ffmpeg: no video)" : (", " + Shown(seq.video)).c_str());
    html_ << "<h2>2. Unwrapping an arm coiled around a pole</h2>\n"
             "<p>The 20-link arm starts wrapped about 720&deg; around the pole; AICO's task is a "
             "total writhe of 0 (linearly interpolated over T = 50 steps) plus reaching the "
             "cylinder, with collision and joint-limit tasks. Left: the arm; right: its writhe "
             "matrix against the pole at the same time step.</p>\n"
          << PlanReportHtml(report);
    if (!seq.video.empty()) {
      html_ << "<p><video controls width=\"960\" src=\"unwrap/movie/"
            << fs::path(seq.video).filename().string() << "\"></video></p>\n";
    }
    if (!seq.contact_sheet.empty()) {
      html_ << "<p><a href=\"unwrap/movie/contact_sheet.png\"><img "
               "src=\"unwrap/movie/contact_sheet.png\" width=\"960\"></a></p>\n";
    }
    html_ << "<p><a href=\"unwrap/writhe_cost.png\"><img src=\"unwrap/writhe_cost.png\" "
             "width=\"640\"></a></p>\n";
    return rc;
  }

  int Ring() {
    const fs::path dir = out_ / "ring";
    nlohmann::json report;
    PlanFrames frames;
    const int rc = PlanAico("reach_through_ring", dir, &report, &frames);
    html_ << "<h2>3. Reaching through a ring with a writhe target (Fig. 4.4)</h2>\n"
             "<p>KUKA LWR 4 with the Schunk SDH; tasks: the writhe matrix of the hand chain "
             "against the ring chain (target from the final-pose estimate) and an end-effector "
             "box (plus collision and joint limits; no reach task). Final pose and its writhe "
             "matrix (rows: wrist-to-palm, palm, palm-to-finger-tip; the outlined cell is the "
             "largest |entry|): the peak is in the finger row, the link that passes through "
             "the ring.</p>\n"
          << PlanReportHtml(report);
    if (!frames.frames.frames.empty() && !frames.heatmaps.frames.empty()) {
      const std::string f =
          "ring/frames/" + fs::path(frames.frames.frames.back()).filename().string();
      const std::string h =
          "ring/heatmaps/" + fs::path(frames.heatmaps.frames.back()).filename().string();
      html_ << "<p><a href=\"" << f << "\"><img src=\"" << f << "\" width=\"560\"></a> "
            << "<a href=\"" << h << "\"><img src=\"" << h << "\" width=\"420\"></a></p>\n";
    }
    html_ << "<p><a href=\"ring/writhe_cost.png\"><img src=\"ring/writhe_cost.png\" "
             "width=\"640\"></a></p>\n";
    return rc;
  }

  int Bench() {
    const fs::path dir = out_ / "bench";
    planning::UnwrapBenchmarkOptions options;
    options.scenario_path = base::ResolveScenarioPath("unwrap");
    options.search_roots = {base::AssetRoot()};
    // Reduced: 0..900 deg every 90 deg, 1 seed; full: 0..1080 deg every 15 deg, 3 seeds.
    const double max_angle = args_.full ? 1080.0 : 900.0, step = args_.full ? 15.0 : 90.0;
    for (int k = 0; k * step <= max_angle + 1e-9; ++k) options.angles_deg.push_back(k * step);
    options.planners = planning::DefaultPlanners();  // with the OMPL peers when built
    options.seeds = args_.full ? 3 : 1;
    options.progress = [this](int done, int total, const planning::UnwrapRun& run) {
      Progress("  %d/%d runs (%s @ %.0f deg seed %d)", done, total,
               planning::PlannerName(run.planner), run.angle_deg, run.seed);
      stop_->Poll();  // a stopped benchmark stage ends (as a failed stage) at a run boundary
      if (done == total) EndProgress();
    };
    // With --jobs N > 1 the angles run in N processes of their own, as the grasp trials do.
    UnwrapRunOptions run;
    run.workers = workers_;
    run.scratch_dir = (out_ / ".bench-runs").string();
    run.should_stop = [this] { return stop_->Stopped(); };
    const UnwrapForkedResult ran = RunUnwrapBenchmarkInProcesses(options, run);
    if (ran.exit_code != 0) {
      stop_->Poll();  // a stopped worker: the stage ends as a stopped stage
      return ran.exit_code;
    }
    const planning::UnwrapBenchmarkResult& result = ran.result;
    base::WriteFileAtomic((dir / "unwrap.csv").string(), planning::UnwrapCsv(result));
    if (const auto figure = visualize::UnwrapFigure(result)) {
      render::WriteFigure((dir / "unwrap.png").string(), *figure);
      visualize::WriteVectorFormats((dir / "unwrap.png").string(), *figure, args_.formats);
    }
    // Planners that fail at large angles are the figure's point, not a demo failure.
    html_ << "<h2>4. Collision checks vs angle to unwrap (Fig. 4.5)</h2>\n"
             "<p>AICO with the writhe task against uni-directional RRT (10% goal bias) and "
             "bi-directional RRT, both given the final-pose estimate as their goal (and OMPL's "
             "RRT and RRTConnect on the same problem when this build has OMPL); a run that "
             "exhausts its budget of collision checks counts as failed (marked). The figure shows "
             "the median (and the interquartile band with several seeds) over the solved runs, "
             "the table the mean. Wall times are those of this run of the demo. "
          << (args_.full ? "Full sweep."
                         : "Reduced sweep; <code>topoplan demo --full</code> runs "
                           "0&ndash;1080&deg; every 15&deg; with 3 seeds.")
          << "</p>\n<p><a href=\"bench/unwrap.png\"><img src=\"bench/unwrap.png\" "
             "width=\"960\"></a></p>\n"
          << UnwrapHtmlTable(result) << "<p><a href=\"bench/unwrap.csv\">unwrap.csv</a></p>\n";
    return kExitOk;
  }

  int Grasp() {
    const fs::path dir = out_ / "grasp";
    namespace phys = planning::physics;
    const planning::GraspInputs in = planning::LoadGraspInputs(planning::SelectGraspFiles("all"));
    const std::vector<planning::TransferMethod> methods = planning::AllTransferMethods();
    phys::GraspTrialsOptions options;  // default protocol (mu 1), no perturbation
    options.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    // With --jobs N > 1 the trials run in N processes of their own (this stage's process only
    // waits), so the stage keeps every core busy that the other stages leave free.
    GraspRunOptions run;
    run.workers = workers_;
    run.frames = true;
    // The page shows the winding transfers (each with the human grasp beside it); drawing the
    // other 40 trials costs more CPU than all 48 trials' transfers and physics (--all-frames).
    if (!args_.all_frames) run.frame_methods = {planning::TransferMethod::kWinding};
    run.out_dir = dir.string();
    run.scratch_dir = (out_ / ".grasp-trials").string();
    run.should_stop = [this] { return stop_->Stopped(); };
    const GraspRunResult ran = RunGraspTrialsInProcesses(in, methods, options, run);
    stop_->Poll();  // stopped: the stage ends here (as a stopped stage)
    if (ran.exit_code != 0) return ran.exit_code;
    const phys::GraspTrialsResult& result = ran.trials;
    WriteGraspOutputs(result, dir.string(), args_.formats);
    // Unstable baseline grasps are results, not errors.
    html_ << "<h2>5. Grasp transfer: human hand &rarr; Schunk SDH, tested in ODE</h2>\n"
             "<p>Each human grasp is encoded as winding numbers of the finger chains about the "
             "object; AICO finds an SDH posture with the mapped winding target. Every SDH method "
             "solves the same AICO problem and differs only in its target term: winding, "
             "winding_only (windings + non-penetration only), contact_only (the shared contact "
             "and non-penetration terms alone), fingertip, joint (linear joint mapping, then the "
             "same non-penetration projection); human is the demonstration itself under the same "
             "protocol. Stability: gravity along &plusmn;x, &plusmn;y, &plusmn;z for 2 s each at "
             "1 kHz; cells are gravity directions held out of 6.</p>\n"
             "<p><a href=\"grasp/summary.png\"><img src=\"grasp/summary.png\" "
             "width=\"640\"></a></p>\n"
          << GraspHtmlTable(result)
          << "<p><a href=\"grasp/report.json\">report.json</a></p>\n"
             "<h3>Human grasps and the transferred SDH grasps (winding method), with their "
             "stability tests</h3>\n<p>Left: the demonstrated human grasp; right: the SDH "
             "posture the winding method found, both seen by one camera.</p>\n";
    for (const planning::HumanGrasp& g : result.grasps) {
      const std::string name = g.name + "_winding";
      const fs::path run = dir / "frames" / name;
      html_ << "<p><b>" << HtmlEscape(g.name) << "</b><br>";
      const auto transfer = SortedPngs(run / "transfer", "transfer_");
      if (fs::exists(run / "transfer" / "side_by_side.png")) {
        html_ << "<img src=\"grasp/frames/" << name
              << "/transfer/side_by_side.png\" width=\"640\"><br>";
      } else if (!transfer.empty()) {
        html_ << "<img src=\"grasp/frames/" << name << "/transfer/"
              << transfer.back().filename().string() << "\" width=\"320\"><br>";
      }
      if (fs::exists(run / "stability" / "contact_sheet.png")) {
        html_ << "<img src=\"grasp/frames/" << name
              << "/stability/contact_sheet.png\" width=\"640\">";
      }
      html_ << "</p>\n";
    }
    return kExitOk;
  }

  int Viewer() {
    const fs::path script = out_ / "viewer_script.txt";
    base::WriteFileAtomic(
        script.string(),
        "# The viewer after Plan (on its worker thread; wait until it is done), at the\n"
        "# end of the AICO trajectory (seek takes seconds: the plan lasts 2 s).\n"
        "click Plan\nwait\nseek 2\nframes 2\n");
    const int rc = Sub({"view", "unwrap", "--script", script.string(), "--screenshot",
                        (out_ / "viewer.png").string()});
    html_ << "<h2>6. Interactive viewer</h2>\n"
             "<p><code>topoplan view unwrap</code> opens this window (GLFW + Dear ImGui); the "
             "image is its headless twin after clicking Plan, rendered by the same code.</p>\n"
             "<p><a href=\"viewer.png\"><img src=\"viewer.png\" width=\"960\"></a></p>\n";
    return rc;
  }

  void WriteIndex() {
    std::ostringstream page;
    page << "<!doctype html><html><head><meta charset=\"utf-8\"><title>topoplan demo</title>"
            "<style>body{font-family:sans-serif;max-width:64em;margin:2em auto;color:#222}"
            "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;"
            "padding:.3em .6em;text-align:left}img,video{border:1px solid #eee}</style>"
            "</head><body><h1>topoplan demo</h1>\n<p>Topology-based motion planning and grasp "
            "transfer after Zarubin's thesis. Every figure below was produced by "
            "<code>topoplan demo</code>; click a figure for the full image.</p>\n"
         << DemoProvenanceHtml() << "<ul>";
    for (const auto& [title, rc] : stage_status_) {
      page << "<li>" << HtmlEscape(title) << ": "
           << (rc == 0   ? "ok"
               : rc == 1 ? "task failed"
                         : "error")
           << "</li>";
    }
    page << "</ul>\n" << html_.str() << "</body></html>\n";
    base::WriteFileAtomic((out_ / "index.html").string(), page.str());
  }

  DemoArgs args_;
  fs::path out_;
  std::ostringstream html_;
  int stage_ = 0;
  int workers_ = 1;  // processes at a time (--jobs; 1: everything in this process)
  int worst_ = kExitOk;
  const StopCheck* stop_ = nullptr;
  bool stopped_ = false, stopped_timeout_ = false;
  std::vector<std::pair<std::string, int>> stage_status_;
};

}  // namespace

void AddDemoCommand(CLI::App* root, CommandList* commands) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* demo = root->add_subcommand(
      "demo", "Run the main job: every scenario, figure and table, with DIR/index.html");
  demo->add_option("-o,--output", args->out_dir, "output folder")->capture_default_str();
  AddDeprecatedAlias(demo, "--out", "--output", &args->out_dir);
  demo->add_flag("--full", args->full,
                 "the whole Fig. 4.5 sweep (0..1080 deg every 15 deg, 3 seeds)");
  demo->add_flag("--no-grasp", args->no_grasp, "skip the grasp-transfer stage");
  demo->add_flag("--all-frames", args->all_frames,
                 "frames of every grasp trial (all methods and the human hand) under "
                 "DIR/grasp/frames/; default: the winding method's, which the page shows");
  IntIn(demo->add_option("--jobs", args->jobs,
                         "stages run at the same time, each in its own process, and worker "
                         "processes of the grasp trials and of the Fig. 4.5 angles (default 0: "
                         "the number of cores; 1: everything one after the other in this "
                         "process); the outputs do not depend on it"),
        0, 64);
  demo->add_option("--only", args->only,
                   "run only these stages (comma-separated): writhe, unwrap, ring, bench, grasp, "
                   "viewer")
      ->delimiter(',')
      ->check(CLI::IsMember({"writhe", "unwrap", "ring", "bench", "grasp", "viewer"}));
  AddTimeoutFlag(demo, &args->timeout);
  AddFormatsFlag(demo, &args->formats);
  commands->push_back({demo, [args]() { return Demo(*args).Run(); }});
}

}  // namespace app
