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
import collections
import functools
import json
import math
import os
import sys
import tempfile
import time

CSV_HEADER = (
    "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
    "time_s,path_length,reach_error_m,pole_offset_m"
)
MAX_ANGLES = 10000  # as `bench unwrap --angles`
MAX_RUNS = 1000000  # as `bench unwrap`: angles x planners x seeds


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


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


def parse_planners(text, available):
    """Comma-separated planner names, each one of `available` and listed once; None -> all of
    `available` (the OMPL peers too when the module was built with them), as `bench unwrap`."""
    if text is None:
        return list(available)
    names = [p for p in text.split(",")]
    if not names or any(not p for p in names):
        raise UsageError(f"--planners: empty name in '{text}'")
    for i, p in enumerate(names):
        if p not in available:
            raise UsageError(f"--planners: unknown planner '{p}' ({', '.join(available)})")
        if p in names[:i]:
            raise UsageError(f"--planners: '{p}' is listed twice")
    return names


def fmt_number(x):
    """A number as C++ iostreams print it by default (6 significant digits), as in unwrap.csv."""
    return "%g" % x


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
    }


def pole_offset_norm(seed, seeds, perturb):
    if perturb <= 0:
        return 0.0
    return float(sum(x * x for x in pole_offset(seed, seeds, perturb)[1]) ** 0.5)


def row_line(row):
    return ",".join(
        [
            fmt_number(row["angle_deg"]),
            row["planner"],
            str(row["seed"]),
            str(row["success"]),
            row["failure_reason"],
            str(row["collision_checks"]),
            str(row["narrow_phase_calls"]),
            fmt_number(row["time_s"]),
            fmt_number(row["path_length"]),
            fmt_number(row["reach_error_m"]),
            fmt_number(row["pole_offset_m"]),
        ]
    )


def read_rows(path, header=CSV_HEADER, parse=None, key=None):
    """Complete rows of an existing result CSV (a torn last line is dropped and cut off), keyed
    by key(row); parse(parts) -> row raises ValueError/IndexError for a malformed line."""
    parse = parse or parse_unwrap_row
    key = key or unwrap_key
    rows = {}
    if not os.path.exists(path):
        return rows
    with open(path, "rb+") as f:
        data = f.read()
        end = data.rfind(b"\n") + 1
        if end != len(data):  # a crash mid-line: keep only complete lines
            f.truncate(end)
    lines = data[:end].decode().splitlines()
    if not lines and data:  # only a torn header: no finished run
        return rows
    if lines and lines[0] != header:
        raise UsageError(f"{path}: not a {os.path.basename(path)} of this sweep (header '{lines[0]}')")
    for n, line in enumerate(lines[1:], start=2):
        try:
            row = parse(line.split(","))
        except (ValueError, IndexError):
            raise UsageError(f"{path}:{n}: malformed row '{line}'") from None
        rows[key(row)] = row
    return rows


def parse_unwrap_row(parts):
    return {
        "angle_deg": float(parts[0]),
        "planner": parts[1],
        "seed": int(parts[2]),
        "success": int(parts[3]),
        "failure_reason": parts[4],
        "collision_checks": int(parts[5]),
        "narrow_phase_calls": int(parts[6]),
        "time_s": float(parts[7]),
        "path_length": float(parts[8]),
        "reach_error_m": float(parts[9]),
        "pole_offset_m": float(parts[10]),
    }


def unwrap_key(row):
    return (fmt_number(row["angle_deg"]), row["planner"], row["seed"])


def connect(scheduler, workers, timeout):
    """A dask.distributed Client: to `scheduler`, or to a new LocalCluster of `workers`
    single-threaded processes. Raises UsageError when the scheduler is unreachable."""
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            return Client(scheduler, timeout=timeout), None
        except (OSError, TimeoutError) as e:
            raise UsageError(f"--scheduler: cannot reach {scheduler} within {timeout} s ({e})")
    # Without Dask's statistical profiler in the workers: it samples the running task's stack
    # every 10 ms on the worker's event loop, and with two workers on two cores each run then took
    # 1.6x longer than in `topoplan bench unwrap` (README, "Running sweeps").
    # The nannies hand this process's configuration to the worker processes they start.
    import dask

    with dask.config.set({"distributed.worker.profile.enabled": False}):
        cluster = LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
        )
    return Client(cluster), cluster


def check_common(args):
    if not 1 <= args.seeds <= 1000:
        raise UsageError("--seeds: must be in 1..1000")
    if args.workers is not None and args.workers < 1:
        raise UsageError("--workers: must be >= 1")
    if not (math.isfinite(args.timeout) and 0 < args.timeout <= 3600):
        raise UsageError("--timeout: expected seconds in (0, 3600]")
    if args.scheduler is not None:
        url = args.scheduler
        scheme, sep, rest = url.partition("://")
        if not sep or scheme not in ("tcp", "tls", "inproc", "ucx", "ws", "wss") or not rest:
            raise UsageError(f"--scheduler: expected tcp://HOST:PORT, got '{url}'")
    check_output_folder(args.output)


def check_output_folder(output):
    """-o: a folder that exists or can be made (its nearest existing ancestor is a writable
    folder); checked before any work, so a bad -o exits 2 and starts no cluster."""
    if not output:
        raise UsageError("-o: empty output path")
    if os.path.exists(output):
        if not os.path.isdir(output):
            raise UsageError(f"-o: {output} exists and is not a folder")
        if not os.access(output, os.W_OK | os.X_OK):
            raise UsageError(f"-o: {output} is not writable")
        return
    parent = os.path.dirname(os.path.abspath(output))
    while not os.path.exists(parent):
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent):
        raise UsageError(f"-o: {output}: {parent} is not a folder")
    try:  # a probe folder, removed again: permissions alone do not tell (e.g. /proc as root)
        os.rmdir(tempfile.mkdtemp(prefix=".topoplan-probe-", dir=parent))
    except OSError as e:
        raise UsageError(f"-o: {output}: cannot create folders in {parent} ({e.strerror})") from None


def params_path(csv_path):
    """The sidecar that records the flags a result CSV was computed with but does not hold."""
    return os.path.join(os.path.dirname(csv_path), "." + os.path.basename(csv_path) + ".json")


def check_params(csv_path, done, params):
    """A rerun into a folder must use the flags its finished rows were computed with (those not
    in the rows themselves): exit 2 naming the first flag that differs."""
    path = params_path(csv_path)
    if not done or not os.path.exists(path):
        return
    with open(path) as f:
        before = json.load(f)
    for flag, value in params.items():
        if flag in before and before[flag] != value:
            raise UsageError(
                f"{flag}: {csv_path} was computed with {flag} {before[flag]}, not {value}; "
                "use another -o folder"
            )


def run_tasks(args, csv_path, header, runs, done, key, line, submit, label, params=None):
    """Submits one task per run not yet in `done` (submit(client, run) -> future), appends each
    finished row to csv_path (line(row), fsync'ed) and records it in done[key(row)]. Returns the
    number of runs that raised."""
    todo = [r for r in runs if r not in done]
    if not todo:
        return 0
    client, cluster = connect(args.scheduler, args.workers or os.cpu_count() or 1, args.timeout)
    os.makedirs(args.output, exist_ok=True)
    failed = 0
    try:
        from distributed import as_completed

        # A file without its complete header line (a crash before it reached the disk) is
        # started afresh: it holds no finished run.
        new_file = not os.path.exists(csv_path) or os.path.getsize(csv_path) <= len(header)
        if new_file and params is not None:
            write_atomically(params_path(csv_path), lambda tmp: json.dump(params, open(tmp, "w")))
        with open(csv_path, "w" if new_file else "a") as f:
            if new_file:
                f.write(header + "\n")
                f.flush()
                os.fsync(f.fileno())
            futures = [submit(client, r) for r in todo]
            count = len(runs) - len(todo)
            start = time.monotonic()
            for future in as_completed(futures):
                count += 1
                try:
                    row = future.result()
                except Exception as e:  # noqa: BLE001 - a run's error is reported, not fatal
                    failed += 1
                    print(f"\nsweep: a run failed: {e}", file=sys.stderr)
                    continue
                f.write(line(row) + "\n")
                f.flush()
                os.fsync(f.fileno())
                done[key(row)] = row
                if not args.quiet:
                    print(
                        f"\r[{count}/{len(runs)}] {label(row)} ({time.monotonic() - start:.1f} s)   ",
                        end="",
                        file=sys.stderr,
                        flush=True,
                    )
            if not args.quiet:
                print(file=sys.stderr)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    if failed:
        print(f"sweep: {failed} runs failed; rerun to retry them", file=sys.stderr)
    return failed


def write_atomically(path, write):
    """write(tmp_path), then rename onto path: the file appears whole or not at all."""
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp")
    write(tmp)
    os.replace(tmp, path)


def sweep_unwrap(args):
    import topoplan

    angles = parse_range(args.angles)
    planners = parse_planners(args.planners, topoplan.available_planners())
    check_common(args)
    if not (0 <= args.perturb <= 1):  # also refuses NaN
        raise UsageError("--perturb: expected a distance in metres in 0..1")
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
                f"--perturb: {csv_path} holds runs with another pole perturbation "
                f"(seed {row['seed']}: offset {fmt_number(row['pole_offset_m'])} m); use another -o"
            )

    setups = {}  # (angle, seed or 0) -> future of unwrap_setup

    def submit(client, run):
        # By reference (topoplan.sweep.*), also when this file runs as __main__.
        from topoplan.sweep import run_unwrap as task
        from topoplan.sweep import unwrap_setup

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
            task, angle, run[1], seed, args.budget, args.seeds, args.perturb, setups[key],
            pure=False, retries=1, priority=priority,
        )

    def label(row):
        return f"{row['planner']} @ {fmt_number(row['angle_deg'])} deg seed {row['seed']}"

    params = {"--budget": args.budget, "--perturb": args.perturb}
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


GRASP_HEADER = (
    "grasp,method,seed,mu,close_by,stable,directions_passed,epsilon_quality,perturbed_trials,"
    "perturbed_stable"
)
GRASP_SUMMARY_HEADER = "grasp,method,trials,stable,rate,ci95_lo,ci95_hi"


def parse_names(text, available, flag):
    """'all' or comma-separated names, each one of `available` (order kept)."""
    if text == "all":
        return list(available)
    names = text.split(",")
    for n in names:
        if n not in available:
            raise UsageError(f"{flag}: unknown name '{n}' ({', '.join(available)})")
    if len(set(names)) != len(names):
        raise UsageError(f"{flag}: a name is repeated in '{text}'")
    return names


def run_grasp(grasp, method, seed, mu, perturb, close_by=0.15):
    """One (grasp, method, seed) run of the grasp transfer experiment (on a worker): a dict with
    the grasp.csv columns (the method's entry of `grasp transfer --perturb N --seed S
    --close-by D`)."""
    import topoplan

    entry = topoplan.grasp_transfer(
        grasp, method, mu=mu, perturb=perturb, seed=seed, close_by=close_by
    )
    m = entry["methods"][method]
    perturbed = m.get("perturbed", {"trials": 0, "stable": 0})
    return {
        "grasp": grasp,
        "method": method,
        "seed": seed,
        "mu": mu,
        "close_by": close_by,
        "stable": 1 if m["stable"] else 0,
        "directions_passed": int(m["directions_passed"]),
        "epsilon_quality": float(m.get("epsilon_quality", 0.0)),
        "perturbed_trials": int(perturbed["trials"]),
        "perturbed_stable": int(perturbed["stable"]),
    }


def grasp_line(row):
    return ",".join(
        [
            row["grasp"],
            row["method"],
            str(row["seed"]),
            fmt_number(row["mu"]),
            fmt_number(row["close_by"]),
            str(row["stable"]),
            str(row["directions_passed"]),
            fmt_number(row["epsilon_quality"]),
            str(row["perturbed_trials"]),
            str(row["perturbed_stable"]),
        ]
    )


def parse_grasp_row(parts):
    if len(parts) != 10:
        raise ValueError("column count")
    return {
        "grasp": parts[0],
        "method": parts[1],
        "seed": int(parts[2]),
        "mu": float(parts[3]),
        "close_by": float(parts[4]),
        "stable": int(parts[5]),
        "directions_passed": int(parts[6]),
        "epsilon_quality": float(parts[7]),
        "perturbed_trials": int(parts[8]),
        "perturbed_stable": int(parts[9]),
    }


def grasp_key(row):
    return (
        row["grasp"],
        row["method"],
        row["seed"],
        fmt_number(row["mu"]),
        fmt_number(row["close_by"]),
    )


def grasp_summary(rows, perturb):
    """Per (grasp, method): trials and stable runs over all seeds (the perturbed repetitions when
    perturb > 0, else the nominal runs) and the Wilson 95 % interval of the rate."""
    import topoplan

    table = {}
    for r in rows:
        t = table.setdefault((r["grasp"], r["method"]), [0, 0])
        if perturb > 0:
            t[0] += r["perturbed_trials"]
            t[1] += r["perturbed_stable"]
        else:
            t[0] += 1
            t[1] += r["stable"]
    out = []
    for (grasp, method), (trials, stable) in table.items():
        lo, hi = topoplan.wilson_interval(stable, trials)
        out.append((grasp, method, trials, stable, stable / max(1, trials), lo, hi))
    return out


def sweep_grasp(args):
    import topoplan

    grasps = parse_names(args.grasps, topoplan.available_grasps(), "--grasps")
    methods = parse_names(args.methods, topoplan.transfer_methods(), "--methods")
    if not (args.mu >= 0.0) or args.mu != args.mu or args.mu == float("inf"):
        raise UsageError("--mu: must be finite and >= 0")
    if not (0 <= args.perturb <= 1000):
        raise UsageError("--perturb: must be in 0..1000")
    if not (0.0 <= args.close_by <= 0.5):
        raise UsageError("--close-by: must be a number of radians in [0, 0.5]")
    if args.perturb == 0 and args.seeds > 1:
        # Without perturbations every seed is the same deterministic trial: counting them as
        # independent trials would narrow the intervals on no new evidence.
        raise UsageError("--seeds: without --perturb every seed is the same run; use --seeds 1")
    check_common(args)
    csv_path = os.path.join(args.output, "grasp.csv")
    done = read_rows(csv_path, GRASP_HEADER, parse_grasp_row, grasp_key)
    mu, close_by = fmt_number(args.mu), fmt_number(args.close_by)
    runs = [(g, m, s, mu, close_by) for g in grasps for m in methods for s in range(args.seeds)]

    def submit(client, run):
        from topoplan.sweep import run_grasp as task

        return client.submit(
            task,
            run[0],
            run[1],
            run[2],
            args.mu,
            args.perturb,
            args.close_by,
            pure=False,
            retries=1,
        )

    def label(row):
        return f"{row['grasp']} / {row['method']} seed {row['seed']}"

    params = {"--perturb": args.perturb}
    check_params(csv_path, done, params)
    if run_tasks(args, csv_path, GRASP_HEADER, runs, done, grasp_key, grasp_line, submit, label,
                 params):
        return 1
    summary = grasp_summary([done[r] for r in runs], args.perturb)
    summary_path = os.path.join(args.output, "grasp_summary.csv")

    def write_summary(tmp):
        with open(tmp, "w") as f:
            f.write(GRASP_SUMMARY_HEADER + "\n")
            for g, m, trials, stable, rate, lo, hi in summary:
                f.write(
                    f"{g},{m},{trials},{stable},{fmt_number(rate)},{fmt_number(lo)},{fmt_number(hi)}\n"
                )

    write_atomically(summary_path, write_summary)
    print(f"wrote {csv_path} and {summary_path} ({len(runs)} runs)")
    return 0


def add_cluster_flags(p):
    p.add_argument("--scheduler", help="tcp://HOST:PORT of a dask scheduler (default: local)")
    p.add_argument("--workers", type=int, help="local worker processes (default: one per core)")
    p.add_argument("--timeout", type=float, default=10.0, help="scheduler connect timeout [s] (default 10)")
    p.add_argument("--quiet", action="store_true", help="no progress line")
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
        help="comma-separated planners, each at most once (default: all of this build, with the "
        "OMPL peers when built)",
    )
    u.add_argument("--budget", type=int, default=-1, help="RRT collision-check budget (default: the scenario's, 100000)")
    u.add_argument(
        "--perturb",
        type=float,
        default=0.0,
        help="move the pole of each seed by at most M metres perpendicular to its axis "
        "(as `bench unwrap --perturb`; default 0)",
    )
    add_cluster_flags(u)
    g = sub.add_parser(
        "grasp",
        help="grasp transfer: one run per (grasp, method, seed) of `grasp transfer --perturb N`",
    )
    g.add_argument("--grasps", default="all", help="'all' or comma-separated grasp names")
    g.add_argument("--methods", default="all", help="'all' or comma-separated transfer methods")
    g.add_argument("--seeds", type=int, default=1, help="perturbation seeds 0..N-1 per run (default 1)")
    g.add_argument("--perturb", type=int, default=0, help="perturbed repetitions per seed (default 0)")
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
    except UsageError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # every finished run is already in the CSV (fsync'ed)
        print(f"\ninterrupted: the finished runs are in {args.output}; rerun to go on",
              file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
