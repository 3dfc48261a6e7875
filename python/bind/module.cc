// The topoplan Python module (_core): one binding file per layer (python/bind/topology.cc,
// planning.cc with scenario_loading.cc, render.cc), all into one flat namespace, re-exported by
// topoplan/__init__.py.
#include "base/version.h"
#include "python/bind/planning_types.h"

using namespace topoplan_py;  // NOLINT(build/namespaces): the module's own helpers

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
  m.attr("__version__") = base::Version();
  m.attr("__commit__") = base::Commit();
  BindTopology(m);
  BindPlanning(m);
  BindRender(m);
}
