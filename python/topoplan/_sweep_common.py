"""The machinery shared by the sweeps of ``python3 -m topoplan.sweep``: bad-input errors, the
result CSVs (the unwrap.csv row format, reading back finished rows, the flags sidecar, atomic
writes), the flag checks and the Dask cluster that runs the tasks."""

import json
import math
import os
import sys
import tempfile
import time

# unwrap.csv, the columns of `bench unwrap` (the default format of read_rows).
CSV_HEADER = (
    "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
    "time_s,path_length,reach_error_m,pole_offset_m,state_queries,bool_pair_tests,"
    "distance_pair_tests,cpu_time_s,setup_time_s,goal_samples,goal_sampler_state_queries,"
    "goal_sampler_pair_tests,goal_sampler_cpu_time_s"
)


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


class TimeLimit(Exception):
    """--timeout passed: the finished runs are kept (exit code 1)."""


def fmt_number(x):
    """A number as C++ iostreams print it by default (6 significant digits), as in unwrap.csv."""
    return "%g" % x


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
            str(row["state_queries"]),
            str(row["bool_pair_tests"]),
            str(row["distance_pair_tests"]),
            fmt_number(row["cpu_time_s"]),
            fmt_number(row["setup_time_s"]),
            str(row["goal_samples"]),
            str(row["goal_sampler_state_queries"]),
            str(row["goal_sampler_pair_tests"]),
            fmt_number(row["goal_sampler_cpu_time_s"]),
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
        "state_queries": int(parts[11]),
        "bool_pair_tests": int(parts[12]),
        "distance_pair_tests": int(parts[13]),
        "cpu_time_s": float(parts[14]),
        "setup_time_s": float(parts[15]),
        "goal_samples": int(parts[16]),
        "goal_sampler_state_queries": int(parts[17]),
        "goal_sampler_pair_tests": int(parts[18]),
        "goal_sampler_cpu_time_s": float(parts[19]),
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
            raise UsageError(f"--scheduler: cannot reach {scheduler} within {timeout} s ({e}); see --connect-timeout")
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
        raise UsageError("--threads: must be >= 1")
    if not (math.isfinite(args.timeout) and 0 <= args.timeout <= 1e6):
        raise UsageError("--timeout: expected seconds in [0, 1e6] (0: no limit)")
    if not (math.isfinite(args.connect_timeout) and 0 < args.connect_timeout <= 3600):
        raise UsageError("--connect-timeout: expected seconds in (0, 3600]")
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
    client, cluster = connect(
        args.scheduler, args.workers or os.cpu_count() or 1, args.connect_timeout
    )
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
            # Progress: one line rewritten in place on a terminal, a line per run in a log file.
            tty = sys.stderr.isatty() and not getattr(args, "verbose", False)
            limit = getattr(args, "timeout", 0.0)
            for future in as_completed(futures):
                if limit > 0 and time.monotonic() - start > limit:
                    for other in futures:
                        other.cancel()
                    if not args.quiet and tty:
                        print(file=sys.stderr)
                    raise TimeLimit()
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
                    text = f"[{count}/{len(runs)}] {label(row)} ({time.monotonic() - start:.1f} s)"
                    if tty:
                        print(f"\r{text}   ", end="", file=sys.stderr, flush=True)
                    else:
                        print(text, file=sys.stderr, flush=True)
            if not args.quiet and tty:
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
