#!/usr/bin/env bash
# A user's program with its own plugin runs ftsense's verbs through the ftsense::app library
# (issue 16): `insole_fdi check | run | calibrate | inject | report` on the real insole walk, with
# the insole virtual sensor the `ftsense` program does not know. For a config of reference plugins
# only, `insole_fdi run` writes byte for byte what `ftsense run` writes.
#
# usage: test_insole_verbs.sh INSOLE_FDI FTSENSE EXAMPLE_DIR
set -u
insole=$1
ftsense=$2
example=$3
config="$example/config/insole_fdi.json"
walk="$example/data/GaCo01_01.csv"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passes=0
failures=0
check() {  # check NAME EXPECTED_STATUS ACTUAL_STATUS [grep-pattern file]...
  local name=$1 expected=$2 actual=$3
  shift 3
  local ok=1
  [ "$actual" -eq "$expected" ] || { echo "FAIL $name: exit $actual, expected $expected"; ok=0; }
  while [ $# -ge 2 ]; do
    grep -qE -- "$1" "$2" || { echo "FAIL $name: '$1' not in $(basename "$2"):"; sed 's/^/    /' "$2" | head -20; ok=0; }
    shift 2
  done
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}
# py NAME PYTHON-CODE: a check written in Python (exit 0 = ok); its output is the failure reason.
py() {
  local name=$1
  if /usr/bin/python3 -c "$2" > "$work/py.out" 2>&1; then passes=$((passes + 1)); echo "ok   $name"
  else failures=$((failures + 1)); echo "FAIL $name:"; sed 's/^/    /' "$work/py.out"; fi
}
channels="left/L1 left/L2 left/L3 left/L4 left/L5 left/L6 left/L7 left/L8 right/R1 right/R2 right/R3 right/R4 right/R5 right/R6 right/R7 right/R8"

# The program's plugins are the reference ones plus its own; ftsense's are not.
"$insole" plugins > "$work/out" 2> "$work/err"
check plugins_lists_its_own 0 $? "^insole_virtual_sensor$" "$work/out" "^low_pass$" "$work/out"
"$insole" check -c "$config" > "$work/out" 2> "$work/err"
check check_with_its_plugin 0 $? "^ok: .*insole_fdi.json: 2 inputs, 8 stages, 16 monitored channels$" "$work/out"
"$ftsense" check -c "$config" > "$work/out" 2> "$work/err"
check ftsense_does_not_know_it 2 $? "unknown plugin 'insole_virtual_sensor'" "$work/err"

# run on the recorded walk: every monitored column of every channel, every row, no alarm.
"$insole" run -c "$config" -i "$walk" -o "$work/run.csv" > "$work/out" 2> "$work/err"
check run 0 $? "^insole_fdi run: 12119 ticks, 16 channels -> .*run.csv$" "$work/out" "^  no channel flagged$" "$work/out"
header=$(head -1 "$work/run.csv")
missing=""
for ch in $channels; do
  for q in measured_N virtual_N fault_estimate_N recovered_N fault fault_type stance; do
    case ",$header," in *",$ch/$q,"*) ;; *) missing="$missing $ch/$q";; esac
  done
done
rows=$(($(wc -l < "$work/run.csv") - 1))
[ -z "$missing" ] && [ "$rows" -eq 12119 ] && { passes=$((passes + 1)); echo "ok   run_columns_and_rows"; } \
  || { failures=$((failures + 1)); echo "FAIL run_columns_and_rows: $rows rows; missing:$missing"; }
py run_virtual_sensor_ran "
import csv, math
rows = list(csv.DictReader(open('$work/run.csv')))
v = [float(r['left/L3/virtual_N']) for r in rows]
finite = [x for x in v if math.isfinite(x)]
assert len(finite) > 0.9 * len(v), f'{len(finite)} finite of {len(v)}'
assert max(finite) - min(finite) > 100, 'the virtual sensor does not follow the walk'
"

# calibrate: one threshold per channel, written where asked.
"$insole" calibrate -c "$config" -i "$walk" -o "$work/thresholds.json" > "$work/out" 2> "$work/err"
check calibrate 0 $? "^insole_fdi calibrate: detect: thresholds( [0-9.]+){16}$" "$work/out"
py calibrate_writes_thresholds "
import json
t = json.load(open('$work/thresholds.json'))['stages']['detect']['thresholds']
assert len(t) == 16 and all(x > 0 for x in t), t
"
"$insole" run -c "$config" -i "$walk" --thresholds "$work/thresholds.json" -o "$work/run_calibrated.csv" > "$work/out" 2> "$work/err"
check run_with_thresholds 0 $? "^insole_fdi run: 12119 ticks, 16 channels" "$work/out" "^  no channel flagged$" "$work/out"

# inject: +80 N on left/L3 from 50 s to 65 s, the column changed there only, truth columns added.
cat > "$work/faults.json" <<'JSON'
{"seed": 1, "channels": {"left/L3": "left/L3/force_N"},
 "faults": [{"channel": "left/L3", "type": "offset", "start_s": 50.0, "end_s": 65.0, "offset_N": 80}]}
JSON
"$insole" inject -i "$walk" --faults "$work/faults.json" -o "$work/injected.csv" > "$work/out" 2> "$work/err"
check inject 0 $? "^insole_fdi inject: 12119 rows, 1 fault\(s\); left/L3 \(left/L3/force_N\) faulty on 1500 rows" "$work/out"
py inject_changes_the_chosen_column "
import csv
walk = list(csv.DictReader(open('$walk')))
out = list(csv.DictReader(open('$work/injected.csv')))
assert len(walk) == len(out)
for a, b in zip(walk, out):
    t = float(a['time_s'])
    for k, v in a.items():
        if k != 'left/L3/force_N':
            assert float(b[k]) == float(v), (t, k)
    x, y = float(a['left/L3/force_N']), float(b['left/L3/force_N'])
    assert abs(y - (x + 80 if 50 <= t < 65 else x)) < 1e-9, (t, x, y)
    assert float(b['truth/left/L3/force_N']) == x
    assert float(b['truth/left/L3/fault']) == (2 if 50 <= t < 65 else 0), t
"

# run on the injected walk and report against its truth.
"$insole" run -c "$config" -i "$work/injected.csv" -o "$work/run_injected.csv" > "$work/out" 2> "$work/err"
check run_flags_the_fault 0 $? "^  left/L3: fault first flagged at t = 5[0-9.]+ s; fault types unclassified, offset$" "$work/out"
"$insole" report --run "$work/run_injected.csv" -t "$work/injected.csv" -o "$work/report" > "$work/out" 2> "$work/err"
check report 0 $? "^left/L3 +offset" "$work/out" "^detected 1 of 1 faulty channels" "$work/out"
py report_writes_metrics "
import json
m = json.load(open('$work/report/metrics.json'))
assert m['summary']['faulty_channels'] == 1 and m['summary']['detected'] == 1, m['summary']
l3 = [c for c in m['channels'] if c['channel'] == 'left/L3'][0]
assert l3['injected_type'] == 'offset' and 0 < l3['detection_delay_s'] < 15, l3
"
[ -s "$work/report/report.md" ] && { passes=$((passes + 1)); echo "ok   report_writes_markdown"; } \
  || { failures=$((failures + 1)); echo "FAIL report_writes_markdown"; }

# The library's conventions and messages, with the program's name.
"$insole" run -c "$config" -i "$work/missing.csv" > "$work/out" 2> "$work/err"
check missing_input_named 2 $? "^error: insole_fdi run: --input \(-i\) .*missing.csv: no such file" "$work/err"
"$insole" rnu > "$work/out" 2> "$work/err"
check unknown_verb 2 $? "^insole_fdi: unknown verb 'rnu'; did you mean 'run'" "$work/err"

# A config of reference plugins only: insole_fdi run and ftsense run write the same bytes.
cat > "$work/reference_only.json" <<'JSON'
{
  "description": "Heel pads of both feet against each other, reference plugins only.",
  "sample_period_s": 0.01,
  "inputs": {
    "left": {"columns": ["left/L1/force_N", "left/L2/force_N"], "unit": "N"},
    "right": {"columns": ["right/R1/force_N", "right/R2/force_N"], "unit": "N"}
  },
  "stages": [
    {"name": "residual", "plugin": "difference_residual", "inputs": {"measured": "input.left", "virtual": "input.right"}},
    {"name": "smooth", "plugin": "low_pass", "params": {"cutoff_hz": 0.1}, "inputs": {"signal": "residual.residual"}},
    {"name": "detect", "plugin": "threshold_detector", "params": {"thresholds": [60.0], "warmup_s": 2.0},
     "inputs": {"signal": "smooth.filtered"}}
  ],
  "monitor": {"channels": ["L1", "L2"], "measured": "input.left", "virtual": "input.right",
              "fault_estimate": "smooth.filtered", "recovered": "input.right",
              "fault": "detect.fault", "fault_type": "detect.fault_type"}
}
JSON
"$insole" run -c "$work/reference_only.json" -i "$work/injected.csv" -o "$work/a.csv" > "$work/a.out" 2> "$work/err"
status_a=$?
"$ftsense" run -c "$work/reference_only.json" -i "$work/injected.csv" -o "$work/b.csv" > "$work/b.out" 2> "$work/err"
status_b=$?
sed -i 's/^insole_fdi run: /ftsense run: /; s#/a.csv$#/b.csv#' "$work/a.out"
if [ $status_a -eq 0 ] && [ $status_b -eq 0 ] && cmp -s "$work/a.csv" "$work/b.csv" && cmp -s "$work/a.out" "$work/b.out"; then
  passes=$((passes + 1)); echo "ok   run_same_as_ftsense_run"
else
  failures=$((failures + 1)); echo "FAIL run_same_as_ftsense_run: exit $status_a / $status_b"; diff "$work/a.out" "$work/b.out"
fi

echo "insole_fdi verbs: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
