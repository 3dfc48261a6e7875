#!/usr/bin/env python3
"""`topoplan bench unwrap --ompl-log FILE`: the logs load the way OMPL's
ompl_benchmark_statistics.py loads a benchmark log (its rules restated here: header lines found by
their fixed words, <<<| ... |>>> blocks, "N <word>" counts, "; "-terminated run values, "nan" as
NULL, property names turned into SQL columns), into an in-memory SQLite database with the same
tables; then every run is checked against unwrap.csv.

usage: ompl_log_check.py TOPOPLAN_EXE WORK_DIR
"""

import csv
import math
import os
import shutil
import sqlite3
import subprocess
import sys

ANGLES = [0.0, 90.0]
PLANNERS = ["aico", "birrt"]
SEEDS = 2


class Log:
    """A log file read line by line, with the script's 'optional value' rule: a line whose fixed
    words do not match is put back."""

    def __init__(self, path):
        with open(path) as f:
            self.lines = f.read().split("\n")
        self.pos = 0

    def line(self):
        if self.pos >= len(self.lines):
            raise AssertionError("unexpected end of log")
        self.pos += 1
        return self.lines[self.pos - 1] + "\n"

    def value(self, index, expected, required=None):
        start = self.pos
        tokens = self.line().split()
        for i, word in expected.items():
            if tokens[i] != word:
                self.pos = start
                if required:
                    raise AssertionError("unable to read " + required)
                return None
        return tokens[index]

    def block(self, required):
        start = self.pos
        if not self.line().startswith("<<<|"):
            self.pos = start
            if required:
                raise AssertionError("expected <<<|")
            return None
        text = ""
        line = self.line()
        while not line.startswith("|>>>"):
            text += line
            line = self.line()
        return text


def load(db, path):
    c = db.cursor()
    log = Log(path)
    start = log.pos
    library = log.value(0, {1: "version"}) or "OMPL"
    log.pos = start
    version = log.value(-1, {1: "version"}) or "0.0.0"
    name = log.value(-1, {0: "Experiment"}, "experiment name")
    props = {}
    for _ in range(int(log.value(0, {-2: "experiment", -1: "properties"}) or 0)):
        key, value = log.line().strip().split(" = ")
        words = key.split(" ")
        props["".join(words[:-1]).replace("-", "_")] = (value, words[-1])
    c.execute("PRAGMA table_info(experiments)")
    have = [col[1] for col in c.fetchall()]
    for key in sorted(props):
        if key not in have:
            c.execute("ALTER TABLE experiments ADD %s %s" % (key, props[key][1]))
    host = log.value(-1, {0: "Running"}, "hostname")
    started = log.line()
    assert started.startswith("Starting"), started
    setup = log.block(True)
    cpu = log.block(False)
    seed = log.value(0, {-2: "random", -1: "seed"}, "random seed")
    time_limit = float(log.value(0, {-3: "seconds", -2: "per", -1: "run"}, "time limit"))
    memory_limit = float(log.value(0, {-3: "MB", -2: "per", -1: "run"}, "memory limit"))
    runs_per_planner = int(log.value(0, {-3: "runs", -2: "per", -1: "planner"}) or -1)
    total = float(log.value(0, {-3: "collect", -2: "the", -1: "data"}, "total time"))
    for _ in range(int(log.value(0, {-2: "enum"}) or 0)):
        enum = log.line()[:-1].split("|")
        c.execute("SELECT * FROM enums WHERE name IS ?", (enum[0],))
        if c.fetchone() is None:
            for j, text in enumerate(enum[1:]):
                c.execute("INSERT INTO enums VALUES (?,?,?)", (enum[0], j, text))
    columns = ["name", "totaltime", "timelimit", "memorylimit", "runcount", "version",
               "hostname", "cpuinfo", "date", "seed", "setup"] + list(props)
    values = [name, total, time_limit, memory_limit, runs_per_planner,
              library + " " + version, host, cpu, " ".join(started.split()[2:]), seed,
              setup] + [v[0] for v in props.values()]
    c.execute("INSERT INTO experiments (%s) VALUES (%s)"
              % (",".join(columns), ",".join("?" * len(values))), values)
    experiment = c.lastrowid
    for _ in range(int(log.value(0, {-1: "planners"}, "planner count"))):
        planner = log.line()[:-1]
        settings = "".join(log.line() + ";" for _ in range(int(log.line().split()[0])))
        c.execute("SELECT id FROM plannerConfigs WHERE (name=? AND settings=?)",
                  (planner, settings))
        row = c.fetchone()
        if row is None:
            c.execute("INSERT INTO plannerConfigs VALUES (?,?,?)", (None, planner, settings))
            planner_id = c.lastrowid
        else:
            planner_id = row[0]
        c.execute("PRAGMA table_info(runs)")
        have = [col[1] for col in c.fetchall()]
        names = ["experimentid", "plannerid"]
        for _ in range(int(log.line().split()[0])):
            field = log.line().split()
            column = "_".join(field[:-1])
            if column not in have:
                c.execute("ALTER TABLE runs ADD %s %s" % (column, field[-1]))
            names.append(column)
        insert = "INSERT INTO runs (%s) VALUES (%s)" % (",".join(names),
                                                        ",".join("?" * len(names)))
        for _ in range(int(log.line().split()[0])):
            cells = [None if not x or x in ("nan", "inf") else x
                     for x in log.line().split("; ")[:-1]]
            c.execute(insert, tuple([experiment, planner_id] + cells))
        assert log.line().strip() == ".", "no progress data expected, planner block ends with ."
    db.commit()


def new_db():
    db = sqlite3.connect(":memory:")
    db.executescript("""
        CREATE TABLE experiments (id INTEGER PRIMARY KEY AUTOINCREMENT, name VARCHAR(512),
          totaltime REAL, timelimit REAL, memorylimit REAL, runcount INTEGER,
          version VARCHAR(128), hostname VARCHAR(1024), cpuinfo TEXT, date DATETIME,
          seed VARCHAR(24), setup TEXT);
        CREATE TABLE plannerConfigs (id INTEGER PRIMARY KEY AUTOINCREMENT,
          name VARCHAR(512) NOT NULL, settings TEXT);
        CREATE TABLE enums (name VARCHAR(512), value INTEGER, description TEXT,
          PRIMARY KEY (name, value));
        CREATE TABLE runs (id INTEGER PRIMARY KEY AUTOINCREMENT, experimentid INTEGER,
          plannerid INTEGER);""")
    return db


def close(a, b):
    if a is None or math.isnan(b):
        return a is None and math.isnan(b)
    return abs(float(a) - float(b)) <= 1e-5 * max(1.0, abs(float(b)))


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "bench")
    log = os.path.join(work, "logs", "unwrap.log")
    r = subprocess.run([exe, "bench", "unwrap", "--angles", "0:90:90", "--seeds", str(SEEDS),
                        "--planners", ",".join(PLANNERS), "--budget", "2000", "-o", out,
                        "--ompl-log", log], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "wrote 2 OMPL benchmark logs" in r.stdout, r.stdout
    logs = sorted(os.listdir(os.path.join(work, "logs")))
    assert logs == ["unwrap_0deg.log", "unwrap_90deg.log"], logs

    db = new_db()
    for name in logs:
        load(db, os.path.join(work, "logs", name))
    c = db.cursor()
    c.execute("SELECT name, runcount, angle_deg, seeds FROM experiments ORDER BY id")
    assert c.fetchall() == [("unwrap_0deg", SEEDS, 0.0, SEEDS), ("unwrap_90deg", SEEDS, 90.0, SEEDS)]
    c.execute("SELECT name FROM plannerConfigs ORDER BY id")
    assert [x[0] for x in c.fetchall()] == PLANNERS  # one config per planner across angles
    c.execute("SELECT description FROM enums WHERE name = 'failure_reason' ORDER BY value")
    reasons = [x[0] for x in c.fetchall()]
    assert reasons[0] == "none" and "budget_exhausted" in reasons, reasons
    c.execute("""SELECT e.angle_deg, p.name, r.seed, r.solved, r.failure_reason,
                 r.collision_checks, r.narrow_phase_calls, r.time, r.path_length,
                 r.reach_error, r.pole_offset, r.state_queries, r.bool_pair_tests,
                 r.distance_pair_tests, r.cpu_time, r.setup_time
                 FROM runs r JOIN experiments e ON r.experimentid = e.id
                 JOIN plannerConfigs p ON r.plannerid = p.id""")
    got = {(row[0], row[1], row[2]): row[3:] for row in c.fetchall()}

    with open(os.path.join(out, "unwrap.csv")) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(ANGLES) * len(PLANNERS) * SEEDS == len(got), (len(rows), len(got))
    for row in rows:
        key = (float(row["angle_deg"]), row["planner"], int(row["seed"]))
        (solved, reason, checks, narrow, time, length, reach, pole, states, bool_tests,
         distance_tests, cpu, setup) = got[key]
        assert solved == int(row["success"]), (key, solved)
        assert reasons[reason] == row["failure_reason"], (key, reason)
        assert checks == int(row["collision_checks"]), (key, checks)
        assert narrow == int(row["narrow_phase_calls"]), (key, narrow)
        # The common cost units: the same counts in both files, non-zero for every run.
        assert states == int(row["state_queries"]) and states > 0, (key, states)
        assert bool_tests == int(row["bool_pair_tests"]), (key, bool_tests)
        assert distance_tests == int(row["distance_pair_tests"]), (key, distance_tests)
        assert bool_tests + distance_tests > 0, key
        for name, value in [("time_s", time), ("path_length", length),
                            ("reach_error_m", reach), ("pole_offset_m", pole),
                            ("cpu_time_s", cpu), ("setup_time_s", setup)]:
            assert close(value, float(row[name])), (key, name, value, row[name])
    print("ok: %d runs in %d OMPL logs match unwrap.csv" % (len(rows), len(logs)))


if __name__ == "__main__":
    main()
