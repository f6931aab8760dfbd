#!/usr/bin/python3
"""Runs the robust pipeline (configs/suralp_robust.json) on SURALP walks the demo does not use, and
reports the false alarms of each: the trial a new user makes before trusting it. With --robot
quadruped, configs/quadruped.json on crawls of the 13 kg quadruped the demo does not use. With
--robot light_biped, configs/suralp_robust.json told another biped's build (48 kg, legs 0.22 + 0.21 m,
a 0.18 x 0.11 m sole: the simulator's scenario "body") as its user would, on its walks: gaits
0.10/0.8/0.3, 0.15/0.6/0.15, 0.12/0.7/0.25, 0.08/0.65/0.2 (step height 0.03 m, feet 0.08 m off the
midline); sensors 0.001/0.5/0, 0.005/1.5/0, 0.002/1/1, 0.001/1/2.5; seeds 700 + (800 + with faults);
fault sizes for its 118 N per pad in single support: offsets +-20/30/50 N, drifts +-3/5/8 N/s, noise bursts 8/15/20 N,
spikes 50/120 N, saturation at 110/160 N.

With --robot heavy_biped, the same for a heavier build (180 kg, legs 0.40 + 0.38 m, a 0.30 x 0.18 m
sole, the ankle 0.15 m above it): gaits 0.25/1.0/0.3, 0.28/0.8/0.15, 0.30/0.9/0.25, 0.20/0.85/0.2
(step height 0.05 m, feet 0.12 m off the midline); sensors 0.001/2/0, 0.005/4/0, 0.002/3/3,
0.001/3/8; seeds 900 + (950 + with faults); fault sizes for its 441 N per pad in single support:
offsets +-60/100/160 N, drifts +-8/15/24 N/s, noise bursts 25/45/60 N, spikes 160/400 N,
saturation at 400/550 N. A config that takes a CoM height (configs/suralp_robust.json no longer
does) is told the simulator's planned one (plan/com_z_m of a 0.05 s walk), printed.

    tools/unseen_walks.py BUILD_BIN [--robot suralp|light_biped|heavy_biped|quadruped] [--gaits walks|stress]
                          [--faults] [--calibrate] [--config FILE] [--work DIR] [--duration S] [--jobs N]

BUILD_BIN holds ftsense and ftsense-sim (e.g. build/bin). 4 gaits x 4 sensor settings, each walk
seeded 300 + its number (printed), the config told each walk's sensors and log period as a user
would (noise_std_N, resolution_N, sample_period_s). Gaits (step length m, step time s, double
support ratio): 0.15/1.0/0.3, 0.25/0.7/0.15, 0.2/0.9/0.25, 0.18/0.75/0.2 (the demo walks
0.2/0.8/0.2 and a slower one). Sensors (log period s, noise N, resolution N): 0.001/1/0,
0.005/3/0, 0.002/2/2, 0.001/2/5. Exit 1 on any false alarm. About 10 s on 2 cores (ctest unseen_walks).

The quadruped's gaits (stride m, cycle s, step height m): 0.08/4.0/0.04, 0.12/3.0/0.05,
0.06/5.0/0.03, 0.10/3.5/0.04 (the demo crawls 0.08/4.0/0.04 only); its sensors (log period s,
noise N, resolution N): 0.001/0.5/0, 0.005/1/0, 0.002/0.3/0.5, 0.001/1/2; seeds 500 + its number
(600 + with faults); fault sizes for its 32 N per foot: offsets +-10/15/25 N, drifts +-2/3/5 N/s,
noise bursts 5/8 N, spikes 30/60 N, saturation at 30/40 N.

With --faults, each walk (seeded 400 + its number) carries two faults on two channels drawn by a
random.Random(FAULT_SEED) that is printed: one starting in 4-9 s, one in 13-18 s, each lasting 3-7
s, of a type among offset (+-40/60/100 N), drift (+-5/10/15 N/s), frozen (exact), frozen keeping
the sensor's noise, gain (x0.5/1.5/2), noise burst (15/30/40 N), spikes (100/250 N at 2/5 Hz),
saturation (at 250/350 N). Per fault: detection delay (all and loaded), the type shown most,
the recovered RMSE; then counts: detected, type shown right, recovered within 15 N RMS (issue
13's figure, for either robot). Exit 0 unless a run fails: a report, not a gate (its misses are
the open work, listed in docs/results.md).

With --gaits stress, the same sensor settings, seeds and faults on gaits unlike the walks': a biped
stepping in place (step length 0), walking slowly (2.5 s a step, double support 0.3), taking four
steps after 5 s of standing and then standing to the end, and walking fast (0.55 s a step, 0.7 s for
the heavy biped, which falls at 0.55 s; double support 0.1), each from its ordinary step (SURALP
0.2/0.8/0.2, the light biped 0.10/0.8/0.3, the heavy biped 0.25/1.0/0.3); the quadruped crawling
in place (stride 0, 4 s a cycle), slowly (8 s), one cycle after 5 s of standing, and fast (2 s).

With --fault-seed D and --seed-offset S, another draw: faults drawn by random.Random(D) (default
7) on walks seeded S more than above (default 0), to look for what the fixed draw no longer shows
(docs/results.md runs D 13, S 2000).

With --config, another config for the robot: `--robot quadruped --config quadruped_generic.json
--calibrate` judges the generic parts alone on the same crawls (docs/results.md).

With --calibrate, the config is not told the sensors' noise and resolution: as a user with a new
sensor suite would, it is calibrated first (`ftsense calibrate`, which measures both on a
fault-free log) on a fault-free walk of the same gait and sensors, seeded 1000 + the walk's seed,
and run with what calibrate wrote (`ftsense run --thresholds`). Only the log period is told.
"""
import argparse
import concurrent.futures
import json
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GAITS = [(0.15, 1.0, 0.3), (0.25, 0.7, 0.15), (0.2, 0.9, 0.25), (0.18, 0.75, 0.2)]
SENSORS = [(0.001, 1.0, 0.0), (0.005, 3.0, 0.0), (0.002, 2.0, 2.0), (0.001, 2.0, 5.0)]


FAULT_SEED = 7
BIPED_CHANNELS = [f"{foot}/p{pad}" for foot in ("l_foot", "r_foot") for pad in range(1, 5)]


def biped_gaits(steps, foot_half_spacing_m, step_height_m):
    """The gait of each (step length m, step time s, double support ratio) for a biped build."""
    return [{"step_length_m": a, "step_time_s": b, "double_support_ratio": c,
             "foot_half_spacing_m": foot_half_spacing_m, "step_height_m": step_height_m} for a, b, c in steps]

def biped_stress_gaits(length_m, step_time_s, double_support_ratio, slow_length_m, fast_step_time_s,
                       **build):
    """Gaits unlike the walks' (--gaits stress), from a biped's ordinary step: stepping in place,
    a slow walk (2.5 s a step), four steps then standing to the end, a fast walk with short double
    support (0.1 of a step)."""
    base = dict(build, step_length_m=length_m, step_time_s=step_time_s, double_support_ratio=double_support_ratio)
    return [dict(base, step_length_m=0.0),
            dict(base, step_length_m=slow_length_m, step_time_s=2.5, double_support_ratio=0.3),
            dict(base, num_steps=4, initial_stand_s=5.0),
            dict(base, step_time_s=fast_step_time_s, double_support_ratio=0.1)]


# Per robot: its config, channels, gaits, sensor settings, seeds and fault sizes (docstring).
ROBOTS = {
    "suralp": {
        "config": "suralp_robust.json",
        "channels": BIPED_CHANNELS,
        "gaits": [{"step_length_m": a, "step_time_s": b, "double_support_ratio": c} for a, b, c in GAITS],
        "stress_gaits": biped_stress_gaits(0.2, 0.8, 0.2, slow_length_m=0.15, fast_step_time_s=0.55),
        "sensors": SENSORS, "seeds": (300, 400),
        "offset_N": [40, 60, 100], "slope_N_s": [5, 10, 15], "noise_N": [15, 30, 40],
        "spike_N": [100, 250], "ceiling_N": [250, 350],
    },
    # A lighter biped of another build (sim/README.md "body"): 48 kg, shorter legs, a smaller sole.
    # Its config is configs/suralp_robust.json told this robot as a user would (adapt_to_body):
    # the pads at the sole's corners, the mass and the legs' effective mass (7.1 kg at 114 kg,
    # limb_inertia_correction.hpp, scaled with the mass: the same build). Fault sizes and sensors scaled to its 118 N per pad on one foot.
    "light_biped": {
        "config": "suralp_robust.json",
        "body": {"total_mass_kg": 48.0, "upper_leg_m": 0.22, "lower_leg_m": 0.21, "sole_ankle_m": 0.09,
                 "foot_length_m": 0.18, "foot_width_m": 0.11},
        "channels": BIPED_CHANNELS,
        "gaits": biped_gaits([(0.10, 0.8, 0.3), (0.15, 0.6, 0.15), (0.12, 0.7, 0.25), (0.08, 0.65, 0.2)], 0.08, 0.03),
        "stress_gaits": biped_stress_gaits(0.10, 0.8, 0.3, slow_length_m=0.10, fast_step_time_s=0.55,
                                           foot_half_spacing_m=0.08, step_height_m=0.03),
        "sensors": [(0.001, 0.5, 0.0), (0.005, 1.5, 0.0), (0.002, 1.0, 1.0), (0.001, 1.0, 2.5)], "seeds": (700, 800),
        "offset_N": [20, 30, 50], "slope_N_s": [3, 5, 8], "noise_N": [8, 15, 20],
        "spike_N": [50, 120], "ceiling_N": [110, 160],
    },
    # A heavier biped of another build: 180 kg, longer legs, a larger sole, noisier sensors. Told to
    # configs/suralp_robust.json as the light biped is; sizes scaled to its 441 N per pad on one foot.
    "heavy_biped": {
        "config": "suralp_robust.json",
        "body": {"total_mass_kg": 180.0, "upper_leg_m": 0.40, "lower_leg_m": 0.38, "sole_ankle_m": 0.15,
                 "foot_length_m": 0.30, "foot_width_m": 0.18},
        "channels": BIPED_CHANNELS,
        "gaits": biped_gaits([(0.25, 1.0, 0.3), (0.28, 0.8, 0.15), (0.30, 0.9, 0.25), (0.20, 0.85, 0.2)], 0.12, 0.05),
        # Its fast gait is slower than the others': at 0.55 s a step the simulated robot falls.
        "stress_gaits": biped_stress_gaits(0.25, 1.0, 0.3, slow_length_m=0.25, fast_step_time_s=0.7,
                                           foot_half_spacing_m=0.12, step_height_m=0.05),
        "sensors": [(0.001, 2.0, 0.0), (0.005, 4.0, 0.0), (0.002, 3.0, 3.0), (0.001, 3.0, 8.0)], "seeds": (900, 950),
        "offset_N": [60, 100, 160], "slope_N_s": [8, 15, 24], "noise_N": [25, 45, 60],
        "spike_N": [160, 400], "ceiling_N": [400, 550],
    },
    "quadruped": {
        "config": "quadruped.json",
        "channels": ["lf_foot", "rf_foot", "lh_foot", "rh_foot"],
        "gaits": [{"stride_m": a, "cycle_s": b, "step_height_m": c}
                  for a, b, c in [(0.08, 4.0, 0.04), (0.12, 3.0, 0.05), (0.06, 5.0, 0.03), (0.10, 3.5, 0.04)]],
        # Crawling in place, a slow crawl, one cycle then standing, a fast crawl.
        "stress_gaits": [{"stride_m": 0.0, "cycle_s": 4.0, "step_height_m": 0.04},
                         {"stride_m": 0.08, "cycle_s": 8.0, "step_height_m": 0.04},
                         {"stride_m": 0.08, "cycle_s": 4.0, "step_height_m": 0.04, "num_cycles": 1, "initial_stand_s": 5.0},
                         {"stride_m": 0.10, "cycle_s": 2.0, "step_height_m": 0.04}],
        "sensors": [(0.001, 0.5, 0.0), (0.005, 1.0, 0.0), (0.002, 0.3, 0.5), (0.001, 1.0, 2.0)], "seeds": (500, 600),
        "offset_N": [10, 15, 25], "slope_N_s": [2, 3, 5], "noise_N": [5, 8],
        "spike_N": [30, 60], "ceiling_N": [30, 40],
    },
}


def draw_fault(rng, robot, channel, start_s, noise_std_N):
    """One fault of a type drawn by rng (the module docstring's list)."""
    kind = rng.choice(["offset", "drift", "frozen", "gain", "noise", "spikes", "saturation", "frozen_noisy"])
    fault = {"channel": channel, "start_s": start_s, "end_s": round(start_s + rng.uniform(3.0, 7.0), 2)}
    sign = rng.choice([-1, 1])
    if kind == "offset":
        fault.update(type="offset", offset_N=sign * rng.choice(robot["offset_N"]))
    elif kind == "drift":
        fault.update(type="drift", slope_N_s=sign * rng.choice(robot["slope_N_s"]))
    elif kind == "frozen":
        fault.update(type="frozen")
    elif kind == "frozen_noisy":
        fault.update(type="frozen", std_N=noise_std_N)
    elif kind == "gain":
        fault.update(type="gain", gain=rng.choice([0.5, 1.5, 2.0]))
    elif kind == "noise":
        fault.update(type="noise", std_N=rng.choice(robot["noise_N"]))
    elif kind == "spikes":
        fault.update(type="spikes", amplitude_N=rng.choice(robot["spike_N"]), rate_hz=rng.choice([2, 5]))
    else:
        fault.update(type="saturation", max_N=rng.choice(robot["ceiling_N"]), min_N=0.0)
    return fault


def walks(robot_name, duration_s, with_faults, gaits="walks", fault_seed=FAULT_SEED, seed_offset=0):
    robot = ROBOTS[robot_name]
    channels = robot["channels"]
    rng = random.Random(fault_seed)
    number = 0
    for gait in robot["stress_gaits" if gaits == "stress" else "gaits"]:
        for period, noise, resolution in robot["sensors"]:
            number += 1
            faults = []
            if with_faults:
                first = rng.choice(channels)
                second = rng.choice([c for c in channels if c != first])
                faults = [draw_fault(rng, robot, first, round(rng.uniform(4.0, 9.0), 2), noise),
                          draw_fault(rng, robot, second, round(rng.uniform(13.0, 18.0), 2), noise)]
            scenario = {
                "name": f"unseen_{number}",
                "description": "walk for tools/unseen_walks.py",
                "duration_s": duration_s,
                "seed": seed_offset + robot["seeds"][1 if with_faults else 0] + number,
                "gait": gait,
                "sensors": {"force": {"noise_std_N": noise, "resolution_N": resolution}},
                "faults": faults,
            }
            if "body" in robot:
                scenario["body"] = robot["body"]
            elif robot_name != "suralp":
                scenario["robot"] = robot_name
            if period != 0.001:
                scenario["log_period_s"] = period
            yield scenario


def told(config, scenario, sensors=True):
    """The config told the walk's log period and (unless sensors is False) its force sensors."""
    config = json.loads(json.dumps(config))
    config.pop("$schema", None)
    config["sample_period_s"] = scenario.get("log_period_s", 0.001)
    stages = [s for s in config["stages"] if s["plugin"] == "contact_force_fdi"]
    if not stages and not sensors:
        return config  # a config of generic parts: calibrate measures what they use
    if len(stages) != 1:
        sys.exit("the config: one contact_force_fdi stage expected")
    for key in ("noise_std_N", "resolution_N"):
        if sensors:
            stages[0]["params"][key] = scenario["sensors"]["force"][key]
        else:
            stages[0]["params"].pop(key, None)  # left to `ftsense calibrate`
    return config


def planned_com_height(bin_dir, work, robot):
    """The CoM height the simulator's walking planner holds for this build (plan/com_z_m of a
    0.05 s walk): what the robot's own planner would tell its user."""
    scenario = {"name": "com_height_probe", "description": "the planned CoM height of this build",
                "duration_s": 0.05, "seed": 1, "body": robot["body"], "gait": robot["gaits"][0], "faults": []}
    path, log = os.path.join(work, "com_height_probe.json"), os.path.join(work, "com_height_probe.csv")
    json.dump(scenario, open(path, "w"), indent=1)
    done = subprocess.run([os.path.join(bin_dir, "ftsense-sim"), "--scenario", path, "--out", log, "--quiet"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"the CoM height probe failed: ftsense-sim: {done.stderr.strip()[:300]}")
    with open(log) as f:
        header, first = f.readline().strip().split(","), f.readline().strip().split(",")
    return round(float(first[header.index("plan/com_z_m")]), 3)


def adapt_to_body(config, robot, com_height_m):
    """configs/suralp_robust.json told another biped's build, as its user would: the sole's pads,
    the mass, the legs' effective mass (the default build's 7.1 of 114 kg) and, for a config that
    takes one, the CoM height."""
    config = json.loads(json.dumps(config))
    body = robot["body"]
    gravity = 9.806
    half_length, half_width = body["foot_length_m"] / 2, body["foot_width_m"] / 2
    config["definitions"]["sole_pads"] = [[half_length, half_width], [half_length, -half_width],
                                          [-half_length, half_width], [-half_length, -half_width]]
    mass = body["total_mass_kg"]
    for stage in config["stages"]:
        params = stage.get("params", {})
        if "com_height_m" in params:
            params["com_height_m"] = com_height_m
        if "mass_kg" in params:
            params["mass_kg"] = mass
        if "leg_effective_mass_kg" in params:
            params["leg_effective_mass_kg"] = round(7.1 * mass / 114.0, 3)
        if "weight_N" in params:
            params["weight_N"] = round(mass * gravity, 2)
    return config


CALIBRATION_SEED_OFFSET = 1000


def trial(bin_dir, work, config, scenario, calibrate=False):
    d = os.path.join(work, scenario["name"])
    os.makedirs(d, exist_ok=True)
    paths = {k: os.path.join(d, f) for k, f in
             (("scenario", "scenario.json"), ("config", "config.json"), ("log", "log.csv"), ("run", "run.csv"),
              ("calibration_scenario", "calibration_scenario.json"), ("calibration_log", "calibration_log.csv"),
              ("calibration", "calibration.json"))}
    json.dump(scenario, open(paths["scenario"], "w"), indent=1)
    json.dump(told(config, scenario, sensors=not calibrate), open(paths["config"], "w"), indent=1)
    sim = os.path.join(bin_dir, "ftsense-sim")
    ftsense = os.path.join(bin_dir, "ftsense")
    steps = []
    thresholds = []
    if calibrate:
        fault_free = dict(scenario, name=scenario["name"] + "_calibration", faults=[],
                          seed=scenario["seed"] + CALIBRATION_SEED_OFFSET)
        json.dump(fault_free, open(paths["calibration_scenario"], "w"), indent=1)
        steps += [[sim, "--scenario", paths["calibration_scenario"], "--out", paths["calibration_log"], "--quiet"],
                  [ftsense, "calibrate", "--config", paths["config"], "--input", paths["calibration_log"],
                   "--output", paths["calibration"]]]
        thresholds = ["--thresholds", paths["calibration"]]
    steps += [[sim, "--scenario", paths["scenario"], "--out", paths["log"], "--quiet"],
              [ftsense, "run", "--config", paths["config"], "--input", paths["log"],
               "--output", paths["run"]] + thresholds,
              [ftsense, "report", "--run", paths["run"], "--truth", paths["log"],
               "--out", os.path.join(d, "report"), "--no-figures"]]
    for command in steps:
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            return scenario, None, f"{os.path.basename(command[0])} failed: {done.stderr.strip()[:300]}"
    if calibrate:
        stages = json.load(open(paths["calibration"]))["stages"].values()
        params = [stage["params"] for stage in stages if "noise_std_N" in stage.get("params", {})]
        # A config of generic parts: the first stage's measured noise and resolution, the largest.
        params += [{"noise_std_N": max(p["noise_std"]), "resolution_N": max(p["resolution"])}
                   for p in (stage.get("params", {}) for stage in stages) if "noise_std" in p and "resolution" in p]
        scenario = dict(scenario, calibrated=params[0] if params else {})
    metrics = json.load(open(os.path.join(d, "report", "metrics.json")))
    return scenario, metrics, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bin", help="directory holding ftsense and ftsense-sim")
    parser.add_argument("--work", help="where logs and runs go, kept (default: a temporary directory, removed)")
    parser.add_argument("--duration", type=float, default=25.0, help="seconds per walk (default 25)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--faults", action="store_true", help="two faults per walk (a report, not a gate)")
    parser.add_argument("--robot", choices=sorted(ROBOTS), default="suralp")
    parser.add_argument("--gaits", choices=["walks", "stress"], default="walks",
                        help="the robot's ordinary gaits, or gaits unlike them: in place, slow, a short walk "
                             "then standing, fast (default walks)")
    parser.add_argument("--fault-seed", type=int, default=FAULT_SEED,
                        help=f"seed of the faults' draw (default {FAULT_SEED}, the draw docs/results.md reports)")
    parser.add_argument("--seed-offset", type=int, default=0, help="added to every walk's seed (default 0)")
    parser.add_argument("--calibrate", action="store_true",
                        help="measure the sensors' noise and resolution with ftsense calibrate, not told")
    parser.add_argument("--config", help="another config for the robot (a path, or a name under configs/), e.g. "
                                         "quadruped_generic.json; one without a contact_force_fdi stage needs "
                                         "--calibrate (it measures every statistic it uses)")
    args = parser.parse_args()
    if args.config and "body" in ROBOTS[args.robot]:
        parser.error("--config: only for the robots the configs describe as they are (suralp, quadruped)")
    if args.work:
        os.makedirs(args.work, exist_ok=True)
        return run_all(args, robot_config(args, args.work), args.work)
    with tempfile.TemporaryDirectory(prefix="unseen_walks_") as work:  # removed afterwards
        return run_all(args, robot_config(args, work), work)


def robot_config(args, work):
    """The robot's config; another biped's build is told its own numbers (adapt_to_body)."""
    robot = ROBOTS[args.robot]
    path = os.path.join(ROOT, "configs", robot["config"])
    if args.config:
        path = args.config if os.path.exists(args.config) else os.path.join(ROOT, "configs", args.config)
        print(f"config: {path}")
    config = json.load(open(path))
    # Files the config names relative to itself (a URDF) stay found from the work directory.
    for stage in config["stages"]:
        urdf = stage.get("params", {}).get("urdf")
        if isinstance(urdf, str) and not os.path.isabs(urdf):
            stage["params"]["urdf"] = os.path.join(os.path.dirname(os.path.abspath(path)), urdf)
    if not any(s["plugin"] == "contact_force_fdi" for s in config["stages"]) and not args.calibrate:
        sys.exit(f"{path} has no contact_force_fdi stage to tell the sensors: give --calibrate")
    if "body" in robot:
        com_height_m = None  # asked of the planner only by a config that takes a CoM height
        if any("com_height_m" in s.get("params", {}) for s in config["stages"]):
            com_height_m = planned_com_height(args.bin, work, robot)
            print(f"planned CoM height of this build: {com_height_m} m")
        config = adapt_to_body(config, robot, com_height_m)
    return config


def fault_line(m):
    """A faulty channel's metrics in one line."""
    def seconds(key):
        return "-" if m.get(key) is None else f"{m[key]:.3f} s"
    rmse = m.get("recovered_rmse")
    return (f"{m['channel']} {m['injected_type']} from {m['onset_s']:.2f} s: found after {seconds('detection_delay_s')} "
            f"({seconds('loaded_delay_s')} loaded), shown {m.get('shown_type') or '-'}, recovered "
            + ("-" if rmse is None else f"{rmse:.1f} N RMS"))


def run_all(args, config, work):
    print(f"work directory: {work}")
    if args.faults:
        print(f"faults drawn by random.Random({args.fault_seed})")
    if args.calibrate:
        print(f"sensors not told: calibrated on a fault-free walk each, seeded {CALIBRATION_SEED_OFFSET} + its seed")
    failed = False
    alarm_total = walks_with_alarms = 0
    faulty = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        jobs = [pool.submit(trial, args.bin, work, config, s, args.calibrate)
                for s in walks(args.robot, args.duration, args.faults, args.gaits, args.fault_seed, args.seed_offset)]
        for job in jobs:
            scenario, metrics, error = job.result()
            gait = scenario["gait"]
            force = scenario["sensors"]["force"]
            label = (f"{scenario['name']:10s} seed {scenario['seed']} gait {'/'.join(str(v) for v in gait.values())} "
                     f"period {scenario.get('log_period_s', 0.001)} s "
                     f"noise {force['noise_std_N']} N resolution {force['resolution_N']} N")
            if "calibrated" in scenario:
                found = scenario["calibrated"]
                label += (f" (calibrated {found.get('noise_std_N', float('nan')):.2f} N, "
                          f"{found.get('resolution_N', float('nan')):g} N)")
            if error:
                print(f"{label}: ERROR {error}")
                failed = True
                continue
            alarms = [(m["channel"], m["false_alarms"], m.get("false_alarm_time_s", 0.0))
                      for m in metrics["channels"] if m["false_alarms"]]
            count = sum(a[1] for a in alarms)
            alarm_total += count
            walks_with_alarms += 1 if count else 0
            text = f"{count} false alarms" + (" (" + ", ".join(f"{c} {n} x, {t:.2f} s" for c, n, t in alarms) + ")" if alarms else "")
            print(f"{label}: {text}")
            for m in metrics["channels"]:
                if m.get("onset_s") is not None:
                    faulty.append(m)
                    print(f"    {fault_line(m)}")
    print(f"false alarms: {alarm_total} on {walks_with_alarms} of {len(jobs)} walks")
    if args.faults:
        n = len(faulty)
        detected = sum(1 for m in faulty if m.get("detection_delay_s") is not None)
        typed = sum(1 for m in faulty if m.get("type_correct"))
        recovered = sum(1 for m in faulty if m.get("recovered_rmse") is not None and m["recovered_rmse"] <= 15.0)
        print(f"faults: {n}; detected {detected}; type shown right {typed}; recovered within 15 N RMS {recovered}")
        return 1 if failed else 0
    return 1 if failed or alarm_total else 0


if __name__ == "__main__":
    sys.exit(main())
