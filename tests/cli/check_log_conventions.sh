#!/usr/bin/env bash
# check_log_conventions.sh FTSENSE ROOT: a log in a real logger's conventions, configured by JSON
# alone, gives what the same walk in ftsense's own conventions gives (issue 14).
#
# Simulates a 6 s walk (seed 1) and rewrites its log as a logger might have written it:
#   - the time column is PlotJuggler's `__time`, in nanoseconds since the epoch;
#   - the force pads are raw ADC counts: counts = (N - offset) / scale with scale = 0.25 N per
#     count and offset = -200 N (the count of an unloaded pad is 800);
#   - orientations are quaternions instead of roll, pitch, yaw: the trunk's in x, y, z, w order,
#     the feet's in w, x, y, z order;
# and the config (configs/suralp_robust.json) learns it by JSON alone: "time": {"column":
# "__time", "unit": "ns"}, per-input "scale" and "offset", and an `orientation_to_rpy` stage per
# quaternion. Oracle: the outputs equal those of the original log and config, value by value, to
# 1e-6 N (the conversions round in the last bits), and the flags exactly.
# Then the same log without its contact plan and with no trunk orientation (many logs have
# neither): the robust config reads no gait plan, and `attitude_from_imu` gives the trunk's roll,
# pitch, yaw from its gyro and accelerometer; the fault-free walk raises no flag, with every channel's recovered RMS
# error within 10 % of the reference run's. Last, the conventions' errors: a wrong time column name says what to write.
set -u
ftsense=$1
root=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
ok() { echo "ok   $1"; passes=$((passes + 1)); }
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

sed 's/"duration_s": [0-9.]*/"duration_s": 6.0/' "$root/configs/scenarios/clean.json" > "$work/scenario.json"
"$ftsense" simulate --scenario "$work/scenario.json" --out "$work/walk.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }

/usr/bin/python3 - "$work/walk.csv" "$work/logger.csv" "$root/configs/suralp_robust.json" "$work/logger.json" "$work/no_plan" <<'PY'
import csv, json, math, sys
walk, logger, config_in, config_out, no_plan = sys.argv[1:6]
SCALE, OFFSET, EPOCH_NS = 0.25, -200.0, 1_763_900_000_000_000_000
ORIENTATIONS = {"base": "xyzw", "l_foot": "wxyz", "r_foot": "wxyz"}  # group -> quaternion order

def quaternion(roll, pitch, yaw):
    # R = Rz(yaw) Ry(pitch) Rx(roll) (plugins/biped/include/ftsense/biped/frames.hpp) as w, x, y, z.
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return {"w": cr * cp * cy + sr * sp * sy, "x": sr * cp * cy - cr * sp * sy,
            "y": cr * sp * cy + sr * cp * sy, "z": cr * cp * sy - sr * sp * cy}

rows = csv.reader(open(walk))
header = next(rows)
index = {h: i for i, h in enumerate(header)}
out_header = ["__time"]
for h in header[1:]:
    group = h.split("/")[0]
    if h.endswith("/rpy_roll_rad") and group in ORIENTATIONS:
        out_header += [f"{group}/q{c}" for c in ORIENTATIONS[group]]
    elif "/rpy_" in h and group in ORIENTATIONS:
        continue
    else:
        out_header.append(h)
with open(logger, "w", newline="") as f:
    out = csv.writer(f, lineterminator="\n")
    out.writerow(out_header)
    for row in rows:
        cells = {"__time": str(EPOCH_NS + round(float(row[0]) * 1e9))}
        for group, order in ORIENTATIONS.items():
            q = quaternion(*(float(row[index[f"{group}/rpy_{a}_rad"]]) for a in ("roll", "pitch", "yaw")))
            for c in order:
                cells[f"{group}/q{c}"] = repr(q[c])
        for h in out_header[1:]:
            if h in cells:
                continue
            cell = row[index[h]]
            cells[h] = repr((float(cell) - OFFSET) / SCALE) if h.endswith("/force_N") and not h.startswith("truth/") else cell
        out.writerow([cells[h] for h in out_header])

config = json.load(open(config_in))
config["time"] = {"column": "__time", "unit": "ns"}
for name in ("l_forces", "r_forces"):
    config["inputs"][name]["scale"] = SCALE
    config["inputs"][name]["offset"] = OFFSET
converters = []
for group, order in ORIENTATIONS.items():
    rpy_input = f"{group}_rpy"
    del config["inputs"][rpy_input]
    config["inputs"][f"{group}_quaternion"] = {"columns": [f"{group}/q{c}" for c in order], "unit": "1"}
    converters.append({"name": f"{group}_orientation", "plugin": "orientation_to_rpy",
                       "params": {"from": f"quaternion_{order}"},
                       "inputs": {"orientation": f"input.{group}_quaternion"}})
def rewire(value):
    if isinstance(value, list):
        return [rewire(v) for v in value]
    for group in ORIENTATIONS:
        if value == f"input.{group}_rpy":
            return f"{group}_orientation.rpy"
    return value
for stage in config["stages"]:
    stage["inputs"] = {port: rewire(wire) for port, wire in stage.get("inputs", {}).items()}
config["stages"] = converters + config["stages"]
json.dump(config, open(config_out, "w"), indent=1)

# Without a contact plan (the log below drops its columns; the config reads none) and without the
# trunk's orientation: attitude_from_imu estimates it from gyro and accelerometer.
del config["inputs"]["base_quaternion"]
config["stages"] = [s for s in config["stages"] if s["name"] != "base_orientation"]
config["inputs"]["imu_gyro"] = {"columns": ["imu/gyro_x_rad_s", "imu/gyro_y_rad_s", "imu/gyro_z_rad_s"], "unit": "rad/s"}
config["stages"].insert(0, {"name": "attitude", "plugin": "attitude_from_imu",
                            "inputs": {"gyro": "input.imu_gyro", "imu_acc": "input.imu_acc"}})
renamed = {"base_orientation.rpy": "attitude.rpy"}
for stage in config["stages"]:
    stage["inputs"] = {port: renamed.get(wire, wire) if isinstance(wire, str) else wire
                       for port, wire in stage["inputs"].items()}
json.dump(config, open(no_plan + ".json", "w"), indent=1)
with open(logger) as f, open(no_plan + ".csv", "w") as g:
    lines = csv.reader(f)
    head = next(lines)
    keep = [i for i, h in enumerate(head) if not h.startswith("plan/contact")]
    w = csv.writer(g, lineterminator="\n")
    w.writerow([head[i] for i in keep])
    for line in lines:
        w.writerow([line[i] for i in keep])
PY

"$ftsense" run --config "$root/configs/suralp_robust.json" --input "$work/walk.csv" --output "$work/reference.csv" > /dev/null \
  || { echo "FAIL: the reference run"; exit 1; }
if "$ftsense" run --config "$work/logger.json" --input "$work/logger.csv" --output "$work/logger_run.csv" > "$work/out" 2> "$work/err"; then
  if /usr/bin/python3 - "$work/reference.csv" "$work/logger_run.csv" <<'PY'
import csv, math, sys
ref, got = (list(csv.reader(open(p))) for p in sys.argv[1:3])
EPOCH_S = 1_763_900_000.0
assert ref[0] == got[0], f"headers differ: {ref[0][:4]} vs {got[0][:4]}"
worst, problems = 0.0, []
for r, g in zip(ref[1:], got[1:]):
    # Time: seconds since the epoch now, within the double's resolution there (0.24 us).
    if abs(float(g[0]) - EPOCH_S - float(r[0])) > 1e-6:
        problems.append(f"time {g[0]} is not {EPOCH_S} + {r[0]}")
    for name, a, b in zip(ref[0][1:], r[1:], g[1:]):
        a, b = float(a), float(b)
        if name.endswith("/fault") or name.endswith("/fault_type"):
            if a != b:
                problems.append(f"t = {r[0]}: {name} = {b}, not {a}")
        elif math.isnan(a) != math.isnan(b):
            problems.append(f"t = {r[0]}: {name} = {b}, not {a}")
        elif not math.isnan(a):
            worst = max(worst, abs(a - b))
if len(ref) != len(got):
    problems.append(f"{len(got)} rows, not {len(ref)}")
if worst > 1e-6:
    problems.append(f"values differ by up to {worst} N")
print(f"     largest difference from the reference run: {worst:.3g}")
for p in problems[:5]:
    print("     " + p)
sys.exit(1 if problems else 0)
PY
  then ok "ns_time_raw_counts_and_quaternions_equal_the_reference"; else fail "ns_time_raw_counts_and_quaternions_equal_the_reference"; fi
else
  fail "ns_time_raw_counts_and_quaternions_equal_the_reference: exit $?"; cat "$work/err"
fi

if "$ftsense" run --config "$work/no_plan.json" --input "$work/no_plan.csv" --output "$work/no_plan_run.csv" > "$work/out" 2> "$work/err"; then
  if /usr/bin/python3 - "$work/reference.csv" "$work/no_plan_run.csv" "$work/walk.csv" <<'PY'
import csv, math, sys
def load(path):
    rows = csv.reader(open(path))
    header = next(rows)
    return {h: i for i, h in enumerate(header)}, [[float(x) for x in r] for r in rows]
ref_col, ref = load(sys.argv[1])
col, got = load(sys.argv[2])
log_col, log = load(sys.argv[3])
problems = []
for ch in [h[:-len("/fault")] for h in col if h.endswith("/fault")]:
    flagged = [r[0] for r in got if r[col[ch + "/fault"]] != 0]
    if flagged:
        problems.append(f"{ch} flagged from t = {flagged[0]} s on a fault-free walk")
    truth = log_col["truth/" + ch + "/force_N"]
    err = math.sqrt(sum((g[col[ch + "/recovered_N"]] - l[truth]) ** 2 for g, l in zip(got, log)) / len(got))
    ref_err = math.sqrt(sum((r[ref_col[ch + "/recovered_N"]] - l[truth]) ** 2 for r, l in zip(ref, log)) / len(ref))
    print(f"     {ch}: recovered RMS error {err:.3f} N without plan and orientation, {ref_err:.3f} N with them")
    if not err <= 1.1 * ref_err:
        problems.append(f"{ch}: recovered RMS error {err:.3f} N, more than 1.1 x {ref_err:.3f} N")
for p in problems:
    print("     " + p)
sys.exit(1 if problems else 0)
PY
  then ok "no_contact_plan_nor_trunk_orientation"; else fail "no_contact_plan_nor_trunk_orientation"; fi
else
  fail "no_contact_plan_nor_trunk_orientation: exit $?"; cat "$work/err"
fi

# The original config on the logger's file: the error names the column and the config key to set.
"$ftsense" run --config "$root/configs/suralp_robust.json" --input "$work/logger.csv" > /dev/null 2> "$work/err"
status=$?
if [ $status -eq 2 ] && grep -q "the first column is '__time'.*\"time\": {\"column\": \"__time\"" "$work/err"; then
  ok "time_column_not_declared_says_how"
else
  fail "time_column_not_declared_says_how: exit $status"; cat "$work/err"
fi
# A time unit that is none of s, ms, us, ns; a scale of 0; a scale list of the wrong length.
/usr/bin/python3 - "$work/logger.json" "$work" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
bad = json.loads(json.dumps(config)); bad["time"]["unit"] = "min"
json.dump(bad, open(sys.argv[2] + "/bad_unit.json", "w"))
bad = json.loads(json.dumps(config)); bad["inputs"]["l_forces"]["scale"] = 0
json.dump(bad, open(sys.argv[2] + "/zero_scale.json", "w"))
bad = json.loads(json.dumps(config)); bad["inputs"]["l_forces"]["offset"] = [1, 2]
json.dump(bad, open(sys.argv[2] + "/short_offset.json", "w"))
PY
for case in "bad_unit:/time/unit = \"min\" is not one of s, ms, us, ns" \
            "zero_scale:/inputs/l_forces/scale = 0 would erase the signal" \
            "short_offset:/inputs/l_forces/offset: has 2 numbers for 4 columns"; do
  name=${case%%:*}
  message=${case#*:}
  "$ftsense" check --config "$work/$name.json" > /dev/null 2> "$work/err"
  status=$?
  if [ $status -eq 2 ] && grep -qF -- "$message" "$work/err"; then ok "$name"; else fail "$name: exit $status"; cat "$work/err"; fi
done
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
