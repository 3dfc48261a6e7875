// Scenario loading in Python: load_scenario (overrides, moved objects, an unwrap geometry, resolved
// poses) and unwrap_perturbation (the pole offsets of `bench unwrap --pole-offset`).
#include "base/assets.h"
#include "planning/motion/unwrap_benchmark.h"
#include "python/bind/planning_types.h"

namespace topoplan_py {
namespace {

// load_scenario's move_objects as {name: (3,) offset} (each offset checked).
std::map<std::string, Eigen::Vector3d> ObjectOffsets(
    const std::map<std::string, py::object>& move_objects) {
  std::map<std::string, Eigen::Vector3d> offsets;
  for (const auto& [name, xyz] : move_objects) {
    offsets[name] = ToVector(xyz, "move_objects['" + name + "']", 3);
  }
  return offsets;
}

// Adds each offset to the position of the scenario's object of that name.
void MoveScenarioObjects(const std::map<std::string, Eigen::Vector3d>& offsets,
                         planning::ScenarioSpec* spec) {
  for (const auto& [name, offset] : offsets) {
    auto it = std::find_if(spec->objects.begin(), spec->objects.end(),
                           [&](const auto& o) { return o.name == name; });
    if (it == spec->objects.end()) {
      ThrowValue("move_objects: the scenario has no object '" + name + "'");
    }
    it->xyz += offset;
  }
}

// load_scenario's resolved: the dict of Scenario.resolved_poses(), or nothing for None.
std::optional<planning::ResolvedPoses> ResolvedPosesFromPython(const py::object& resolved) {
  std::optional<planning::ResolvedPoses> given;
  if (resolved.is_none()) return given;
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
  return given;
}

// load_scenario: checks the overrides, parses and moves, then sets up without the GIL.
PyScenario LoadScenarioPy(const fs::path& arg_path, std::optional<double> start_wrap,
                          long rrt_budget, const std::map<std::string, py::object>& move_objects,
                          const py::object& resolved, std::optional<bool> stop_when_solved,
                          const std::optional<fs::path>& geometry) {
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
  const std::map<std::string, Eigen::Vector3d> offsets = ObjectOffsets(move_objects);
  planning::ScenarioSpec spec = planning::ParseScenarioSpec(path, overrides.search_roots);
  if (geometry) {
    if (!fs::is_regular_file(*geometry)) {
      ThrowPy(PyExc_FileNotFoundError, "geometry: no such file: " + geometry->string());
    }
    const planning::UnwrapGeometry g = Named("geometry", [&] {
      return planning::ReadUnwrapGeometry(geometry->string(), overrides.search_roots);
    });
    Named("geometry", [&] { planning::ApplyUnwrapGeometry(g, &spec); });
  }
  MoveScenarioObjects(offsets, &spec);
  // Options go into the spec: the set-up scenario is the model, not changed afterwards.
  if (rrt_budget > 0) spec.rrt.max_checks = rrt_budget;
  if (stop_when_solved) spec.aico_stop_when_solved = *stop_when_solved;
  const std::optional<planning::ResolvedPoses> given = ResolvedPosesFromPython(resolved);
  PyScenario s;
  {
    py::gil_scoped_release release;
    // Bad resolved poses throw std::invalid_argument "resolved: ..." (a ValueError).
    s.scenario = planning::SetUpScenario(std::move(spec), start_wrap, given ? &*given : nullptr);
  }
  return s;
}

// unwrap_perturbation: the pole offsets of `bench unwrap --pole-offset`.
py::dict UnwrapPerturbationPy(const fs::path& arg_path, int seeds, double pole_offset,
                              std::optional<double> perturb) {
  if (perturb) {
    WarnDeprecated("perturb", "pole_offset");
    pole_offset = *perturb;
  }
  const double m = pole_offset;
  const std::string path = Named(
      "path_or_name", [&] { return base::ResolveScenarioPath(arg_path.string()); },
      PyExc_FileNotFoundError);
  if (seeds < 1) ThrowValue("seeds: must be >= 1");
  if (!(m >= 0.0) || !std::isfinite(m)) ThrowValue("pole_offset: must be >= 0");
  planning::UnwrapPerturbation p;
  {
    py::gil_scoped_release release;
    const planning::ScenarioSpec spec = planning::ParseScenarioSpec(path, {base::AssetRoot()});
    p = planning::MakeUnwrapPerturbation(spec, 0.0, seeds, m);
  }
  Eigen::MatrixXd offsets(seeds, 3);
  for (int s = 0; s < seeds; ++s) offsets.row(s) = p.offsets[s].transpose();
  py::dict d;
  d["object"] = p.object_name;
  d["offsets"] = offsets;
  return d;
}

}  // namespace

// load_scenario and unwrap_perturbation: scenario files and the unwrap benchmark's set-ups.
void BindScenarioLoading(py::module_& m) {
  m.def(
      "load_scenario", &LoadScenarioPy, py::arg("path_or_name"), py::arg("start_wrap") = py::none(),
      py::arg("rrt_budget") = -1, py::arg("move_objects") = std::map<std::string, py::object>{},
      py::arg("resolved") = py::none(), py::arg("stop_when_solved") = py::none(),
      py::arg("geometry") = py::none(),
      "Loads a scenario file, or a name in the shipped assets/scenarios (e.g. 'unwrap'), and\n"
      "sets it up (start coil, final-pose estimate). start_wrap overrides the coil's angle to\n"
      "unwrap [deg]; rrt_budget > 0 replaces the RRTs' collision-check budget; move_objects\n"
      "{name: (3,) offset [m]} moves objects of the scenario before it is set up; resolved (a\n"
      "dict from Scenario.resolved_poses() of the same set-up) skips the expensive part;\n"
      "stop_when_solved (bool) replaces the scenario's aico.stop_when_solved (True: AICO stops at\n"
      "the first accepted sweep whose trajectory meets the success criteria, status 'solved');\n"
      "geometry (a file of assets/scenarios/unwrap_geometries/) applies an unwrap geometry (pole\n"
      "tilt, radius, translation, target offset, arm) first, as `topoplan plan --geometry`.");
  m.def("unwrap_perturbation", &UnwrapPerturbationPy, py::arg("path_or_name"), py::arg("seeds"),
        py::arg("pole_offset") = 0.0, py::kw_only(), py::arg("perturb") = py::none(),
        "The pole perturbation of `topoplan bench unwrap --pole-offset M --seeds N`: dict with\n"
        "'object' (the moved object's name, '' when pole_offset is 0) and 'offsets' (N x 3\n"
        "world-frame offsets [m], row s for seed s; at most pole_offset from the pole's line;\n"
        "perturb= is its deprecated name). Pass\n"
        "move_objects={object: offsets[s]} to load_scenario for seed s's set-up.");
}

}  // namespace topoplan_py
