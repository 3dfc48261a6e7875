"""Parameter sweeps on a Dask cluster: ``python3 -m topoplan.sweep unwrap ...``.

One Dask task per (angle, seed, planner) run of the unwrap benchmark (thesis Fig. 4.5, the
experiment of ``topoplan bench unwrap``). Without ``--scheduler`` a LocalCluster with one
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
import functools
import os
import sys
import time

CSV_HEADER = (
    "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
    "time_s,path_length,reach_error_m,pole_offset_m"
)
MAX_ANGLES = 10000  # as `bench unwrap --angles`


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


def parse_range(text, flag="--angles"):
    """'a:b:step' -> [a, a+step, ...] up to b (inclusive), the values of `bench unwrap`."""
    try:
        a, b, step = (float(x) for x in text.split(":"))
    except ValueError:
        raise UsageError(f"{flag}: expected a:b:step, got '{text}'") from None
    if not (step > 0.0) or b < a or a < 0.0 or b > 2000.0:
        raise UsageError(f"{flag}: expected a:b:step with 0 <= a <= b <= 2000, step > 0")
    count = int((b - a) / step + 1e-9) + 1  # the same values as `bench unwrap`: a + i * step
    if count > MAX_ANGLES:
        raise UsageError(f"{flag}: more than {MAX_ANGLES} angles (use a larger step)")
    return [a + i * step for i in range(count)]


def parse_planners(text, available):
    """Comma-separated planner names, each one of `available`."""
    names = [p for p in text.split(",")]
    if not names or any(not p for p in names):
        raise UsageError(f"--planners: empty name in '{text}'")
    for p in names:
        if p not in available:
            raise UsageError(f"--planners: unknown planner '{p}' ({', '.join(available)})")
    return names


def fmt_number(x):
    """A number as C++ iostreams print it by default (6 significant digits), as in unwrap.csv."""
    return "%g" % x


@functools.lru_cache(maxsize=4)
def _scenario(angle, budget):
    import topoplan

    return topoplan.load_scenario("unwrap", start_wrap=angle, rrt_budget=budget)


def run_unwrap(angle, planner, seed, budget=-1):
    """One run of the unwrap benchmark (on a worker): a dict with the unwrap.csv columns.

    The scenario of each angle is set up once per worker process and reused, as
    ``bench unwrap`` reuses it for every planner and seed of an angle."""
    scenario = _scenario(angle, budget)
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
        "pole_offset_m": 0.0,  # the sweep does not move the pole (bench unwrap --perturb does)
    }


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


def read_rows(path):
    """Complete rows of an existing unwrap.csv (a torn last line is dropped and cut off)."""
    rows = {}
    if not os.path.exists(path):
        return rows
    with open(path, "rb+") as f:
        data = f.read()
        end = data.rfind(b"\n") + 1
        if end != len(data):  # a crash mid-line: keep only complete lines
            f.truncate(end)
    lines = data[:end].decode().splitlines()
    if lines and lines[0] != CSV_HEADER:
        raise UsageError(f"{path}: not an unwrap.csv (header '{lines[0]}')")
    for n, line in enumerate(lines[1:], start=2):
        parts = line.split(",")
        try:
            angle, planner, seed = float(parts[0]), parts[1], int(parts[2])
            row = {
                "angle_deg": angle,
                "planner": planner,
                "seed": seed,
                "success": int(parts[3]),
                "failure_reason": parts[4],
                "collision_checks": int(parts[5]),
                "narrow_phase_calls": int(parts[6]),
                "time_s": float(parts[7]),
                "path_length": float(parts[8]),
                "reach_error_m": float(parts[9]),
                "pole_offset_m": float(parts[10]),
            }
        except (ValueError, IndexError):
            raise UsageError(f"{path}:{n}: malformed row '{line}'") from None
        rows[(fmt_number(angle), planner, seed)] = row
    return rows


def append_row(f, row):
    f.write(row_line(row) + "\n")
    f.flush()
    os.fsync(f.fileno())


def connect(scheduler, workers, timeout):
    """A dask.distributed Client: to `scheduler`, or to a new LocalCluster of `workers`
    single-threaded processes. Raises UsageError when the scheduler is unreachable."""
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            return Client(scheduler, timeout=timeout), None
        except (OSError, TimeoutError) as e:
            raise UsageError(f"--scheduler: cannot reach {scheduler} within {timeout} s ({e})")
    cluster = LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
    )
    return Client(cluster), cluster


def sweep_unwrap(args):
    import topoplan

    angles = parse_range(args.angles)
    planners = parse_planners(args.planners, topoplan.available_planners())
    if args.seeds < 1:
        raise UsageError("--seeds: must be >= 1")
    if args.workers is not None and args.workers < 1:
        raise UsageError("--workers: must be >= 1")
    if os.path.exists(args.output) and not os.path.isdir(args.output):
        raise UsageError(f"-o: {args.output} exists and is not a folder")
    csv_path = os.path.join(args.output, "unwrap.csv")
    done = read_rows(csv_path)
    runs = [(a, p, s) for a in angles for p in planners for s in range(args.seeds)]
    todo = [r for r in runs if (fmt_number(r[0]), r[1], r[2]) not in done]
    total = len(runs)

    client, cluster = None, None
    if todo:
        client, cluster = connect(
            args.scheduler, args.workers or os.cpu_count() or 1, args.timeout
        )
    os.makedirs(args.output, exist_ok=True)
    failed = 0
    try:
        if todo:
            from distributed import as_completed

            # By reference (topoplan.sweep.run_unwrap), also when this file runs as __main__.
            from topoplan.sweep import run_unwrap as task

            new_file = not os.path.exists(csv_path)
            with open(csv_path, "a") as f:
                if new_file:
                    f.write(CSV_HEADER + "\n")
                    f.flush()
                    os.fsync(f.fileno())
                futures = [
                    client.submit(task, a, p, s, args.budget, pure=False, retries=1)
                    for (a, p, s) in todo
                ]
                count = total - len(todo)
                start = time.monotonic()
                for future in as_completed(futures):
                    count += 1
                    try:
                        row = future.result()
                    except Exception as e:  # noqa: BLE001 - a run's error is reported, not fatal
                        failed += 1
                        print(f"\nsweep: a run failed: {e}", file=sys.stderr)
                        continue
                    append_row(f, row)
                    done[(fmt_number(row["angle_deg"]), row["planner"], row["seed"])] = row
                    if not args.quiet:
                        print(
                            f"\r[{count}/{total}] {row['planner']} @ {fmt_number(row['angle_deg'])}"
                            f" deg seed {row['seed']} ({time.monotonic() - start:.1f} s)   ",
                            end="",
                            file=sys.stderr,
                            flush=True,
                        )
                if not args.quiet:
                    print(file=sys.stderr)
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    if failed:
        print(f"sweep: {failed} runs failed; rerun to retry them", file=sys.stderr)
        return 1
    rows = [done[(fmt_number(a), p, s)] for (a, p, s) in runs]
    figure = topoplan.unwrap_figure(rows, angles, planners, args.seeds)
    if figure is not None:
        tmp = os.path.join(args.output, ".unwrap.png.tmp")
        topoplan.write_png(tmp, figure)
        os.replace(tmp, os.path.join(args.output, "unwrap.png"))
    print(f"wrote {csv_path} and {os.path.join(args.output, 'unwrap.png')} ({total} runs)")
    return 0


def build_parser():
    parser = argparse.ArgumentParser(
        prog="python3 -m topoplan.sweep", description="topoplan parameter sweeps on Dask"
    )
    sub = parser.add_subparsers(dest="command", required=True)
    u = sub.add_parser(
        "unwrap",
        help="thesis Fig. 4.5: collision checks vs angle to unwrap (as `topoplan bench unwrap`)",
    )
    u.add_argument("--angles", default="0:900:90", help="start wraps a:b:step in degrees")
    u.add_argument("--seeds", type=int, default=3, help="seeds 0..N-1 per angle and planner")
    u.add_argument("--planners", default="aico,rrt,birrt", help="comma-separated planners")
    u.add_argument("--budget", type=int, default=-1, help="RRT collision-check budget")
    u.add_argument("--scheduler", help="tcp://HOST:PORT of a dask scheduler (default: local)")
    u.add_argument("--workers", type=int, help="local worker processes (default: one per core)")
    u.add_argument("--timeout", type=float, default=10.0, help="scheduler connect timeout [s]")
    u.add_argument("--quiet", action="store_true", help="no progress line")
    u.add_argument("-o", "--output", required=True, help="output folder")
    return parser


def main(argv=None):
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 for bad flags already
        return e.code
    try:
        return sweep_unwrap(args)
    except UsageError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
