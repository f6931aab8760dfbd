#!/usr/bin/env bash
# check_bad_values.sh FTSENSE ROOT: bad values in a real-looking log, one table row each.
# Simulates a 12 s fault-free walk, calibrates the paper pipeline on it, then for every row of
# the table below replaces one column (or several, joined by +) by a bad value over a time
# window and runs the paper
# (configs/suralp.json) and the robust (configs/suralp_robust.json) pipelines over the result.
# What each row expects (docs/reliability.md):
#   invalid:CH  CH is flagged with type 8 (invalid) on every tick of the window; no other flag
#   not_ready   no channel is flagged anywhere, and inside the window the virtual value of every
#               loaded pad (measured > 50 N) is NaN: a fault of the virtual sensor's inputs is
#               not blamed on a force sensor. (The robust pipeline still knows that a pad its
#               kinematics puts in the air carries 0 N, so only loaded pads are checked.)
#   quiet       no channel is flagged anywhere
#   finite      the pipeline runs through (flags allowed: the input really is wrong)
# except the rows of a gait-plan column (plan/...) on the robust pipeline, which reads no plan:
# its output must be byte-identical to its run on the clean log;
# and every row: exit 0 and no NaN or Inf in any recovered signal, ever. Before the table, each
# pipeline runs the clean log twice: the outputs must be byte-identical (determinism).
set -u
ftsense=$1
root=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed 's/"duration_s": [0-9.]*/"duration_s": 12.0/' "$root/configs/scenarios/clean.json" > "$work/scenario.json"
"$ftsense" simulate --scenario "$work/scenario.json" --out "$work/clean.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }
"$ftsense" calibrate --config "$root/configs/suralp.json" --input "$work/clean.csv" --output "$work/thresholds.json" > /dev/null \
  || { echo "FAIL: calibrate"; exit 1; }

#      name          column               from  to    value  expectation
table="force_nan      r_foot/p2/force_N    6.0   7.0   nan    invalid:r_foot/p2
force_inf             l_foot/p3/force_N    6.0   6.3   inf    invalid:l_foot/p3
force_minus_inf       r_foot/p4/force_N    6.0   6.01  -inf   invalid:r_foot/p4
imu_nan               imu/acc_x_m_s2       6.0   6.5   nan    not_ready
imu_inf               imu/acc_z_m_s2       6.0   6.2   inf    not_ready
base_roll_inf         base/rpy_roll_rad    6.0   6.2   inf    not_ready
contact_plan_nan      plan/contact_l       6.0   6.2   nan    not_ready
foot_pos_nan          l_foot/pos_x_m       6.0   6.2   nan    quiet
planned_zmp_nan       plan/zmp_x_m         6.0   6.2   nan    quiet
zero_vertical_force   imu/acc_z_m_s2       6.0   6.2   0      finite
cop_far_outside       plan/zmp_y_m         6.0   7.0   2.0    quiet
planned_zmp_nan_3s    plan/zmp_x_m+plan/zmp_y_m 6.0 9.0 nan   quiet
contact_plan_all_0    plan/contact_l+plan/contact_r 6.0 7.0 0 not_ready
force_burst_1e12      r_foot/p2/force_N    6.0   6.2   1e12   invalid:r_foot/p2
imu_stuck_at_16g      imu/acc_z_m_s2       6.0   6.5   156.9  not_ready
foot_pos_1e6_m        l_foot/pos_x_m       6.0   6.2   1e6    quiet
contact_plan_minus_1  plan/contact_l       6.0   6.2   -1     not_ready
robot_lifted          l_foot/p1/force_N+l_foot/p2/force_N+l_foot/p3/force_N+l_foot/p4/force_N+r_foot/p1/force_N+r_foot/p2/force_N+r_foot/p3/force_N+r_foot/p4/force_N 6.0 6.2 0 finite"

passes=0
failures=0
# Determinism first: the same log and config give byte-identical output, for both pipelines.
for config in suralp suralp_robust; do
  "$ftsense" run --config "$root/configs/$config.json" --input "$work/clean.csv" --output "$work/a.csv" > /dev/null 2>&1
  "$ftsense" run --config "$root/configs/$config.json" --input "$work/clean.csv" --output "$work/b.csv" > /dev/null 2>&1
  if [ -s "$work/a.csv" ] && cmp -s "$work/a.csv" "$work/b.csv"; then
    echo "ok   deterministic/$config"; passes=$((passes + 1))
  else
    echo "FAIL deterministic/$config: two runs of the same log differ (or wrote nothing)"; failures=$((failures + 1))
  fi
done
while read -r name column from to value expect; do
  awk -F, -v OFS=, -v name="$column" -v t0="$from" -v t1="$to" -v val="$value" \
      'NR == 1 { n = split(name, want, "+"); for (i = 1; i <= NF; i++) for (k = 1; k <= n; k++) if ($i == want[k]) cols[++found] = i
                 if (found != n) exit 3; print; next }
       { if ($1 + 0 >= t0 && $1 + 0 < t1) for (k = 1; k <= found; k++) $(cols[k]) = val; print }' "$work/clean.csv" > "$work/bad.csv" \
    || { echo "FAIL $name: column $column not in the log"; failures=$((failures + 1)); continue; }
  for config in suralp suralp_robust; do
    thresholds=()
    [ "$config" = suralp ] && thresholds=(--thresholds "$work/thresholds.json")
    "$ftsense" run --config "$root/configs/$config.json" "${thresholds[@]}" --input "$work/bad.csv" \
        --output "$work/run.csv" > "$work/out" 2> "$work/err"
    status=$?
    if [ $status -ne 0 ]; then
      echo "FAIL $name/$config: exit $status"; cat "$work/err"; failures=$((failures + 1)); continue
    fi
    # The robust pipeline reads no gait plan: a bad plan column changes nothing of its output.
    if [ "$config" = suralp_robust ] && [[ "$column" == plan/* ]]; then
      "$ftsense" run --config "$root/configs/$config.json" --input "$work/clean.csv" --output "$work/clean_run.csv" \
          > /dev/null 2>&1
      if cmp -s "$work/run.csv" "$work/clean_run.csv"; then
        echo "ok   $name/$config (the plan is not read: output unchanged)"; passes=$((passes + 1))
      else
        echo "FAIL $name/$config: a plan column it does not read changed its output"; failures=$((failures + 1))
      fi
      continue
    fi
    if /usr/bin/python3 - "$work/run.csv" "$from" "$to" "$expect" "$name/$config" <<'PY'
import csv, math, sys
path, t0, t1, expect, label = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4], sys.argv[5]
rows = csv.reader(open(path))
header = next(rows)
channels = [h[:-len("/fault")] for h in header if h.endswith("/fault")]
col = {h: i for i, h in enumerate(header)}
problems = []
flagged_channels = set()
in_window = 0
for row in rows:
    t = float(row[0])
    inside = t0 <= t < t1
    in_window += inside
    for ch in channels:
        recovered = float(row[col[ch + "/recovered_N"]])
        if not math.isfinite(recovered):
            problems.append(f"t = {t}: {ch} recovered = {recovered}")
        flag, kind = float(row[col[ch + "/fault"]]), int(float(row[col[ch + "/fault_type"]]))
        if flag != 0:
            flagged_channels.add(f"{ch}:{kind}")
        virtual = float(row[col[ch + "/virtual_N"]])
        if expect.startswith("invalid:"):
            if ch == expect[len("invalid:"):] and inside and (flag != 1 or kind != 8):
                problems.append(f"t = {t}: {ch} not flagged invalid (fault {flag}, type {kind})")
            if ch != expect[len("invalid:"):] and flag != 0:
                problems.append(f"t = {t}: {ch} flagged (type {kind}) though only another channel is bad")
        elif expect in ("not_ready", "quiet") and flag != 0:
            problems.append(f"t = {t}: {ch} flagged (type {kind}): blamed for a fault of the virtual sensor's inputs")
        measured = float(row[col[ch + "/measured_N"]])
        if expect == "not_ready" and inside and measured > 50.0 and not math.isnan(virtual):
            problems.append(f"t = {t}: {ch} virtual = {virtual} while the virtual sensor cannot be ready (want NaN)")
if in_window == 0:
    problems.append("no row inside the window")
if expect == "finite":
    print(f"     {label}: flagged channels {sorted(flagged_channels) or 'none'}")
for p in problems[:5]:
    print(f"FAIL {label}: {p}")
if len(problems) > 5:
    print(f"FAIL {label}: ... {len(problems) - 5} more")
sys.exit(1 if problems else 0)
PY
    then
      echo "ok   $name/$config ($expect)"; passes=$((passes + 1))
    else
      failures=$((failures + 1))
    fi
  done
done <<< "$table"

# Silently blind no more (issue 15 finding 8): the IMU NaN for 1 s and a real +300 N offset on a
# pad meanwhile. The virtual sensor cannot judge the pad then, so no flag is right, but the run's
# summary must say that the channels were not judged, and for how long.
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "imu/acc_x_m_s2") a = i; if ($i == "r_foot/p2/force_N") f = i }; print; next }
  { if ($1 + 0 >= 6.0 && $1 + 0 < 7.0) { $a = "nan"; $f = $f + 300 } print }' "$work/clean.csv" > "$work/blind.csv"
for config in suralp suralp_robust; do
  thresholds=()
  [ "$config" = suralp ] && thresholds=(--thresholds "$work/thresholds.json")
  "$ftsense" run --config "$root/configs/$config.json" "${thresholds[@]}" --input "$work/blind.csv" > "$work/out" 2> "$work/err"
  # The paper pipeline's virtual sensor is out for the whole second; the robust one's only while
  # the pad is loaded, and its jump test may still catch the offset: either is said.
  expected="r_foot/p2[,:].*not judged for [0-9]+ ticks \([0-9.]+ s\), the longest stretch 1[.0-9]* s from t = 6 s: the virtual sensor was not ready"
  [ "$config" = suralp_robust ] && expected="r_foot/p2([,:].*not judged for [0-9]+ ticks .*from t = 6[.0-9]* s:|: fault first flagged at t = 6\.)"
  if grep -qE "$expected" "$work/out"; then
    echo "ok   imu_nan_with_offset/$config (said)"; passes=$((passes + 1))
  else
    echo "FAIL imu_nan_with_offset/$config: the summary says nothing of r_foot/p2 at t = 6 s:"; cat "$work/out"
    failures=$((failures + 1))
  fi
done
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
