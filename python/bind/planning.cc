// The planning layer in Python: robots (forward kinematics, Jacobians, chains, collision),
// scenarios and their planners, grasp transfer with the ODE stability test.
#include "base/assets.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/motion/planner.h"
#include "planning/motion/report.h"
#include "planning/physics/grasp_report.h"
#include "planning/physics/grasp_trials.h"
#include "planning/robot/ik.h"
#include "python/bind/planning_types.h"

namespace topoplan_py {
namespace {

py::object FkPy(PyRobot& r, const py::handle& q, const std::optional<std::string>& link) {
  r.Fk(q);
  if (link) return py::cast(Eigen::Matrix4d(r.kin->world_from_link[r.Link(*link)].matrix()));
  py::dict out;
  for (size_t i = 0; i < r.robot.links.size(); ++i) {
    out[py::str(r.robot.links[i].name)] = Eigen::Matrix4d(r.kin->world_from_link[i].matrix());
  }
  return out;
}

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

// Robot.distances: every checked pair closer than margin as a list of dicts.
py::list DistancesPy(PyRobot& r, const py::handle& q, double margin) {
  if (!(margin >= 0.0)) ThrowValue("margin: must be >= 0");
  r.Fk(q);
  std::vector<planning::ProximityPair> pairs;
  planning::ComputeProximity(r.robot, *r.kin, margin, r.Coll(), &pairs);
  py::list out;
  for (const auto& p : pairs) {
    py::dict d;
    d["link_a"] = r.robot.links[p.link_a].name;
    d["other"] = p.object >= 0 ? r.env.objects[p.object].name : r.robot.links[p.link_b].name;
    d["is_object"] = p.object >= 0;
    d["distance"] = p.distance;
    d["point_a"] = p.point_a;
    d["point_b"] = p.point_b;
    d["normal"] = p.normal;
    out.append(d);
  }
  return out;
}

// grasp_transfer: one grasp and method through RunGraspTrials, its report.json entry.
py::object GraspTransferPy(const fs::path& grasp_path, const std::string& method, double mu,
                           int repeats, std::uint32_t seed, double close_by,
                           std::optional<int> perturb) {
  if (perturb) {
    WarnDeprecated("perturb", "repeats");
    repeats = *perturb;
  }
  const std::string grasp = grasp_path.string();
  if (!(mu >= 0.0) || !std::isfinite(mu)) ThrowValue("mu: must be finite and >= 0");
  if (!(close_by >= 0.0 && close_by <= planning::physics::GraspTrialsOptions::kMaxCloseBy))
    ThrowValue("close_by: must be in [0, 0.5] rad");
  if (repeats < 0 || repeats > 1000) ThrowValue("repeats: must be in 0..1000");
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
    options.perturb = repeats;
    options.seed = seed;
    options.close_by = close_by;
    const auto result = planning::physics::RunGraspTrials(ode, in.human, in.lwr_sdh, in.objects,
                                                          in.grasps, {tm}, options);
    report = planning::physics::GraspReportJson(result);
  }
  return JsonToPython(report["grasps"][0]);
}

// Robot.ik: one position (+ axis) target through planning::SolveIk, as a dict.
py::dict IkPy(PyRobot& r, const std::string& link, const py::handle& position,
              const py::handle& offset, const py::object& axis, const py::handle& q0,
              const std::vector<std::string>& frozen, int starts, std::uint32_t seed,
              bool check_collision, double tolerance, double axis_tolerance) {
  planning::IkTarget target;
  target.link = r.Link(link);
  target.position = ToVector(position, "position", 3);
  target.offset = ToVector(offset, "offset", 3);
  if (!axis.is_none()) {
    const py::tuple pair = Named("axis", [&] { return py::cast<py::tuple>(axis); });
    if (pair.size() != 2) ThrowValue("axis: expected (link_axis, world_direction)");
    target.axis =
        planning::IkAxis{ToVector(pair[0], "axis[0]", 3), ToVector(pair[1], "axis[1]", 3)};
    if (target.axis->local.norm() < 1e-12 || target.axis->world.norm() < 1e-12)
      ThrowValue("axis: directions must be non-zero");
  }
  if (starts < 1 || starts > 100000) ThrowValue("starts: must be in 1..100000");
  if (!(tolerance > 0.0) || !(axis_tolerance > 0.0) || !std::isfinite(tolerance) ||
      !std::isfinite(axis_tolerance))
    ThrowValue("tolerance, axis_tolerance: must be finite and > 0");
  planning::IkProblem problem;
  problem.targets.push_back(target);
  if (!q0.is_none()) problem.seed = r.Q(q0);
  problem.frozen_dofs = Named("frozen", [&] { return planning::DofIndices(r.robot, frozen); });
  planning::IkOptions options;
  options.starts = starts;
  options.random_seed = seed;
  options.position_tolerance = tolerance;
  options.axis_tolerance = axis_tolerance;
  if (check_collision) {
    planning::CollisionData* coll = r.Coll();
    options.is_valid = [&r, coll](const Eigen::VectorXd& q) {
      planning::ForwardKinematics(r.robot, q, r.kin.get());
      return !planning::InCollision(r.robot, *r.kin, coll);
    };
  }
  planning::IkData data(r.robot);
  const planning::IkResult result =
      Named("ik", [&] { return planning::SolveIk(r.robot, problem, options, &data); });
  py::dict out;
  out["status"] = planning::IkStatusName(result.status);
  out["q"] = result.q;
  out["position_error"] = result.position_error;
  out["axis_error"] = result.axis_error;
  out["iterations"] = result.iterations;
  out["starts"] = result.starts;
  out["start"] = result.start;
  out["rejected"] = result.rejected;
  return out;
}

// Robot: loading, names, limits and forward kinematics.
void BindRobotModel(py::class_<PyRobot>& robot) {
  robot
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
           "Forward kinematics: {link name: 4x4 world_from_link}, or one 4x4 when link is given.");
}

// Robot: Jacobians of link points and frames, chain points and their Jacobian.
void BindRobotJacobians(py::class_<PyRobot>& robot) {
  robot
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
      .def("ik", &IkPy, py::arg("link"), py::arg("position"),
           py::arg("offset") = std::vector<double>{0, 0, 0}, py::arg("axis") = py::none(),
           py::arg("q0") = py::none(), py::arg("frozen") = std::vector<std::string>{},
           py::arg("starts") = 8, py::arg("seed") = 0, py::arg("check_collision") = false,
           py::arg("tolerance") = 1e-5, py::arg("axis_tolerance") = 1e-5,
           "Inverse kinematics (damped least squares inside the joint limits, multistart):\n"
           "q that puts the point offset (link frame, m) of link at position (world, m);\n"
           "axis=(link_axis, world_direction) also aligns a link axis. q0: start (default the\n"
           "middle of the limits); frozen: joint names held at q0; check_collision: accept\n"
           "only collision-free q (placed objects and self). Returns {status ('solved',\n"
           "'not_reached', 'invalid'), q, position_error [m], axis_error [rad], iterations,\n"
           "starts, start, rejected}.");
}

// Robot: placed objects and the collision and distance queries.
void BindRobotCollision(py::class_<PyRobot>& robot) {
  robot
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
      .def("distances", &DistancesPy, py::arg("q"), py::arg("margin") = 0.1,
           "Every checked pair closer than margin [m]: list of dicts with link_a, other (link or\n"
           "object name), is_object, distance, point_a, point_b, normal (world frame).");
}

// The Robot class.
void BindRobot(py::module_& m) {
  py::class_<PyRobot> robot(
      m, "Robot",
      "A robot model loaded from a URDF, with placed collision objects. q is an\n"
      "array in joint_names order or a dict {joint name: value} (others 0).");
  BindRobotModel(robot);
  BindRobotJacobians(robot);
  BindRobotCollision(robot);
}

// The Scenario class: its poses, writhe and planners.
void BindScenario(py::module_& m) {
  py::class_<PyScenario>(m, "Scenario", "A set-up planning scenario (see load_scenario).")
      .def_property_readonly(
          "name", [](const PyScenario& s) { return s.scenario->name; }, "Scenario name.")
      .def_property_readonly(
          "joint_names", [](const PyScenario& s) { return planning::DofNames(s.scenario->robot); },
          "Joint names in q order.")
      .def_property_readonly(
          "q0", [](const PyScenario& s) { return Eigen::VectorXd(s.scenario->initial.problem.q0); },
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
}

// grasp_transfer and the grasp experiment's names and statistics.
void BindGrasp(py::module_& m) {
  m.def(
      "grasp_transfer", &GraspTransferPy, py::arg("grasp"), py::arg("method") = "winding",
      py::arg("mu") = 1.0, py::arg("repeats") = 0, py::arg("seed") = 0,
      py::arg("close_by") = planning::physics::HandBuildOptions{}.close_by, py::kw_only(),
      py::arg("perturb") = py::none(),
      "Transfers one human grasp (a name in assets/grasps or a file) to the SDH with method\n"
      "(winding, winding_only, contact_only, fingertip, joint, human), tests it in ODE with\n"
      "friction mu and returns its entry of `topoplan grasp transfer`'s report.json. repeats = N\n"
      "> 0 repeats the test N times with the object moved (<= 5 mm) and turned (<= 5 deg), seeded\n"
      "by seed as `grasp transfer --repeats N --seed S` (methods[...]['perturbed']; perturb= is\n"
      "the deprecated name). close_by:\n"
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
}

namespace {

// Planner names, in registry order.
std::vector<std::string> PlannerNames(const std::vector<planning::Planner>& planners) {
  std::vector<std::string> names;
  for (planning::Planner p : planners) names.emplace_back(planning::PlannerName(p));
  return names;
}

}  // namespace

// available_planners, default_planners and asset_root: what this build and installation provide.
void BindBuildInfo(py::module_& m) {
  m.def(
      "available_planners", [] { return PlannerNames(planning::AvailablePlanners()); },
      "Names of the planners of this build (aico, rrt, birrt, and ompl-* with OMPL).");
  m.def(
      "default_planners", [] { return PlannerNames(planning::DefaultPlanners()); },
      "The planners an unwrap sweep runs when none are named: available_planners() without the\n"
      "OMPL goal-region peers (ompl-rrt-region, ompl-rrtconnect-region), run by name only.");
  m.def("asset_root", &base::AssetRoot,
        "Root of the asset tree ($TOPOPLAN_ASSETS, else the installed or source assets/).");
}

}  // namespace

void BindPlanning(py::module_& m) {
  // Classes before the functions that take or return them (their signatures name them).
  BindRobot(m);
  BindScenario(m);
  BindScenarioLoading(m);
  BindGrasp(m);
  BindBuildInfo(m);
}

}  // namespace topoplan_py
