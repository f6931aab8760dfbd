"""Issue 16 acceptance 2: the Python module gives `ftsense run`'s numbers.

python3 test_matches_cli.py FTSENSE SOURCE_DIR
Simulates a short walk with a fault (offset_walk.json, fixed seed) and a fault-free one, runs
configs/suralp_robust.json over the first with `ftsense run` and with the module, and checks:
  - run_log: the same column names, and every value the same double as the CSV's cell (the CSV
    is written shortest-round-trip, so reading a cell gives back the very double written);
  - run_log(output=...): the same CSV bytes;
  - run_table over the log's columns as arrays (read by ftsense's own reader): the same doubles;
  - the offset channel is flagged (the comparison covers a fault, not only zeros);
and that calibrate (configs/suralp.json, on the fault-free walk) and report give what the
verbs `ftsense calibrate` and `ftsense report` write."""

import csv
import json
import os
import re
import struct
import subprocess
import sys
import tempfile

import numpy

import ftsense

FTSENSE, SOURCE = sys.argv[1], sys.argv[2]
HERE = os.path.dirname(os.path.abspath(__file__))
ROBUST = os.path.join(SOURCE, "configs", "suralp_robust.json")
PLAIN = os.path.join(SOURCE, "configs", "suralp.json")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def ftsense_cli(*args):
    result = subprocess.run([FTSENSE, *args], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("ftsense %s failed (%d):\n%s%s" % (args[0], result.returncode, result.stdout, result.stderr))
    return result.stdout


def bits(x):
    return struct.pack("<d", x)


def equal_to_csv(csv_path, table):
    """(header equal, number of cells, cells whose double differs, first difference)."""
    with open(csv_path, newline="") as f:
        rows = csv.reader(f)
        header = next(rows)
        if header != list(table):
            return False, 0, 0, "header %s != %s" % (header[:4], list(table)[:4])
        columns = [table[name] for name in header]
        cells = differ = 0
        first = ""
        for k, row in enumerate(rows):
            for c, cell in enumerate(row):
                cells += 1
                if k >= len(columns[c]) or bits(float(cell)) != bits(float(columns[c][k])):
                    differ += 1
                    if not first:
                        got = columns[c][k] if k < len(columns[c]) else "(no row)"
                        first = "row %d column %s: csv %s, python %r" % (k, header[c], cell, got)
        if len(columns[0]) != sum(1 for _ in open(csv_path)) - 1:
            return True, cells, differ + 1, "python has %d rows" % len(columns[0])
        return True, cells, differ, first


with tempfile.TemporaryDirectory() as work:
    log = os.path.join(work, "log.csv")
    clean = os.path.join(work, "clean.csv")
    ftsense_cli("simulate", "--scenario", os.path.join(HERE, "offset_walk.json"), "--out", log, "--quiet")
    ftsense_cli("simulate", "--scenario", os.path.join(HERE, "clean_walk.json"), "--out", clean, "--quiet")
    cli_run = os.path.join(work, "run.csv")
    ftsense_cli("run", "--config", ROBUST, "--input", log, "--output", cli_run)

    p = ftsense.Pipeline(ROBUST)
    py_run = os.path.join(work, "py_run.csv")
    table = p.run_log(log, output=py_run)
    header_ok, cells, differ, first = equal_to_csv(cli_run, table)
    check(header_ok, "run_log has the columns of ftsense run's CSV (%d columns)" % len(table))
    check(cells > 0 and differ == 0, "run_log: %d values, %d differ from ftsense run's CSV %s" % (cells, differ, first))
    with open(cli_run, "rb") as a, open(py_run, "rb") as b:
        check(a.read() == b.read(), "run_log(output=...) writes the bytes ftsense run writes")
    check(table.summary["ticks"] == len(table["time_s"]) and table.summary["gap_resets"] == 0,
          "run_log summary: %s ticks, no gap" % table.summary["ticks"])
    flagged = table["r_foot/p2/fault"]
    check(flagged.any() and not table["l_foot/p1/fault"].any(),
          "the offset channel r_foot/p2 is flagged (first at t = %s s), l_foot/p1 is not"
          % table.summary["first_fault_time_s"]["r_foot/p2"])

    log_columns = p.read_log(log)
    arrays = p.inputs_from(log_columns)
    check(set(arrays) == {i.name for i in p.inputs}, "inputs_from gives every input")
    by_arrays = p.run_table(arrays, time=log_columns["time_s"])
    header_ok, cells, differ, first = equal_to_csv(cli_run, by_arrays)
    check(header_ok and cells > 0 and differ == 0,
          "run_table over the log's arrays: %d values, %d differ from ftsense run's CSV %s" % (cells, differ, first))

    # The fault type names are ftsense's table (as `ftsense plugins --fault-types` prints it).
    listed = {int(m.group(1)): m.group(2)
              for m in re.finditer(r"^\| (\d+) \| `(\w+)` \|", ftsense_cli("plugins", "--fault-types"), re.M)}
    check(len(listed) > 2 and ftsense.FAULT_TYPES == listed, "FAULT_TYPES is the fault type table %s" % listed)
    check(ftsense.fault_type_name(table["r_foot/p2/fault_type"][-1]) == "offset",
          "r_foot/p2 ends typed offset (%s)" % ftsense.fault_type_name(table["r_foot/p2/fault_type"][-1]))

    # calibrate: the verb's thresholds file, from Python.
    cli_thresholds = os.path.join(work, "cli_thresholds.json")
    ftsense_cli("calibrate", "--config", PLAIN, "--input", clean, "--output", cli_thresholds)
    py_thresholds = ftsense.calibrate(PLAIN, clean)
    with open(cli_thresholds) as f:
        expected = json.load(f)
    check(py_thresholds == expected and py_thresholds["stages"]["detector"]["thresholds"],
          "calibrate gives ftsense calibrate's thresholds %s" % py_thresholds["stages"]["detector"]["thresholds"])
    try:
        ftsense.calibrate(ROBUST, clean)
        check(False, "calibrate of a config without threshold_detector raises")
    except ftsense.ConfigError as e:
        check("has no threshold_detector stage" in str(e) and e.problems[0][0] == ROBUST + ":/stages",
              "calibrate of a config without threshold_detector raises ConfigError at its /stages: " + str(e))

    # report: the metrics ftsense report writes, from Python.
    ftsense_cli("report", "--run", cli_run, "--truth", log, "--out", os.path.join(work, "cli_report"), "--no-figures")
    with open(os.path.join(work, "cli_report", "metrics.json")) as f:
        expected = json.load(f)
    r = ftsense.report(cli_run, truth=log, out=os.path.join(work, "py_report"), figures=False)
    check(r.metrics == expected, "report gives ftsense report's metrics.json")
    with open(os.path.join(work, "cli_report", "report.md")) as a, open(os.path.join(work, "py_report", "report.md")) as b:
        check(a.read() == b.read(), "report(out=...) writes ftsense report's report.md")
    delays = {m["channel"]: m["detection_delay_s"] for m in r.metrics["channels"]}
    check(delays.get("r_foot/p2") is not None, "report: r_foot/p2 detected after %s s" % delays.get("r_foot/p2"))

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("all checks passed")
