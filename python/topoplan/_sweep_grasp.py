"""``python3 -m topoplan.sweep grasp``: one Dask task per (grasp, method, seed) of the grasp
transfer experiment (``topoplan grasp transfer --perturb N --seed S``), written to DIR/grasp.csv,
and DIR/grasp_summary.csv (per grasp and method: stable repetitions over all seeds and their
Wilson 95 % interval) at the end."""

import os

from ._sweep_common import (
    UsageError,
    check_common,
    check_params,
    fmt_number,
    read_rows,
    run_tasks,
    write_atomically,
)

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
        grasp, method, mu=mu, repeats=perturb, seed=seed, close_by=close_by
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

    grasps = parse_names(args.grasps, topoplan.available_grasps(), "--grasp")
    methods = parse_names(args.methods, topoplan.transfer_methods(), "--method")
    if not (args.mu >= 0.0) or args.mu != args.mu or args.mu == float("inf"):
        raise UsageError("--mu: must be finite and >= 0")
    if not (0 <= args.perturb <= 1000):
        raise UsageError("--repeats: must be in 0..1000")
    if not (0.0 <= args.close_by <= 0.5):
        raise UsageError("--close-by: must be a number of radians in [0, 0.5]")
    if args.perturb == 0 and args.seeds > 1:
        # Without perturbations every seed is the same deterministic trial: counting them as
        # independent trials would narrow the intervals on no new evidence.
        raise UsageError("--seeds: without --repeats every seed is the same run; use --seeds 1")
    check_common(args)
    csv_path = os.path.join(args.output, "grasp.csv")
    done = read_rows(csv_path, GRASP_HEADER, parse_grasp_row, grasp_key)
    mu, close_by = fmt_number(args.mu), fmt_number(args.close_by)
    runs = [(g, m, s, mu, close_by) for g in grasps for m in methods for s in range(args.seeds)]

    def submit(client, run):
        # run_grasp goes to the workers by reference (topoplan._sweep_grasp.run_grasp).
        return client.submit(
            run_grasp,
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

    params = {"--repeats": args.perturb}
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
