#!/usr/bin/python3
"""Runs the robust pipeline (configs/suralp_robust.json) on fault-free SURALP walks the demo does
not use, and reports the false alarms of each: the trial a new user makes before trusting it.

    tools/unseen_walks.py BUILD_BIN [--work DIR] [--duration S] [--jobs N]

BUILD_BIN holds ftsense and ftsense-sim (e.g. build/bin). 4 gaits x 4 sensor settings, each walk
seeded 300 + its number (printed), the config told each walk's sensors and log period as a user
would (noise_std_N, resolution_N, sample_period_s). Gaits (step length m, step time s, double
support ratio): 0.15/1.0/0.3, 0.25/0.7/0.15, 0.2/0.9/0.25, 0.18/0.75/0.2 (the demo walks
0.2/0.8/0.2 and a slower one). Sensors (log period s, noise N, resolution N): 0.001/1/0,
0.005/3/0, 0.002/2/2, 0.001/2/5. Exit 1 on any false alarm. About 10 s on 2 cores (ctest unseen_walks).
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GAITS = [(0.15, 1.0, 0.3), (0.25, 0.7, 0.15), (0.2, 0.9, 0.25), (0.18, 0.75, 0.2)]
SENSORS = [(0.001, 1.0, 0.0), (0.005, 3.0, 0.0), (0.002, 2.0, 2.0), (0.001, 2.0, 5.0)]


def walks(duration_s):
    number = 0
    for length, step, support in GAITS:
        for period, noise, resolution in SENSORS:
            number += 1
            scenario = {
                "name": f"unseen_{number}",
                "description": "fault-free walk for tools/unseen_walks.py",
                "duration_s": duration_s,
                "seed": 300 + number,
                "gait": {"step_length_m": length, "step_time_s": step, "double_support_ratio": support},
                "sensors": {"force": {"noise_std_N": noise, "resolution_N": resolution}},
                "faults": [],
            }
            if period != 0.001:
                scenario["log_period_s"] = period
            yield scenario


def told(config, scenario):
    """The config told the walk's force sensors and log period."""
    config = json.loads(json.dumps(config))
    config.pop("$schema", None)
    config["sample_period_s"] = scenario.get("log_period_s", 0.001)
    stages = [s for s in config["stages"] if s["plugin"] == "contact_force_fdi"]
    if len(stages) != 1:
        sys.exit("configs/suralp_robust.json: one contact_force_fdi stage expected")
    for key in ("noise_std_N", "resolution_N"):
        stages[0]["params"][key] = scenario["sensors"]["force"][key]
    return config


def trial(bin_dir, work, config, scenario):
    d = os.path.join(work, scenario["name"])
    os.makedirs(d, exist_ok=True)
    paths = {k: os.path.join(d, f) for k, f in
             (("scenario", "scenario.json"), ("config", "config.json"), ("log", "log.csv"), ("run", "run.csv"))}
    json.dump(scenario, open(paths["scenario"], "w"), indent=1)
    json.dump(told(config, scenario), open(paths["config"], "w"), indent=1)
    steps = [[os.path.join(bin_dir, "ftsense-sim"), "--scenario", paths["scenario"], "--out", paths["log"], "--quiet"],
             [os.path.join(bin_dir, "ftsense"), "run", "--config", paths["config"], "--input", paths["log"],
              "--output", paths["run"]],
             [os.path.join(bin_dir, "ftsense"), "report", "--run", paths["run"], "--truth", paths["log"],
              "--out", os.path.join(d, "report"), "--no-figures"]]
    for command in steps:
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            return scenario, None, f"{os.path.basename(command[0])} failed: {done.stderr.strip()[:300]}"
    metrics = json.load(open(os.path.join(d, "report", "metrics.json")))
    alarms = [(m["channel"], m["false_alarms"], m.get("false_alarm_time_s", 0.0))
              for m in metrics["channels"] if m["false_alarms"]]
    return scenario, alarms, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bin", help="directory holding ftsense and ftsense-sim")
    parser.add_argument("--work", help="where logs and runs go, kept (default: a temporary directory, removed)")
    parser.add_argument("--duration", type=float, default=25.0, help="seconds per walk (default 25)")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    config = json.load(open(os.path.join(ROOT, "configs", "suralp_robust.json")))
    if args.work:
        return run_all(args, config, args.work)
    with tempfile.TemporaryDirectory(prefix="unseen_walks_") as work:  # removed afterwards
        return run_all(args, config, work)


def run_all(args, config, work):
    print(f"work directory: {work}")
    failed = False
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        jobs = [pool.submit(trial, args.bin, work, config, s) for s in walks(args.duration)]
        for job in jobs:
            scenario, alarms, error = job.result()
            gait = scenario["gait"]
            force = scenario["sensors"]["force"]
            label = (f"{scenario['name']:10s} seed {scenario['seed']} gait {gait['step_length_m']}/"
                     f"{gait['step_time_s']}/{gait['double_support_ratio']} period {scenario.get('log_period_s', 0.001)} s "
                     f"noise {force['noise_std_N']} N resolution {force['resolution_N']} N")
            if error:
                print(f"{label}: ERROR {error}")
                failed = True
            elif alarms:
                print(f"{label}: {sum(a[1] for a in alarms)} false alarms ("
                      + ", ".join(f"{c} {n} x, {t:.2f} s" for c, n, t in alarms) + ")")
                failed = True
            else:
                print(f"{label}: 0 false alarms")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
