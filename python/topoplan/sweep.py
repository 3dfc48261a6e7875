"""Parameter sweeps on a Dask cluster: ``python3 -m topoplan.sweep unwrap|grasp ...``.

``unwrap``: one Dask task per (angle, seed, planner) run of the unwrap benchmark (thesis Fig. 4.5,
the experiment of ``topoplan bench unwrap``). ``grasp``: one task per (grasp, method, seed) of
the grasp transfer experiment (``topoplan grasp transfer --perturb N --seed S``), written to
DIR/grasp.csv, with DIR/grasp_summary.csv (per grasp and method: stable repetitions over all
seeds and their Wilson 95 % interval) at the end. Without ``--scheduler`` a LocalCluster with one
single-threaded worker process per core runs them; with ``--scheduler tcp://HOST:PORT`` the
cluster's workers do (they need ``topoplan`` importable, e.g. the same PYTHONPATH).

Results stream into DIR/unwrap.csv as they finish (one appended, fsync'ed line per run, the
columns of ``bench unwrap``): a crash loses no finished run, and a rerun skips the runs already
in the file. When every run is there, DIR/unwrap.png is drawn by the same code as
``bench unwrap``.

Exit codes: 0 done, 2 bad input (ranges, planners, seeds) or an unreachable scheduler (nothing
is written to DIR then), 1 when a run raised.
"""

import argparse
import sys

# The work is in _sweep_unwrap, _sweep_grasp and _sweep_common; their names stay importable from
# here (topoplan.sweep.run_unwrap, .connect, ...).
from ._sweep_common import (  # noqa: F401
    CSV_HEADER,
    TimeLimit,
    UsageError,
    check_common,
    check_output_folder,
    check_params,
    connect,
    fmt_number,
    params_path,
    parse_unwrap_row,
    read_rows,
    row_line,
    run_tasks,
    unwrap_key,
    write_atomically,
)
from ._sweep_grasp import (  # noqa: F401
    GRASP_HEADER,
    GRASP_SUMMARY_HEADER,
    grasp_key,
    grasp_line,
    grasp_summary,
    parse_grasp_row,
    parse_names,
    run_grasp,
    sweep_grasp,
)
from ._sweep_unwrap import (  # noqa: F401
    MAX_ANGLES,
    MAX_RUNS,
    parse_planners,
    parse_range,
    pole_offset,
    pole_offset_norm,
    run_unwrap,
    sweep_unwrap,
    unwrap_setup,
)


class _Deprecated(argparse.Action):
    """An old spelling of a flag: stores into the new flag's destination with a warning (kept for
    one release)."""

    def __init__(self, option_strings, dest, new=None, **kwargs):
        self.new = new
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"warning: {option_string} is deprecated; use {self.new}", file=sys.stderr)
        setattr(namespace, self.dest, values)


def deprecated(p, old, new, dest, type_):
    p.add_argument(old, dest=dest, type=type_, action=_Deprecated, new=new, help=argparse.SUPPRESS)


def add_cluster_flags(p):
    p.add_argument("--scheduler", help="tcp://HOST:PORT of a dask scheduler (default: local)")
    p.add_argument("--threads", dest="workers", type=int,
                   help="runs at a time on the local cluster: worker processes of one thread each "
                   "(default: one per core; as `topoplan grasp transfer --threads`)")
    deprecated(p, "--workers", "--threads", "workers", int)
    p.add_argument("--timeout", type=float, default=0.0,
                   help="run limit [s] as for every topoplan command: then the sweep stops, keeps "
                   "the finished runs and exits 1 (a rerun goes on; default 0 = none)")
    p.add_argument("--connect-timeout", type=float, default=10.0,
                   help="how long to wait for --scheduler [s] (default 10)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress")
    p.add_argument("-v", "--verbose", action="store_true",
                   help="a line per finished run, also on a terminal")
    p.add_argument("-o", "--output", required=True, help="output folder")


def build_parser():
    parser = argparse.ArgumentParser(
        prog="python3 -m topoplan.sweep",
        description="topoplan parameter sweeps on Dask",
        epilog="Results stream into OUT/unwrap.csv or OUT/grasp.csv (a rerun skips the runs "
        "already there); the figure and summary are written at the end. Exit codes: 0 done, "
        "1 some runs raised, 2 bad input or an unreachable scheduler, 130 interrupted.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    u = sub.add_parser(
        "unwrap",
        help="thesis Fig. 4.5: collision checks vs angle to unwrap (as `topoplan bench unwrap`)",
    )
    u.add_argument("--angles", default="0:900:90", help="start wraps a:b:step in degrees (default 0:900:90)")
    u.add_argument("--seeds", type=int, default=3, help="seeds 0..N-1 per angle and planner (default 3)")
    u.add_argument(
        "--planners",
        default=None,
        help="comma-separated planners, each at most once (default: topoplan.default_planners(), "
        "with the OMPL peers when built, but not the OMPL goal-region peers)",
    )
    u.add_argument("--budget", type=int, default=-1, help="RRT collision-check budget (default: the scenario's, 100000)")
    u.add_argument(
        "--pole-offset",
        dest="perturb",
        type=float,
        default=0.0,
        help="move the pole of each seed by at most M metres perpendicular to its axis "
        "(as `bench unwrap --pole-offset`; default 0)",
    )
    deprecated(u, "--perturb", "--pole-offset", "perturb", float)
    add_cluster_flags(u)
    g = sub.add_parser(
        "grasp",
        help="grasp transfer: one run per (grasp, method, seed) of `grasp transfer --repeats N`",
    )
    g.add_argument("--grasp", dest="grasps", default="all",
                   help="'all' or comma-separated grasp names (as `grasp transfer --grasp`)")
    deprecated(g, "--grasps", "--grasp", "grasps", str)
    g.add_argument("--method", dest="methods", default="all",
                   help="'all' or comma-separated transfer methods (as `grasp transfer --method`)")
    deprecated(g, "--methods", "--method", "methods", str)
    g.add_argument("--seeds", type=int, default=1, help="perturbation seeds 0..N-1 per run (default 1)")
    g.add_argument("--repeats", dest="perturb", type=int, default=0,
                   help="perturbed repetitions per seed (as `grasp transfer --repeats`; default 0)")
    deprecated(g, "--perturb", "--repeats", "perturb", int)
    g.add_argument("--mu", type=float, default=1.0, help="Coulomb friction of the protocol (default 1)")
    g.add_argument(
        "--close-by",
        type=float,
        default=0.15,
        help="grip of the protocol: flexion set-points RAD past the grasp, in [0, 0.5]",
    )
    add_cluster_flags(g)
    return parser


def main(argv=None):
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 for bad flags already
        return e.code
    try:
        return sweep_unwrap(args) if args.command == "unwrap" else sweep_grasp(args)
    except TimeLimit:
        print(f"time limit reached: the finished runs are in {args.output}; rerun to go on",
              file=sys.stderr)
        return 1
    except UsageError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # every finished run is already in the CSV (fsync'ed)
        print(f"\ninterrupted: the finished runs are in {args.output}; rerun to go on",
              file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
