#!/usr/bin/env bash
# check_limb_inertia.sh FTSENSE CONFIG SCENARIO...
# The total vertical ground force F_z = m (R_wb f_imu)_z of CONFIG (the stage that feeds its `legs`
# stage, or its first total_ground_force or leg_force_split stage) against the simulator's truth
# (the sum of the truth pad forces), without and with its `legs` stage (limb_inertia_correction:
# each leg's mass as it moves with its foot, 7.1 kg of the 16 kg legs of the simulated SURALP;
# added after that stage when the config has none), on each fault-free
# SCENARIO: prints the RMS error of both after the first 2 s, per tick and low-passed at 10 Hz
# (the legs' bandwidth: above it the error is the accelerometer's white noise), and fails unless
# the correction removes at least a quarter of the low-passed error (the swinging legs' inertia
# is the largest error the trunk IMU leaves; docs/results.md, "The legs' inertia").
set -u
ftsense=$1; config=$2; shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
for scenario in "$@"; do
  name=$(basename "$scenario" .json)
  "$ftsense" simulate --scenario "$scenario" --out "$work/$name.csv" --quiet > /dev/null || { echo "FAIL: simulate $name"; exit 1; }
  # The config, with the legs' stage after the total force's unless it has one (`legs`), at the
  # log's sample period (as a user states it); the total force's wire is written to imu_wire.
  /usr/bin/python3 - "$config" "$work/$name.csv" "$work/legs.json" "$work/imu_wire" <<'PY' || { echo "FAIL: config"; exit 1; }
import csv, json, sys
config = json.load(open(sys.argv[1]))
with open(sys.argv[2]) as f:
    reader = csv.DictReader(f)
    times = [float(next(reader)["time_s"]) for _ in range(3)]
config["sample_period_s"] = round(times[2] - times[1], 9)
stages = config["stages"]
legs = [s for s in stages if s["name"] == "legs"]
if legs:  # configs/suralp_robust.json has it
    wire = legs[0]["inputs"]["total_force"]
else:
    at = next(i for i, s in enumerate(stages) if s["plugin"] in ("total_ground_force", "leg_force_split"))
    wire = stages[at]["name"] + ".total_force"
    stages.insert(at + 1, {"name": "legs", "plugin": "limb_inertia_correction",
                           "params": {"mass_kg": 114.0, "leg_effective_mass_kg": 7.1},
                           "inputs": {"total_force": wire,
                                      "foot_pos": ["input.l_foot_pos", "input.r_foot_pos"]}})
config.pop("$schema", None)
json.dump(config, open(sys.argv[3], "w"), indent=1)
open(sys.argv[4], "w").write(wire)
PY
  imu_wire=$(cat "$work/imu_wire")
  "$ftsense" run --config "$work/legs.json" --input "$work/$name.csv" --output "$work/${name}_run.csv" \
    --record "$imu_wire,legs.total_force" > /dev/null || { echo "FAIL: run $name"; exit 1; }
  /usr/bin/python3 - "$work/$name.csv" "$work/${name}_run.csv" "$name" "$imu_wire" <<'PY' || failed=1
import csv, math, sys
log = list(csv.DictReader(open(sys.argv[1])))
run = list(csv.DictReader(open(sys.argv[2])))
truth_columns = [c for c in log[0] if c.startswith("truth/") and c.endswith("/force_N")]
period = float(log[2]["time_s"]) - float(log[1]["time_s"])
# The legs move below 10 Hz (the stage's cutoff_hz); above it the error is the accelerometer's
# white noise, M sigma_a = 114 kg x 0.05 m/s^2 = 5.7 N per tick, which no model of the legs
# removes. The verdict judges the error low-passed at 10 Hz (first order, exp-discretised).
gain = 1.0 - math.exp(-2.0 * math.pi * 10.0 * period)
columns = {"imu": f"{sys.argv[4]}/2_N", "legs": "legs.total_force/2_N"}
sums = {"imu": 0.0, "legs": 0.0}
low_sums = {"imu": 0.0, "legs": 0.0}
low = {"imu": 0.0, "legs": 0.0}
n = 0
for row, out in zip(log, run):
    truth = sum(float(row[c]) for c in truth_columns)
    for stage in sums:
        error = float(out[columns[stage]]) - truth
        low[stage] += gain * (error - low[stage])
        if float(row["time_s"]) >= 2.0:
            sums[stage] += error ** 2
            low_sums[stage] += low[stage] ** 2
    if float(row["time_s"]) >= 2.0:
        n += 1
rms = {stage: math.sqrt(s / n) for stage, s in sums.items()}
low_rms = {stage: math.sqrt(s / n) for stage, s in low_sums.items()}
verdict = "ok  " if low_rms["legs"] <= 0.75 * low_rms["imu"] else "FAIL"
print(f"{verdict} {sys.argv[3]}: F_z error below 10 Hz {low_rms['imu']:.1f} N RMS from the trunk IMU alone, "
      f"{low_rms['legs']:.1f} N with the legs' inertia; per tick {rms['imu']:.1f} and {rms['legs']:.1f} N "
      f"({n} ticks)")
sys.exit(0 if verdict == "ok  " else 1)
PY
done
exit $failed
