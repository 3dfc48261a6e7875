"""``python3 -m topoplan.sweep unwrap``: one Dask task per (angle, seed, planner) run of the unwrap
benchmark (thesis Fig. 4.5, the experiment of ``topoplan bench unwrap``), with a set-up task per
angle (and seed, with --perturb) whose resolved poses the runs reuse."""

import collections
import functools
import math
import os

from ._sweep_common import (
    CSV_HEADER,
    UsageError,
    check_common,
    check_params,
    fmt_number,
    read_rows,
    row_line,
    run_tasks,
    unwrap_key,
    write_atomically,
)

MAX_ANGLES = 10000  # as `bench unwrap --angles`
MAX_RUNS = 1000000  # as `bench unwrap`: angles x planners x seeds


def parse_range(text, flag="--angles"):
    """'a:b:step' -> [a, a+step, ...] up to b (inclusive), the values of `bench unwrap`."""
    try:
        a, b, step = (float(x) for x in text.split(":"))
    except ValueError:
        raise UsageError(
            f"{flag}: expected a:b:step (three numbers separated by ':'), got '{text}'"
        ) from None
    if not all(math.isfinite(x) for x in (a, b, step)) or not (step > 0.0 and 0.0 <= a <= b <= 2000.0):
        raise UsageError(f"{flag}: expected a:b:step with 0 <= a <= b <= 2000, step > 0")
    count = int((b - a) / step + 1e-9) + 1  # the same values as `bench unwrap`: a + i * step
    if count > MAX_ANGLES:
        raise UsageError(f"{flag}: more than {MAX_ANGLES} angles (use a larger step)")
    return [a + i * step for i in range(count)]


def parse_planners(text, available, default=None):
    """Comma-separated planner names, each one of `available` and listed once; None -> `default`
    (topoplan.default_planners(): the OMPL peers too when the module was built with them, but not
    the OMPL goal-region peers), or all of `available` when no default is given, as `bench unwrap`."""
    if text is None:
        return list(default if default is not None else available)
    names = [p for p in text.split(",")]
    if not names or any(not p for p in names):
        raise UsageError(f"--planners: empty name in '{text}'")
    for i, p in enumerate(names):
        if p not in available:
            raise UsageError(f"--planners: unknown planner '{p}' ({', '.join(available)})")
        if p in names[:i]:
            raise UsageError(f"--planners: '{p}' is listed twice")
    return names


@functools.lru_cache(maxsize=4)
def _perturbation(seeds, perturb):
    import topoplan

    return topoplan.unwrap_perturbation("unwrap", seeds, perturb)


def pole_offset(seed, seeds, perturb):
    """(object name, (3,) offset) of seed `seed` as ``bench unwrap --perturb`` moves the pole."""
    p = _perturbation(seeds, perturb)
    return p["object"], p["offsets"][seed]


_SCENARIOS = collections.OrderedDict()  # per worker process: the last few set-up scenarios
_CACHE_SIZE = 4


def _scenario(angle, budget, seed=0, seeds=1, perturb=0.0, resolved=None):
    """The unwrap scenario of `angle` (with perturb > 0: the pole moved by seed's offset), set up
    once per worker process and reused, as ``bench unwrap`` reuses it for every planner of an
    angle and seed. With `resolved` (Scenario.resolved_poses() of the same set-up, computed by
    another process) the expensive start-coil continuation and final-pose estimate are skipped;
    the scenario, and every plan from it, are the same."""
    import topoplan

    if perturb <= 0:
        seed, seeds = 0, 1
    key = (angle, budget, seed, seeds, perturb)
    scenario = _SCENARIOS.get(key)
    if scenario is not None:
        _SCENARIOS.move_to_end(key)
        return scenario
    moves = {}
    if perturb > 0:
        name, offset = pole_offset(seed, seeds, perturb)
        moves = {name: offset}
    scenario = topoplan.load_scenario(
        "unwrap", start_wrap=angle, rrt_budget=budget, move_objects=moves, resolved=resolved
    )
    _SCENARIOS[key] = scenario
    if len(_SCENARIOS) > _CACHE_SIZE:
        _SCENARIOS.popitem(last=False)
    return scenario


def unwrap_setup(angle, budget=-1, seed=0, seeds=1, perturb=0.0):
    """The set-up task of one angle (and, with perturb > 0, seed): sets the scenario up (on a
    worker) and returns its resolved poses, which the run tasks of that angle and seed depend on,
    so the set-up is done once per sweep instead of once per worker."""
    return _scenario(angle, budget, seed, seeds, perturb).resolved_poses()


def run_unwrap(angle, planner, seed, budget=-1, seeds=1, perturb=0.0, resolved=None):
    """One run of the unwrap benchmark (on a worker): a dict with the unwrap.csv columns.

    `resolved`: the result of unwrap_setup for this angle and seed (None: set up here)."""
    scenario = _scenario(angle, budget, seed, seeds, perturb, resolved)
    _, report = scenario.plan(planner, seed)
    return {
        "angle_deg": angle,
        "planner": planner,
        "seed": seed,
        "success": 1 if report["success"] else 0,
        "failure_reason": report["failure_reason"],
        "collision_checks": int(report["collision_checks"]),
        "narrow_phase_calls": int(report["narrow_phase_calls"]),
        "time_s": float(report["time_s"]),
        "path_length": float(report["path_length"]),
        "reach_error_m": float(report["reach_error_m"]),
        "pole_offset_m": pole_offset_norm(seed, seeds, perturb),
        # The common cost units (docs/results/unwrap.md); the set-up is timed by bench unwrap only.
        "state_queries": int(report["state_queries"]),
        "bool_pair_tests": int(report["bool_pair_tests"]),
        "distance_pair_tests": int(report["distance_pair_tests"]),
        "cpu_time_s": float(report["cpu_time_s"]),
        "setup_time_s": 0.0,
        # The goal-region planners' sampler share (0 for the others).
        "goal_samples": int(report["goal_samples"]),
        "goal_sampler_state_queries": int(report["goal_sampler_state_queries"]),
        "goal_sampler_pair_tests": int(report["goal_sampler_bool_pair_tests"])
        + int(report["goal_sampler_distance_pair_tests"]),
        "goal_sampler_cpu_time_s": float(report["goal_sampler_cpu_time_s"]),
    }


def pole_offset_norm(seed, seeds, perturb):
    if perturb <= 0:
        return 0.0
    return float(sum(x * x for x in pole_offset(seed, seeds, perturb)[1]) ** 0.5)


def sweep_unwrap(args):
    import topoplan

    angles = parse_range(args.angles)
    planners = parse_planners(args.planners, topoplan.available_planners(),
                              topoplan.default_planners())
    check_common(args)
    if not (0 <= args.perturb <= 1):  # also refuses NaN
        raise UsageError("--pole-offset: expected a distance in metres in 0..1")
    if args.budget != -1 and not 1 <= args.budget <= 1000000000:
        raise UsageError("--budget: expected a collision-check count in 1..1e9 (as bench unwrap)")
    keys = [fmt_number(a) for a in angles]
    if len(set(keys)) != len(keys):
        # Runs are keyed by the angle as unwrap.csv prints it (6 significant digits).
        raise UsageError("--angles: two angles print alike with 6 significant digits (use a larger step)")
    csv_path = os.path.join(args.output, "unwrap.csv")
    done = read_rows(csv_path)
    if len(angles) * len(planners) * args.seeds > MAX_RUNS:
        raise UsageError(
            f"--seeds: {len(angles) * len(planners) * args.seeds} runs (angles x planners x seeds), "
            f"more than {MAX_RUNS}"
        )
    runs = [(fmt_number(a), p, s) for a in angles for p in planners for s in range(args.seeds)]
    if done and args.perturb > 0:
        want = {s: fmt_number(pole_offset_norm(s, args.seeds, args.perturb)) for s in range(args.seeds)}
    else:
        want = {s: "0" for s in range(args.seeds)}
    for row in done.values():
        if row["seed"] in want and fmt_number(row["pole_offset_m"]) != want[row["seed"]]:
            raise UsageError(
                f"--pole-offset: {csv_path} holds runs with another pole perturbation "
                f"(seed {row['seed']}: offset {fmt_number(row['pole_offset_m'])} m); use another -o"
            )

    setups = {}  # (angle, seed or 0) -> future of unwrap_setup

    def submit(client, run):
        # run_unwrap and unwrap_setup go to the workers by reference (topoplan._sweep_unwrap.*).
        angle, seed = float(run[0]), run[2]
        key = (angle, seed if args.perturb > 0 else 0)
        # Larger angles first: their runs take longest (the RRTs use up their budget), so the
        # sweep ends with short runs and no worker waits long for the last one.
        priority = int(angle * 100)
        if key not in setups:
            setups[key] = client.submit(
                unwrap_setup, angle, args.budget, key[1], args.seeds, args.perturb,
                pure=False, retries=1, priority=priority + 1,
            )
        return client.submit(
            run_unwrap, angle, run[1], seed, args.budget, args.seeds, args.perturb, setups[key],
            pure=False, retries=1, priority=priority,
        )

    def label(row):
        return f"{row['planner']} @ {fmt_number(row['angle_deg'])} deg seed {row['seed']}"

    params = {"--budget": args.budget, "--pole-offset": args.perturb}
    check_params(csv_path, done, params)
    if run_tasks(args, csv_path, CSV_HEADER, runs, done, unwrap_key, row_line, submit, label,
                 params):
        return 1
    rows = [done[r] for r in runs]
    figure = topoplan.unwrap_figure(rows, angles, planners, args.seeds)
    png = os.path.join(args.output, "unwrap.png")
    if figure is not None:
        write_atomically(png, lambda tmp: topoplan.write_png(tmp, figure))
    print(f"wrote {csv_path} and {png} ({len(runs)} runs)")
    return 0
