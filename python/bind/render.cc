// The render layer in Python: offscreen renders of scene files, robots and scenarios (through
// visualize/), PNG I/O, writhe heatmaps and the unwrap benchmark's figure.
#include "base/file_write.h"
#include "python/bind/planning_types.h"

#include "planning/motion/unwrap_benchmark.h"
#include "visualize/figures.h"
#include "visualize/report_figures.h"
#include "visualize/scene_builder.h"
#include "visualize/scene_file.h"

namespace topoplan_py {
namespace {

render::Image RenderScenario(const planning::Scenario& s, const Eigen::VectorXd& q, int width,
                             int height) {
  planning::KinematicsData kin(s.robot);
  planning::ForwardKinematics(s.robot, q, &kin);
  visualize::SceneMeshCache cache;
  const render::Scene scene = visualize::BuildRobotScene(s.robot, kin, s.initial.objects, {}, &cache);
  return RenderScene(scene, visualize::FrameSceneCamera(scene), width, height);
}

py::array_t<std::uint8_t> RenderPy(const py::handle& what, const py::handle& q,
                                   std::pair<int, int> size) {
  CheckSize(size);
  const auto [width, height] = size;
  render::Image image;
  if (py::isinstance<PyScenario>(what)) {
    PyScenario& s = py::cast<PyScenario&>(what);
    const planning::Robot& robot = s.scenario->robot;
    Eigen::VectorXd qv = s.scenario->initial.problem.q0;
    if (!q.is_none()) {
      qv = ToVector(q, "q", planning::num_dofs(robot));
    }
    py::gil_scoped_release release;
    image = RenderScenario(*s.scenario, qv, width, height);
  } else if (py::isinstance<PyRobot>(what)) {
    PyRobot& r = py::cast<PyRobot&>(what);
    const Eigen::VectorXd qv = r.Q(q);
    py::gil_scoped_release release;
    planning::KinematicsData kin(r.robot);
    planning::ForwardKinematics(r.robot, qv, &kin);
    visualize::SceneMeshCache cache;
    const render::Scene scene = visualize::BuildRobotScene(r.robot, kin, r.env, {}, &cache);
    image = RenderScene(scene, visualize::FrameSceneCamera(scene), width, height);
  } else if (py::isinstance<py::str>(what) || py::hasattr(what, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(what));
    RequireFile(path, "scene");
    if (!planning::IsRobotSceneFile(path)) {
      // A plain scene file (shapes, camera, lights: `topoplan render SCENE.json`).
      if (fs::path(path).extension() != ".json") {
        ThrowValue("scene: " + path + " is not a robot .urdf, a scenario .json or a scene .json");
      }
      if (!q.is_none()) ThrowValue("q: only for a robot .urdf or a scenario");
      const visualize::SceneDocument doc = Named("scene", [&] { return visualize::LoadSceneFile(path); });
      {
        py::gil_scoped_release release;
        image = RenderScene(doc.scene, doc.camera, width, height);
      }
      return ImageArray(image);
    }
    std::string q_text;
    if (!q.is_none()) {
      const Eigen::VectorXd qv = ToVector(q, "q", -1);
      char buf[32];
      for (Eigen::Index i = 0; i < qv.size(); ++i) {
        std::snprintf(buf, sizeof(buf), "%.17g", qv[i]);
        q_text += (i ? "," : "") + std::string(buf);
      }
    }
    py::gil_scoped_release release;
    visualize::SceneDocument doc;
    try {
      doc = visualize::RobotSceneDocument(path, q_text);
    } catch (const std::invalid_argument& e) {
      // The shared code names the CLI's --q; here the argument is q.
      std::string what = e.what();
      if (what.rfind("--q", 0) == 0) what.erase(0, 2);
      py::gil_scoped_acquire gil;
      ThrowValue(what.rfind("q", 0) == 0 ? what : "scene: " + what);
    }
    image = RenderScene(doc.scene, doc.camera, width, height);
  } else {
    ThrowValue("scene: expected a path, a Scenario or a Robot");
  }
  return ImageArray(image);
}

// --- unwrap benchmark ------------------------------------------------------------------------

// Rebuilds an UnwrapBenchmarkResult from run rows (dicts with angle_deg, planner, seed, success,
// collision_checks[, time_s]) so that the figure is drawn by the same code as `bench unwrap`.
planning::UnwrapBenchmarkResult UnwrapResultFromRows(const py::list& rows,
                                                     const std::vector<double>& angles,
                                                     const std::vector<std::string>& planners,
                                                     int seeds) {
  planning::UnwrapBenchmarkResult result;
  result.angles_deg = angles;
  for (const std::string& p : planners) result.planners.push_back(planning::ParsePlanner(p));
  result.seeds = seeds;
  std::map<std::tuple<double, int, int>, planning::UnwrapRun> by_key;
  for (const py::handle& row_obj : rows) {
    const py::dict row = py::cast<py::dict>(row_obj);
    planning::UnwrapRun run;
    run.angle_deg = py::cast<double>(row["angle_deg"]);
    run.planner = planning::ParsePlanner(py::cast<std::string>(row["planner"]));
    run.seed = py::cast<int>(row["seed"]);
    run.report.planner = planning::PlannerName(run.planner);
    run.report.success = py::cast<int>(row["success"]) != 0;
    run.report.collision_checks = py::cast<long>(row["collision_checks"]);
    if (row.contains("narrow_phase_calls")) {
      run.report.narrow_phase_calls = py::cast<long>(row["narrow_phase_calls"]);
    }
    if (row.contains("time_s")) run.report.time_s = py::cast<double>(row["time_s"]);
    by_key[{run.angle_deg, static_cast<int>(run.planner), run.seed}] = run;
  }
  for (double a : result.angles_deg) {
    for (planning::Planner p : result.planners) {
      for (int s = 0; s < seeds; ++s) {
        const auto it = by_key.find({a, static_cast<int>(p), s});
        if (it == by_key.end()) {
          ThrowValue("rows: no run for angle " + std::to_string(a) + ", planner " +
                     planning::PlannerName(p) + ", seed " + std::to_string(s));
        }
        result.runs.push_back(it->second);
      }
    }
  }
  result.summary = planning::SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  return result;
}

}  // namespace

void BindRender(py::module_& m) {
  // images
  m.def(
      "render", &RenderPy, py::arg("scene"), py::arg("q") = py::none(),
      py::arg("size") = std::pair<int, int>{640, 480},
      "Renders offscreen (OSMesa/EGL; $TOPOPLAN_GL) to an H x W x 3 uint8 array. scene is a\n"
      "path (robot .urdf, scene or scenario .json: the same image as `topoplan render --size`),\n"
      "a Scenario (at q, default q0) or a Robot (at q with its objects). RuntimeError without GL.");
  m.def(
      "heatmap",
      [](const py::handle& w, const std::string& a_name, const std::string& b_name,
         std::pair<int, int> size, const std::string& title, bool signed_values) {
        CheckSize(size);
        const Eigen::MatrixXd W = ToMatrix(w, "W");
        return ImageArray(visualize::WritheHeatmapFigure(W, a_name, b_name, size.first, size.second,
                                                   title, signed_values));
      },
      py::arg("W"), py::arg("a_name") = "A", py::arg("b_name") = "B",
      py::arg("size") = std::pair<int, int>{640, 480}, py::arg("title") = "",
      py::arg("signed") = true,
      "Writhe-matrix heatmap figure (the one of `topoplan heatmap`) as an H x W x 3 uint8 array.");
  m.def(
      "read_png",
      [](const fs::path& file) {
        const std::string path = file.string();
        RequireFile(path, "path");
        return ImageArray(render::ReadPng(path));
      },
      py::arg("path"), "Reads a PNG into an H x W x 3 uint8 array.");
  m.def(
      "write_png",
      [](const fs::path& file, const py::array& any) {
        const std::string path = file.string();
        // uint8 only: a silent cast would wrap 300 to 44 and truncate 0.9 to 0.
        if (!any.dtype().is(py::dtype::of<std::uint8_t>())) {
          ThrowValue("image: expected dtype uint8, got " +
                     py::str(any.dtype()).cast<std::string>());
        }
        if (any.ndim() != 3 || any.shape(2) != 3) ThrowValue("image: expected shape (H, W, 3)");
        // The size before any copy or allocation (a broadcast view can claim 2^32 rows).
        if (any.shape(0) < 1 || any.shape(1) < 1 || any.shape(0) > 16384 ||
            any.shape(1) > 16384 || any.shape(0) * any.shape(1) > render::kMaxImagePixels) {
          ThrowValue("image: " + std::to_string(any.shape(0)) + " x " +
                     std::to_string(any.shape(1)) + " pixels, sides must be in [1, 16384] and " +
                     "the area at most " + std::to_string(render::kMaxImagePixels) + " pixels");
        }
        const auto image = py::array_t<std::uint8_t>::ensure(any);
        const fs::path parent = fs::path(path).parent_path();
        if (!parent.empty() && !fs::is_directory(parent)) {
          ThrowPy(PyExc_FileNotFoundError, "path: no folder " + parent.string());
        }
        try {
          base::CheckOutputFile(path, "path");  // never a device, pipe or symlink elsewhere
        } catch (const std::invalid_argument& e) {
          ThrowValue(e.what());
        }
        render::Image out(static_cast<int>(image.shape(1)), static_cast<int>(image.shape(0)));
        const auto v = image.unchecked<3>();
        for (py::ssize_t y = 0; y < image.shape(0); ++y) {
          for (py::ssize_t x = 0; x < image.shape(1); ++x) {
            for (int c = 0; c < 3; ++c) out.rgba[(y * image.shape(1) + x) * 4 + c] = v(y, x, c);
          }
        }
        render::WritePng(path, out);
      },
      py::arg("path"), py::arg("image"),
      "Writes an H x W x 3 uint8 array as a PNG (ValueError for another dtype or shape;\n"
      "FileNotFoundError when the folder does not exist).");

  // experiments
  m.def(
      "unwrap_figure",
      [](const py::list& rows, const std::vector<double>& angles,
         const std::vector<std::string>& planners, int seeds) -> py::object {
        if (seeds < 1) ThrowValue("seeds: must be >= 1");
        const auto result = UnwrapResultFromRows(rows, angles, planners, seeds);
        const auto figure = visualize::UnwrapFigure(result);
        if (!figure) return py::none();
        return ImageArray(figure->Raster());
      },
      py::arg("rows"), py::arg("angles"), py::arg("planners"), py::arg("seeds"),
      "The figure of `topoplan bench unwrap` (three panels over the angle: collision checks,\n"
      "narrow-phase calls, wall time; median and interquartile band) from run rows (dicts with\n"
      "angle_deg, planner, seed, success, collision_checks, narrow_phase_calls, time_s), one per\n"
      "(angle, planner, seed); None when there is nothing to draw.");
}

}  // namespace topoplan_py
