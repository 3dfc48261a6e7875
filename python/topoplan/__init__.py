"""topoplan: topology-based motion planning from Python.

Writhe matrices and winding numbers of chains (with derivatives), robot models (forward
kinematics, Jacobians, chains, collision checks), planning scenarios (AICO, RRT, BiRRT),
grasp transfer with the ODE stability test, and offscreen rendering.

Arrays are float64 NumPy arrays; chains and point lists are N x 3 (one point per row).
Bad input raises ValueError naming the argument, missing files FileNotFoundError, and a
missing GL context RuntimeError.

Example::

    import topoplan
    scenario = topoplan.load_scenario("unwrap", start_wrap=360)
    trajectory, report = scenario.plan("aico")
    print(report["success"], report["collision_checks"])

Sweeps on a Dask cluster: ``python3 -m topoplan.sweep unwrap --help`` (and ``grasp --help``).
"""

import os as _os
from pathlib import Path as _Path

# An installed package (<prefix>/lib/python3/dist-packages/topoplan) uses the installed assets
# (<prefix>/share/topoplan) unless TOPOPLAN_ASSETS says otherwise; the build tree's module finds
# the source tree's assets by itself.
if "TOPOPLAN_ASSETS" not in _os.environ:
    _parents = _Path(__file__).resolve().parents
    if len(_parents) > 4 and (_parents[4] / "share" / "topoplan" / "scenarios").is_dir():
        _os.environ["TOPOPLAN_ASSETS"] = str(_parents[4] / "share" / "topoplan")

from ._core import (  # noqa: E402
    __commit__,
    __version__,
    GLError,
    PlanCancelled,
    Robot,
    Scenario,
    asset_root,
    available_grasps,
    available_planners,
    default_planners,
    grasp_transfer,
    heatmap,
    linking_number,
    load_scenario,
    read_png,
    render,
    transfer_methods,
    unwrap_figure,
    unwrap_perturbation,
    wilson_interval,
    winding,
    write_png,
    writhe_jacobian,
    writhe_matrix,
    writhe_total,
)

__all__ = [
    "__version__",
    "GLError",
    "PlanCancelled",
    "Robot",
    "Scenario",
    "asset_root",
    "available_grasps",
    "available_planners",
    "default_planners",
    "grasp_transfer",
    "heatmap",
    "linking_number",
    "load_scenario",
    "read_png",
    "render",
    "transfer_methods",
    "unwrap_figure",
    "unwrap_perturbation",
    "wilson_interval",
    "winding",
    "write_png",
    "writhe_jacobian",
    "writhe_matrix",
    "writhe_total",
]
