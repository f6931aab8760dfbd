#!/usr/bin/python3
"""Injects one fault at a time into the real insole walk and reports what the insole pipeline made
of it: detected or not, the types it showed, the type shown most, and alarms on other sensors.

    tools/insole_fault_sweep.py INSOLE_FDI [--config C] [--walk W] [--work DIR]

INSOLE_FDI is the example's program (built by tests/insole/run_insole_example.sh, e.g.
/tmp/insw/build/insole_fdi). 8 sensors x 6 faults (offset +-60 N, drift +5 N/s, gain x1.6,
gain x0.5, frozen at the value read at the start), each from 55 s to 75 s, through
`insole_fdi inject` (deterministic: these fault types draw no random numbers) and `insole_fdi run`.
Exit 1 if a detected fault is shown most as a wrong type or a healthy sensor is flagged.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SENSORS = ["left/L1", "left/L2", "left/L4", "left/L6", "right/R1", "right/R3", "right/R4", "right/R7"]
FAULTS = [("offset", {"offset_N": 60}), ("offset", {"offset_N": -60}), ("drift", {"slope_N_s": 5}),
          ("gain", {"gain": 1.6}), ("gain", {"gain": 0.5}), ("frozen", {})]
START_S, END_S, GRACE_S = 55.0, 75.0, 5.0


def fault_type_names(program):
    """code -> name, from the program's own table (`plugins --fault-types`, fault_type.hpp)."""
    table = subprocess.run([program, "plugins", "--fault-types"], check=True, capture_output=True, text=True).stdout
    rows = re.findall(r"^\| (\d+) \| `([a-z_]+)` \|", table, re.M)
    if not rows:
        sys.exit(f"{program} plugins --fault-types printed no fault type table")
    return {int(code): name for code, name in rows}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("insole_fdi")
    parser.add_argument("--config", default=os.path.join(ROOT, "examples/insole_fdi/config/insole_fdi.json"))
    parser.add_argument("--walk", default=os.path.join(ROOT, "examples/insole_fdi/data/GaCo01_01.csv"))
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    codes = fault_type_names(args.insole_fdi)
    work = args.work or tempfile.mkdtemp(prefix="insole_sweep_")
    os.makedirs(work, exist_ok=True)
    print(f"one fault per run from {START_S:g} s to {END_S:g} s; work files in {work}")
    print(f"{'sensor':9} {'fault':18} {'detected':>9} {'typed':>7} {'not judged':>10}  {'type shown most':16} "
          f"{'types shown':18} other sensors flagged")
    print(f"{'':9} {'':18} {'after [s]':>9} {'[s]':>7} {'[s]':>10}")
    detected = typed_right = wrong = cross = runs = 0
    for sensor in SENSORS:
        for kind, size in FAULTS:
            runs += 1
            fault = {"channel": sensor, "type": kind, "start_s": START_S, "end_s": END_S, **size}
            spec = {"seed": 1, "channels": {sensor: sensor + "/force_N"}, "faults": [fault]}
            faults_path = os.path.join(work, f"faults{runs}.json")
            with open(faults_path, "w") as f:
                json.dump(spec, f)
            injected = os.path.join(work, f"injected{runs}.csv")
            out = os.path.join(work, f"run{runs}.csv")
            subprocess.run([args.insole_fdi, "inject", "-i", args.walk, "--faults", faults_path, "-o", injected],
                           check=True, stdout=subprocess.DEVNULL)
            subprocess.run([args.insole_fdi, "run", "-c", args.config, "-i", injected, "-o", out], check=True,
                           stdout=subprocess.DEVNULL)
            with open(out) as f:
                rows = list(csv.DictReader(f))
            period = float(rows[1]["time_s"]) - float(rows[0]["time_s"])
            first = None
            first_typed = None
            shown = Counter()
            others = set()
            not_judged = 0  # ticks the faulty sensor was `cannot_judge` during the fault
            for row in rows:
                t = float(row["time_s"])
                if START_S <= t < END_S and float(row[sensor + "/cannot_judge"]) != 0.0:
                    not_judged += 1
                for key, value in row.items():
                    if not key.endswith("/fault") or float(value) == 0.0:
                        continue
                    channel = key[: -len("/fault")]
                    if channel != sensor:
                        if START_S <= t < END_S + GRACE_S:
                            others.add(channel)
                        continue
                    if not START_S <= t < END_S:
                        continue
                    code = codes.get(int(float(row[sensor + "/fault_type"])), "?")
                    first = t if first is None else first
                    if code == kind and first_typed is None:
                        first_typed = t
                    shown[code] += 1
            label = kind + (" " + " ".join(f"{v:+g}" for v in size.values()) if size else "")
            most = shown.most_common(1)[0][0] if shown else "-"
            if first is not None:
                detected += 1
                typed_right += most == kind
                wrong += most != kind
            cross += len(others)
            det = f"{first - START_S:.2f}" if first is not None else "missed"
            typ = f"{first_typed - START_S:.2f}" if first_typed is not None else "-"
            types = ", ".join(c for c, _ in sorted(shown.items(), key=lambda kv: -kv[1]))
            judged = f"{not_judged * period:.2f}"
            print(f"{sensor:9} {label:18} {det:>9} {typ:>7} {judged:>10}  {most:16} {types:18} "
                  f"{', '.join(sorted(others)) or '-'}")
    print(f"\n{runs} runs: {detected} detected, {typed_right} of them shown most as the injected type, "
          f"{wrong} as another; {cross} healthy sensors flagged")
    return 1 if wrong or cross else 0


if __name__ == "__main__":
    sys.exit(main())
