#!/usr/bin/env bash
# check_log_conventions.sh FTSENSE ROOT: a log in a real logger's conventions, configured by JSON
# alone, gives what the same walk in ftsense's own conventions gives (issue 14).
#
# Simulates a 6 s walk (seed 1) and rewrites its log as a logger might have written it:
#   - the time column is PlotJuggler's `__time`, in nanoseconds since the epoch;
#   - the force pads are raw ADC counts: counts = (N - offset) / scale with scale = 0.25 N per
#     count and offset = -200 N (the count of an unloaded pad is 800);
# and the config (configs/suralp_robust.json) learns it by JSON alone: "time": {"column":
# "__time", "unit": "ns"} and per-input "scale" and "offset". Oracle: the outputs equal those of
# the original log and config, value by value, to 1e-6 N (the conversion rounds in the last bits),
# and the flags exactly. Then the conventions' errors: a wrong time column name says what to write.
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

/usr/bin/python3 - "$work/walk.csv" "$work/logger.csv" "$root/configs/suralp_robust.json" "$work/logger.json" <<'PY'
import csv, json, sys
walk, logger, config_in, config_out = sys.argv[1:5]
SCALE, OFFSET, EPOCH_NS = 0.25, -200.0, 1_763_900_000_000_000_000
rows = csv.reader(open(walk))
header = next(rows)
force = [h.endswith("/force_N") and not h.startswith("truth/") for h in header]
with open(logger, "w", newline="") as f:
    out = csv.writer(f, lineterminator="\n")
    out.writerow(["__time"] + header[1:])
    for row in rows:
        t_ns = EPOCH_NS + round(float(row[0]) * 1e9)
        cells = [str(t_ns)]
        for h, is_force, cell in zip(header[1:], force[1:], row[1:]):
            cells.append(repr((float(cell) - OFFSET) / SCALE) if is_force else cell)
        out.writerow(cells)
config = json.load(open(config_in))
config["time"] = {"column": "__time", "unit": "ns"}
for name in ("l_forces", "r_forces"):
    config["inputs"][name]["scale"] = SCALE
    config["inputs"][name]["offset"] = OFFSET
json.dump(config, open(config_out, "w"), indent=1)
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
        elif not (math.isnan(a) and math.isnan(b)):
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
  then ok "ns_time_and_raw_counts_equal_the_reference"; else fail "ns_time_and_raw_counts_equal_the_reference"; fi
else
  fail "ns_time_and_raw_counts_equal_the_reference: exit $?"; cat "$work/err"
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
