// The `topoplan._core` extension module: NumPy bindings of the topology, planning and render
// libraries (the `topoplan` package re-exports it; see python/topoplan/__init__.py).
//
// Conventions: arrays are float64; a chain or point list is N×3 (one point per row); Jacobians
// are returned dense. Bad input raises ValueError naming the argument, a missing file
// FileNotFoundError, no GL context RuntimeError. Long calls (planning, rendering, grasp trials)
// release the GIL; a plan callback re-acquires it.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/assets.h"
#include "visualize/figures.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/motion/report.h"
#include "planning/physics/grasp_report.h"
#include "visualize/report_figures.h"
#include "planning/motion/robot_scene.h"
#include "visualize/scene_builder.h"
#include "visualize/scene_file.h"
#include "planning/collision/collision.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/robot/kinematics.h"
#include "planning/physics/grasp_trials.h"
#include "planning/motion/planner.h"
#include "planning/robot/robot.h"
#include "planning/robot/robot_io.h"
#include "planning/motion/scenario.h"
#include "planning/motion/unwrap_benchmark.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

[[noreturn]] void ThrowPy(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

[[noreturn]] void ThrowValue(const std::string& message) { ThrowPy(PyExc_ValueError, message); }

// f(), with a std::invalid_argument it throws raised as `type` "arg: <message>".
template <typename F>
auto Named(const std::string& arg, F f, PyObject* type = PyExc_ValueError) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    // The shared app code names its command-line flag or positional ("--grasp: ", "SCENARIO: "):
    // here the Python argument is named instead.
    std::string what = e.what();
    const size_t colon = what.find(": ");
    if (colon != std::string::npos &&
        (what.rfind("--", 0) == 0 || what.rfind("SCENARIO", 0) == 0) && what.find(' ') > colon) {
      what.erase(0, colon + 2);
    }
    ThrowPy(type, arg + ": " + what);
  }
}

// A float64 array from any array-like; ValueError naming `arg` when it is not numeric.
Array ToArray(const py::handle& obj, const std::string& arg) {
  Array a;
  try {
    a = py::cast<Array>(obj);
  } catch (const py::cast_error&) {
    ThrowValue(arg + ": expected an array of numbers");
  } catch (const py::error_already_set&) {
    ThrowValue(arg + ": expected an array of numbers");
  }
  if (!a) ThrowValue(arg + ": expected an array of numbers");
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a.data()[i])) ThrowValue(arg + ": non-finite value (NaN or Inf)");
  }
  return a;
}

// An N×3 point array as a 3×N Eigen matrix (N >= min_points).
Eigen::Matrix3Xd ToPoints(const py::handle& obj, const std::string& arg, int min_points = 2) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
      shape += (d ? ", " : "") + std::to_string(a.shape(d));
    ThrowValue(arg + ": expected shape (N, 3), got " + shape + (a.ndim() == 1 ? ",)" : ")"));
  }
  if (a.shape(0) < min_points) {
    ThrowValue(arg + ": needs at least " + std::to_string(min_points) + " points, got " +
               std::to_string(a.shape(0)));
  }
  Eigen::Matrix3Xd p(3, a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) p(k, i) = a.at(i, k);
  }
  return p;
}

// A vector of exactly `size` entries (size < 0: any).
Eigen::VectorXd ToVector(const py::handle& obj, const std::string& arg, int size) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 1 || (size >= 0 && a.shape(0) != size)) {
    ThrowValue(arg + ": expected shape (" + std::to_string(size) + ",), got " +
               std::to_string(a.size()) + " values in " + std::to_string(a.ndim()) + " dims");
  }
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

Eigen::MatrixXd ToMatrix(const py::handle& obj, const std::string& arg) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1) {
    ThrowValue(arg + ": expected a non-empty 2-D array");
  }
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = a.at(i, j);
  }
  return m;
}

// Points 3×N as an N×3 array.
Eigen::MatrixXd Rows(const Eigen::Matrix3Xd& p) { return p.transpose(); }

void RequireFile(const std::string& path, const std::string& arg) {
  if (!std::filesystem::is_regular_file(path)) {
    ThrowPy(PyExc_FileNotFoundError, arg + ": no such file: " + path);
  }
}

template <typename T>
std::vector<std::string> Names(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const T& item : items) names.push_back(item.name);
  return names;
}

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// An H×W×3 uint8 array of an RGBA image (alpha dropped; row 0 is the top row).
py::array_t<std::uint8_t> ImageArray(const render::Image& image) {
  py::array_t<std::uint8_t> out({image.height, image.width, 3});
  auto m = out.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) m(y, x, c) = image.rgba[(size_t(y) * image.width + x) * 4 + c];
    }
  }
  return out;
}

py::object JsonToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

std::pair<int, int> CheckSize(const std::pair<int, int>& size) {
  if (size.first < 16 || size.second < 16 || size.first > 8192 || size.second > 8192) {
    ThrowValue("size: width and height must be in [16, 8192]");
  }
  return size;
}

render::Image RenderScene(const render::Scene& scene, const render::Camera& camera, int width,
                          int height) {
  render::OffscreenContext context(render::GlBackend::kAuto);
  render::Renderer renderer(context.proc_loader());
  return renderer.Render(scene, camera, width, height, render::RenderOptions{});
}

// --- topology --------------------------------------------------------------------------------

// Largest dense Jacobian writhe_jacobian returns: (N_A−1)(N_B−1)(N_A+N_B)·3 doubles ≤ 2^27 (1 GiB).
constexpr double kMaxDenseJacobianEntries = double(1 << 27);

Eigen::MatrixXd WritheMatrixPy(const py::handle& a_obj, const py::handle& b_obj,
                               bool unsigned_variant) {
  topology::WritheOptions options;
  if (unsigned_variant) options.variant = topology::WritheVariant::kUnsignedSolidAngle;
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  py::gil_scoped_release release;  // O(N_A N_B); other Python threads run meanwhile
  return topology::WritheMatrix(a, b, options);
}

py::tuple WritheJacobianPy(const py::handle& a_obj, const py::handle& b_obj) {
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  const double entries =
      double(a.cols() - 1) * double(b.cols() - 1) * double(a.cols() + b.cols()) * 3.0;
  if (entries > kMaxDenseJacobianEntries) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "A, B: the dense Jacobians of %ld x %ld points would hold %.3g numbers "
                  "(%.3g GB), more than the limit of %.3g (1 GiB); use fewer points, or "
                  "writhe_matrix for W alone",
                  long(a.cols()), long(b.cols()), entries, entries * 8e-9,
                  kMaxDenseJacobianEntries);
    ThrowValue(msg);
  }
  Eigen::MatrixXd w;
  topology::WritheJacobian jac;
  {
    py::gil_scoped_release release;
    topology::WritheWorkspace ws;
    topology::WritheMatrixWithJacobian(a, b, {}, &w, &jac, &ws);
  }
  const py::ssize_t rows = jac.rows, cols = jac.cols, na = a.cols(), nb = b.cols();
  py::array_t<double> da({rows, cols, na, py::ssize_t(3)}), db({rows, cols, nb, py::ssize_t(3)});
  std::fill(da.mutable_data(), da.mutable_data() + da.size(), 0.0);
  std::fill(db.mutable_data(), db.mutable_data() + db.size(), 0.0);
  auto ma = da.mutable_unchecked<4>();
  auto mb = db.mutable_unchecked<4>();
  for (py::ssize_t i = 0; i < rows; ++i) {
    for (py::ssize_t j = 0; j < cols; ++j) {
      const auto col = jac.pair.col(i * cols + j);
      for (int k = 0; k < 3; ++k) {
        ma(i, j, i, k) = col(k);
        ma(i, j, i + 1, k) = col(3 + k);
        mb(i, j, j, k) = col(6 + k);
        mb(i, j, j + 1, k) = col(9 + k);
      }
    }
  }
  return py::make_tuple(w, da, db);
}

py::object WindingPy(const py::handle& chain, const py::handle& point, const py::handle& dir,
                     bool gradient, bool unsigned_variant) {
  topology::Axis axis;
  axis.point = ToVector(point, "axis_point", 3);
  axis.direction = ToVector(dir, "axis_dir", 3);
  if (axis.direction.norm() == 0.0) ThrowValue("axis_dir: must be non-zero");
  topology::WindingOptions options;
  if (unsigned_variant) options.variant = topology::WindingVariant::kUnsignedArccos;
  const Eigen::Matrix3Xd p = ToPoints(chain, "chain");
  if (!gradient) return py::float_(topology::WindingNumber(p, axis, options));
  Eigen::Matrix3Xd grad;
  const double w = topology::WindingNumber(p, axis, options, &grad);
  return py::make_tuple(w, Rows(grad));
}

// --- robots ----------------------------------------------------------------------------------

// A robot model with its kinematics workspace and placed collision objects.
struct PyRobot {
  planning::Robot robot;
  std::unique_ptr<planning::KinematicsData> kin;
  planning::Environment env;
  std::unique_ptr<planning::CollisionData> coll;  // built on first use, reset by add_object

  static PyRobot Load(const fs::path& urdf_path, const std::vector<fs::path>& package_path_list) {
    const std::string urdf = urdf_path.string();
    RequireFile(urdf, "urdf");
    std::vector<std::string> package_paths;
    for (const fs::path& p : package_path_list) package_paths.push_back(p.string());
    PyRobot r;
    planning::RobotLoadOptions options;
    options.package_paths = planning::PackagePaths(package_paths);
    r.robot = planning::LoadRobot(urdf, options);
    r.kin = std::make_unique<planning::KinematicsData>(r.robot);
    return r;
  }

  // q as an array in joint order or a dict {joint name: value} (other joints 0).
  Eigen::VectorXd Q(const py::handle& q) const {
    const int n = planning::num_dofs(robot);
    if (q.is_none()) return Eigen::VectorXd::Zero(n);
    if (py::isinstance<py::dict>(q)) {
      Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
      const std::vector<std::string> names = planning::DofNames(robot);
      for (const auto& [key, value] : py::cast<py::dict>(q)) {
        const std::string name = py::str(key);
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
          ThrowValue("q: unknown joint '" + name + "' (joints: " + Join(names) + ")");
        }
        double v = 0.0;
        try {
          v = py::cast<double>(value);
        } catch (const py::cast_error&) {
          ThrowValue("q: joint '" + name + "' is not a number");
        }
        if (!std::isfinite(v)) ThrowValue("q: joint '" + name + "' is not finite");
        out[it - names.begin()] = v;
      }
      return out;
    }
    return ToVector(q, "q", n);
  }

  int Link(const std::string& name) const {
    for (size_t i = 0; i < robot.links.size(); ++i) {
      if (robot.links[i].name == name) return static_cast<int>(i);
    }
    ThrowValue("link: unknown link '" + name + "' (links: " + Join(Names(robot.links)) + ")");
  }

  int Chain(const std::string& name) const {
    for (size_t i = 0; i < robot.chains.size(); ++i) {
      if (robot.chains[i].name == name) return static_cast<int>(i);
    }
    ThrowValue("chain: unknown chain '" + name + "' (chains: " + Join(Names(robot.chains)) + ")");
  }

  void Fk(const py::handle& q) { planning::ForwardKinematics(robot, Q(q), kin.get()); }

  planning::CollisionData* Coll() {
    if (!coll) coll = std::make_unique<planning::CollisionData>(robot, env);
    return coll.get();
  }
};

py::object FkPy(PyRobot& r, const py::handle& q, const std::optional<std::string>& link) {
  r.Fk(q);
  if (link) return py::cast(Eigen::Matrix4d(r.kin->world_from_link[r.Link(*link)].matrix()));
  py::dict out;
  for (size_t i = 0; i < r.robot.links.size(); ++i) {
    out[py::str(r.robot.links[i].name)] = Eigen::Matrix4d(r.kin->world_from_link[i].matrix());
  }
  return out;
}

// --- scenarios -------------------------------------------------------------------------------

struct PyScenario {
  std::unique_ptr<planning::Scenario> scenario;
};

// Thrown through RunPlanner when the Python callback returns False or raises.
struct CallbackStop {};

py::tuple PlanPy(PyScenario& s, const std::string& planner_name, unsigned seed,
                 const py::object& callback) {
  const planning::Planner planner =
      Named("planner", [&] { return planning::ParsePlanner(planner_name); });
  std::optional<py::error_already_set> callback_error;
  bool cancelled = false;
  int cancelled_sweep = -1;
  Eigen::MatrixXd cancelled_q;
  planning::AicoCallback cb;
  if (!callback.is_none()) {
    cb = [&](int sweep, double cost, bool, const planning::Trajectory& trajectory) {
      py::gil_scoped_acquire gil;
      try {
        const py::object r = callback(sweep, cost, Eigen::MatrixXd(trajectory.q.transpose()));
        // True / None go on, False cancels; anything else is a mistake, not a truth value.
        const std::string type = py::str(py::type::of(r).attr("__name__")).cast<std::string>();
        if (!r.is_none() && type != "bool" && type != "bool_") {  // bool_: NumPy's
          PyErr_SetString(PyExc_TypeError,
                          ("callback: must return True, False or None, got " + type).c_str());
          throw py::error_already_set();
        }
        if (!r.is_none() && !r.cast<bool>()) {
          cancelled = true;
          cancelled_sweep = sweep;
          cancelled_q = trajectory.q.transpose();
          throw CallbackStop{};
        }
      } catch (py::error_already_set& e) {
        callback_error.emplace(std::move(e));
        throw CallbackStop{};
      }
    };
  }
  planning::PlanResult result;
  try {
    py::gil_scoped_release release;
    result = planning::RunPlanner(*s.scenario, planner, seed, cb);
  } catch (const CallbackStop&) {
  }
  if (callback_error) throw *callback_error;
  if (cancelled) {
    py::object exc = py::module_::import("topoplan._core")
                         .attr("PlanCancelled")("plan: cancelled by the callback at sweep " +
                                                std::to_string(cancelled_sweep));
    exc.attr("sweep") = cancelled_sweep;
    exc.attr("trajectory") = cancelled_q;
    PyErr_SetObject(exc.get_type().ptr(), exc.ptr());
    throw py::error_already_set();
  }
  const nlohmann::json report = planning::PlanReportJson(*s.scenario, result.report, seed);
  return py::make_tuple(Eigen::MatrixXd(result.trajectory.q.transpose()), JsonToPython(report));
}

render::Image RenderScenario(const planning::Scenario& s, const Eigen::VectorXd& q, int width,
                             int height) {
  planning::KinematicsData kin(s.robot);
  planning::ForwardKinematics(s.robot, q, &kin);
  visualize::SceneMeshCache cache;
  const render::Scene scene = visualize::BuildRobotScene(s.robot, kin, s.objects, {}, &cache);
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
    Eigen::VectorXd qv = s.scenario->problem.q0;
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

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "topoplan: topology-based motion planning (writhe, winding numbers, AICO and RRT planners, "
      "grasp transfer, offscreen rendering).\n\n"
      "Arrays are float64 NumPy arrays; chains and point lists are N x 3 (one point per row).\n"
      "Bad input raises ValueError naming the argument, missing files FileNotFoundError, and a\n"
      "missing GL context RuntimeError.";

  // Not "EnvironmentError": that is Python's built-in alias of OSError, which `from topoplan
  // import *` would shadow.
  py::register_exception<render::EnvironmentError>(m, "GLError", PyExc_RuntimeError)
      .attr("__doc__") =
      "No usable GL context (OSMesa or EGL could not start): raised by render, heatmap and\n"
      "the figure functions. A RuntimeError.";
  static py::exception<CallbackStop> plan_cancelled(m, "PlanCancelled", PyExc_RuntimeError);
  plan_cancelled.doc() =
      "Raised by Scenario.plan when its callback returned False; has .sweep (the sweep index) and "
      ".trajectory (the (T+1) x n trajectory at that sweep).";

  // topology
  m.def("writhe_matrix", &WritheMatrixPy, py::arg("A"), py::arg("B"), py::arg("unsigned") = false,
        "Writhe matrix of chains A (N_A x 3) and B (N_B x 3): W[i, j] = Gauss linking integral of\n"
        "segment i of A with segment j of B, shape (N_A-1, N_B-1). Its sum over two closed\n"
        "polygons is their linking number. unsigned=True gives |solid angle| in [0, 2 pi)\n"
        "(no 1/(4 pi)).");
  m.def(
      "writhe_jacobian", &WritheJacobianPy, py::arg("A"), py::arg("B"),
      "(W, dW_dA, dW_dB): the signed writhe matrix and its derivatives with respect to every\n"
      "chain point, dW_dA of shape (N_A-1, N_B-1, N_A, 3), dW_dB of shape (N_A-1, N_B-1, N_B, 3)\n"
      "(dW_dA[i, j, p, k] = dW[i, j]/dA[p, k]; nonzero only for p in {i, i+1}). The arrays are\n"
      "dense: sizes whose two Jacobians would exceed 2^27 numbers (1 GiB) raise ValueError.");
  m.def("winding", &WindingPy, py::arg("chain"), py::arg("axis_point"), py::arg("axis_dir"),
        py::arg("gradient") = false, py::arg("unsigned") = false,
        "Winding number (turns) of chain (N x 3) about the oriented axis through axis_point along\n"
        "axis_dir (right-hand rule). gradient=True returns (w, dw_dchain) with dw_dchain N x 3.\n"
        "unsigned=True uses the arccos variant of Ivan et al. (2013).");

  // robots
  py::class_<PyRobot>(m, "Robot",
                      "A robot model loaded from a URDF, with placed collision objects. q is an\n"
                      "array in joint_names order or a dict {joint name: value} (others 0).")
      .def_static("load", &PyRobot::Load, py::arg("urdf"),
                  py::arg("package_paths") = std::vector<fs::path>{},
                  "Loads a URDF (meshes through assimp; package:// URIs resolved against\n"
                  "package_paths, $ROS_PACKAGE_PATH and the URDF's ancestors; chains from the\n"
                  "<stem>.chains.json sidecar). FileNotFoundError for a missing file, ValueError\n"
                  "for a bad one.")
      .def_property_readonly(
          "name", [](const PyRobot& r) { return r.robot.name; }, "Robot name from the URDF.")
      .def_property_readonly(
          "joint_names", [](const PyRobot& r) { return planning::DofNames(r.robot); },
          "Names of the joints driven by q, in q order.")
      .def_property_readonly(
          "link_names", [](const PyRobot& r) { return Names(r.robot.links); }, "Link names.")
      .def_property_readonly(
          "chain_names", [](const PyRobot& r) { return Names(r.robot.chains); },
          "Names of the robot's chains (sidecar file).")
      .def_property_readonly(
          "limits",
          [](const PyRobot& r) {
            return py::make_tuple(planning::LowerLimits(r.robot), planning::UpperLimits(r.robot));
          },
          "(lower, upper): joint limits in q order (+-inf for continuous joints).")
      .def("fk", &FkPy, py::arg("q"), py::arg("link") = py::none(),
           "Forward kinematics: {link name: 4x4 world_from_link}, or one 4x4 when link is given.")
      .def(
          "point_jacobian",
          [](PyRobot& r, const py::handle& q, const std::string& link, const py::handle& point) {
            const Eigen::Vector3d p = ToVector(point, "point", 3);
            const int l = r.Link(link);
            r.Fk(q);
            Eigen::MatrixXd J(3, planning::num_dofs(r.robot));
            planning::PointJacobian(r.robot, *r.kin, l, p, J);
            return J;
          },
          py::arg("q"), py::arg("link"), py::arg("point") = std::vector<double>{0, 0, 0},
          "3 x n Jacobian d p_world / d q of a point fixed in link's frame (world frame).")
      .def(
          "frame_jacobian",
          [](PyRobot& r, const py::handle& q, const std::string& link) {
            const int l = r.Link(link);
            r.Fk(q);
            Eigen::MatrixXd J(6, planning::num_dofs(r.robot));
            planning::FrameJacobian(r.robot, *r.kin, l, J);
            return J;
          },
          py::arg("q"), py::arg("link"),
          "6 x n geometric Jacobian of link's frame: rows 0-2 linear velocity of its origin,\n"
          "rows 3-5 angular velocity (world frame), per unit qdot.")
      .def(
          "chain_points",
          [](PyRobot& r, const py::handle& q, const std::string& chain) {
            const int c = r.Chain(chain);
            r.Fk(q);
            Eigen::Matrix3Xd P;
            planning::ChainPoints(r.robot, *r.kin, c, &P);
            return Rows(P);
          },
          py::arg("q"), py::arg("chain"),
          "World positions (N x 3) of the chain's points at q (closed chains repeat point 0).")
      .def(
          "chain_jacobian",
          [](PyRobot& r, const py::handle& q, const std::string& chain) {
            const int c = r.Chain(chain);
            r.Fk(q);
            Eigen::MatrixXd J(3 * planning::ChainSize(r.robot, c), planning::num_dofs(r.robot));
            planning::ChainJacobian(r.robot, *r.kin, c, J);
            return J;
          },
          py::arg("q"), py::arg("chain"),
          "(3N) x n Jacobian of the chain points: rows 3k..3k+2 = d p_k / d q.")
      .def(
          "add_object",
          [](PyRobot& r, const fs::path& urdf_path, const py::handle& position,
             const py::handle& rpy, const std::string& name) {
            const std::string urdf = urdf_path.string();
            RequireFile(urdf, "urdf");
            const Eigen::Vector3d xyz = ToVector(position, "position", 3);
            const Eigen::Vector3d e = ToVector(rpy, "rpy", 3);
            planning::Robot object = planning::LoadRobot(urdf);
            const Eigen::Isometry3d T = planning::PoseFromXyzRpy(xyz, e);
            r.coll.reset();
            planning::AddObject(object, T, name.empty() ? object.name : name, &r.env);
          },
          py::arg("urdf"), py::arg("position") = std::vector<double>{0, 0, 0},
          py::arg("rpy") = std::vector<double>{0, 0, 0}, py::arg("name") = "",
          "Places a static object (URDF) at position with roll/pitch/yaw rpy (radians, fixed\n"
          "axes x then y then z) for the collision checks.")
      .def(
          "in_collision",
          [](PyRobot& r, const py::handle& q) {
            r.Fk(q);
            return planning::InCollision(r.robot, *r.kin, r.Coll());
          },
          py::arg("q"), "True when the robot at q collides with a placed object or itself.")
      .def(
          "min_distance",
          [](PyRobot& r, const py::handle& q) {
            r.Fk(q);
            return planning::MinDistance(r.robot, *r.kin, r.Coll());
          },
          py::arg("q"),
          "Minimum signed distance [m] over the checked pairs (negative: penetration; inf when\n"
          "nothing is checked).")
      .def(
          "distances",
          [](PyRobot& r, const py::handle& q, double margin) {
            if (!(margin >= 0.0)) ThrowValue("margin: must be >= 0");
            r.Fk(q);
            std::vector<planning::ProximityPair> pairs;
            planning::ComputeProximity(r.robot, *r.kin, margin, r.Coll(), &pairs);
            py::list out;
            for (const auto& p : pairs) {
              py::dict d;
              d["link_a"] = r.robot.links[p.link_a].name;
              d["other"] =
                  p.object >= 0 ? r.env.objects[p.object].name : r.robot.links[p.link_b].name;
              d["is_object"] = p.object >= 0;
              d["distance"] = p.distance;
              d["point_a"] = p.point_a;
              d["point_b"] = p.point_b;
              d["normal"] = p.normal;
              out.append(d);
            }
            return out;
          },
          py::arg("q"), py::arg("margin") = 0.1,
          "Every checked pair closer than margin [m]: list of dicts with link_a, other (link or\n"
          "object name), is_object, distance, point_a, point_b, normal (world frame).");

  // scenarios
  py::class_<PyScenario>(m, "Scenario", "A set-up planning scenario (see load_scenario).")
      .def_property_readonly(
          "name", [](const PyScenario& s) { return s.scenario->name; }, "Scenario name.")
      .def_property_readonly(
          "joint_names", [](const PyScenario& s) { return planning::DofNames(s.scenario->robot); },
          "Joint names in q order.")
      .def_property_readonly(
          "q0", [](const PyScenario& s) { return Eigen::VectorXd(s.scenario->problem.q0); },
          "Start configuration.")
      .def_property_readonly(
          "goal_q", [](const PyScenario& s) { return Eigen::VectorXd(s.scenario->goal_q); },
          "Final-pose estimate (the RRT goal).")
      .def_property_readonly(
          "start_wrap_deg", [](const PyScenario& s) { return s.scenario->start_wrap_deg; },
          "360 deg x |writhe| of the report pair at q0.")
      .def(
          "resolved_poses",
          [](const PyScenario& s) {
            const planning::ResolvedPoses r = planning::ResolvedPosesOf(*s.scenario);
            py::dict d;
            d["q0"] = r.q0;
            d["unwinding"] = r.unwinding;
            d["goal_q"] = r.goal_q;
            return d;
          },
          "The expensive part of the set-up: dict with 'q0' (n,), 'unwinding' (n x (T+1), or\n"
          "0 x 0) and 'goal_q' (n,). load_scenario(..., resolved=d) with the same file and moves\n"
          "skips the start-coil continuation and the final-pose estimate and sets up an equal\n"
          "scenario (plans are bit-identical); picklable, so one process can set up for many.")
      .def(
          "writhe_total",
          [](const PyScenario& s, const py::handle& q) {
            return planning::ReportWritheTotal(
                *s.scenario, ToVector(q, "q", planning::num_dofs(s.scenario->robot)));
          },
          py::arg("q"), "Total writhe of the scenario's report pair (robot chain x object) at q.")
      .def(
          "plan", &PlanPy, py::arg("planner") = "aico", py::arg("seed") = 0,
          py::arg("callback") = py::none(),
          "Runs a planner (aico, rrt, birrt, and ompl-* when built with OMPL) and returns\n"
          "(trajectory, report): trajectory (T+1) x n (RRT: waypoints; empty on failure), report\n"
          "a dict with the keys of `topoplan plan`'s report.json. For AICO, callback(sweep, cost,\n"
          "trajectory) is called after every sweep and returns True or None (go on) or False\n"
          "(cancel: PlanCancelled is raised); any other return value is a TypeError, and an\n"
          "exception in the callback ends the plan and propagates. The GIL is released while\n"
          "planning.");
  m.def(
      "load_scenario",
      [](const fs::path& arg_path, std::optional<double> start_wrap, long rrt_budget,
         const std::map<std::string, py::object>& move_objects, const py::object& resolved,
         std::optional<bool> stop_when_solved) {
        const std::string arg = arg_path.string();
        if (start_wrap && !std::isfinite(*start_wrap)) ThrowValue("start_wrap: must be finite");
        if (start_wrap && !(*start_wrap >= 0.0 && *start_wrap <= 2000.0)) {
          ThrowValue("start_wrap: must be in [0, 2000] degrees");
        }
        const std::string path = Named(
            "path_or_name", [&] { return base::ResolveScenarioPath(arg); }, PyExc_FileNotFoundError);
        planning::ScenarioOverrides overrides;
        overrides.start_wrap_deg = start_wrap;
        overrides.search_roots = {base::AssetRoot()};
        std::map<std::string, Eigen::Vector3d> offsets;
        for (const auto& [name, xyz] : move_objects) {
          offsets[name] = ToVector(xyz, "move_objects['" + name + "']", 3);
        }
        planning::ScenarioSpec spec = planning::ParseScenarioSpec(path, overrides.search_roots);
        for (const auto& [name, offset] : offsets) {
          auto it = std::find_if(spec.objects.begin(), spec.objects.end(),
                                 [&](const auto& o) { return o.name == name; });
          if (it == spec.objects.end()) {
            ThrowValue("move_objects: the scenario has no object '" + name + "'");
          }
          it->xyz += offset;
        }
        std::optional<planning::ResolvedPoses> given;
        if (!resolved.is_none()) {
          if (!py::isinstance<py::dict>(resolved)) {
            ThrowValue("resolved: expected a dict from Scenario.resolved_poses()");
          }
          const py::dict d = resolved.cast<py::dict>();
          for (const char* key : {"q0", "unwinding", "goal_q"}) {
            if (!d.contains(key)) ThrowValue(std::string("resolved: no key '") + key + "'");
          }
          given.emplace();
          given->q0 = ToVector(d["q0"], "resolved['q0']", -1);
          given->goal_q = ToVector(d["goal_q"], "resolved['goal_q']", -1);
          const Array u = ToArray(d["unwinding"], "resolved['unwinding']");
          if (u.ndim() != 2) ThrowValue("resolved['unwinding']: expected a 2-D array");
          if (u.size() > 0) given->unwinding = ToMatrix(d["unwinding"], "resolved['unwinding']");
        }
        PyScenario s;
        {
          py::gil_scoped_release release;
          // Bad resolved poses throw std::invalid_argument "resolved: ..." (a ValueError).
          s.scenario =
              planning::SetUpScenario(std::move(spec), start_wrap, given ? &*given : nullptr);
        }
        if (rrt_budget > 0) s.scenario->rrt.max_checks = rrt_budget;
        if (stop_when_solved) s.scenario->stop_when_solved = *stop_when_solved;
        return s;
      },
      py::arg("path_or_name"), py::arg("start_wrap") = py::none(), py::arg("rrt_budget") = -1,
      py::arg("move_objects") = std::map<std::string, py::object>{},
      py::arg("resolved") = py::none(), py::arg("stop_when_solved") = py::none(),
      "Loads a scenario file, or a name in the shipped assets/scenarios (e.g. 'unwrap'), and\n"
      "sets it up (start coil, final-pose estimate). start_wrap overrides the coil's angle to\n"
      "unwrap [deg]; rrt_budget > 0 replaces the RRTs' collision-check budget; move_objects\n"
      "{name: (3,) offset [m]} moves objects of the scenario before it is set up; resolved (a\n"
      "dict from Scenario.resolved_poses() of the same set-up) skips the expensive part;\n"
      "stop_when_solved (bool) replaces the scenario's aico.stop_when_solved (True: AICO stops at\n"
      "the first accepted sweep whose trajectory meets the success criteria, status 'solved').");
  m.def(
      "unwrap_perturbation",
      [](const fs::path& arg_path, int seeds, double perturb) {
        const std::string path = Named(
            "path_or_name", [&] { return base::ResolveScenarioPath(arg_path.string()); },
            PyExc_FileNotFoundError);
        if (seeds < 1) ThrowValue("seeds: must be >= 1");
        if (!(perturb >= 0.0) || !std::isfinite(perturb)) ThrowValue("perturb: must be >= 0");
        planning::UnwrapPerturbation p;
        {
          py::gil_scoped_release release;
          const planning::ScenarioSpec spec = planning::ParseScenarioSpec(path, {base::AssetRoot()});
          p = planning::MakeUnwrapPerturbation(spec, 0.0, seeds, perturb);
        }
        Eigen::MatrixXd offsets(seeds, 3);
        for (int s = 0; s < seeds; ++s) offsets.row(s) = p.offsets[s].transpose();
        py::dict d;
        d["object"] = p.object_name;
        d["offsets"] = offsets;
        return d;
      },
      py::arg("path_or_name"), py::arg("seeds"), py::arg("perturb"),
      "The pole perturbation of `topoplan bench unwrap --perturb M --seeds N`: dict with\n"
      "'object' (the moved object's name, '' when perturb is 0) and 'offsets' (N x 3 world-frame\n"
      "offsets [m], row s for seed s; at most perturb from the pole's line). Pass\n"
      "move_objects={object: offsets[s]} to load_scenario for seed s's set-up.");

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
        const auto image = py::array_t<std::uint8_t>::ensure(any);
        if (image.ndim() != 3 || image.shape(2) != 3) ThrowValue("image: expected shape (H, W, 3)");
        const fs::path parent = fs::path(path).parent_path();
        if (!parent.empty() && !fs::is_directory(parent)) {
          ThrowPy(PyExc_FileNotFoundError, "path: no folder " + parent.string());
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
  m.def(
      "grasp_transfer",
      [](const fs::path& grasp_path, const std::string& method, double mu, int perturb,
         std::uint32_t seed, double close_by) {
        const std::string grasp = grasp_path.string();
        if (!(mu >= 0.0) || !std::isfinite(mu)) ThrowValue("mu: must be finite and >= 0");
        if (!(close_by >= 0.0 && close_by <= planning::physics::GraspTrialsOptions::kMaxCloseBy))
          ThrowValue("close_by: must be in [0, 0.5] rad");
        if (perturb < 0 || perturb > 1000) ThrowValue("perturb: must be in 0..1000");
        const planning::TransferMethod tm =
            Named("method", [&] { return planning::ParseTransferMethod(method); });
        const std::vector<std::string> files = Named(
            "grasp", [&] { return planning::SelectGraspFiles(grasp); }, PyExc_FileNotFoundError);
        if (files.size() != 1) ThrowValue("grasp: name one grasp (a name or a file), not 'all'");
        nlohmann::json report;
        {
          py::gil_scoped_release release;
          // ODE is initialised once per process (OdeRuntime allows one instance at a time): calls
          // from several Python threads (a multi-threaded Dask worker) take turns here.
          static std::mutex ode_mutex;
          const std::lock_guard<std::mutex> lock(ode_mutex);
          const planning::GraspInputs in = planning::LoadGraspInputs(files);
          const planning::physics::OdeRuntime ode;
          planning::physics::GraspTrialsOptions options;
          options.mu = mu;
          options.perturb = perturb;
          options.seed = seed;
          options.close_by = close_by;
          const auto result = planning::physics::RunGraspTrials(
              ode, in.human, in.lwr_sdh, in.objects, in.grasps, {tm}, options);
          report = planning::physics::GraspReportJson(result);
        }
        return JsonToPython(report["grasps"][0]);
      },
      py::arg("grasp"), py::arg("method") = "winding", py::arg("mu") = 1.0, py::arg("perturb") = 0,
      py::arg("seed") = 0, py::arg("close_by") = planning::physics::HandBuildOptions{}.close_by,
      "Transfers one human grasp (a name in assets/grasps or a file) to the SDH with method\n"
      "(winding, winding_only, contact_only, fingertip, joint, human), tests it in ODE with\n"
      "friction mu and returns its entry of `topoplan grasp transfer`'s report.json. perturb = N\n"
      "> 0 repeats the test N times with the object moved (<= 5 mm) and turned (<= 5 deg), seeded\n"
      "by seed as `grasp transfer --perturb N --seed S` (methods[...]['perturbed']). close_by:\n"
      "the grip, flexion set-points this many rad past the grasp (`--close-by`, in [0, 0.5]).\n"
      "Releases the GIL; concurrent calls from several threads run one after another (ODE is\n"
      "initialised once per process).");
  m.def(
      "available_grasps",
      [] {
        std::vector<std::string> names;
        for (const std::string& f : planning::SelectGraspFiles("all")) {
          names.push_back(fs::path(f).stem().string());
        }
        return names;
      },
      "Names of the shipped human grasps (assets/grasps/*.json except objects.json), sorted.");
  m.def(
      "transfer_methods",
      [] {
        std::vector<std::string> names;
        for (planning::TransferMethod t : planning::AllTransferMethods()) {
          names.emplace_back(planning::ToString(t));
        }
        return names;
      },
      "The six grasp transfer methods in report order (`grasp transfer --method all`).");
  m.def(
      "wilson_interval",
      [](int successes, int trials) {
        if (trials < 1 || successes < 0 || successes > trials) {
          ThrowValue("successes, trials: need 0 <= successes <= trials, trials >= 1");
        }
        const Eigen::Vector2d ci = planning::WilsonInterval(successes, trials);
        return std::pair<double, double>{ci[0], ci[1]};
      },
      py::arg("successes"), py::arg("trials"),
      "Wilson score 95 % interval (lo, hi) of a success rate successes / trials (Wilson 1927).");
  m.def(
      "available_planners",
      [] {
        std::vector<std::string> names;
        for (planning::Planner p : planning::AvailablePlanners()) {
          names.emplace_back(planning::PlannerName(p));
        }
        return names;
      },
      "Names of the planners of this build (aico, rrt, birrt, and ompl-* with OMPL).");
  m.def("asset_root", &base::AssetRoot,
        "Root of the asset tree ($TOPOPLAN_ASSETS, else the installed or source assets/).");
}
