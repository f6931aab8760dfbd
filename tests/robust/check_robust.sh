#!/usr/bin/env bash
# check_robust.sh FTSENSE CONFIG SCENARIO [CHANNEL:TYPE:MAX_DELAY_S ...]
# Simulates SCENARIO, runs CONFIG over it, and checks with `ftsense report`'s metrics that each
# listed channel is detected within MAX_DELAY_S with the named type (the type the flag shows
# most while the fault is active), and that there is no false alarm on any channel. With
# THRESHOLDS set in the environment, the run applies that calibration file (--thresholds).
set -u
ftsense=$1
config=$2
scenario=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$ftsense" simulate --scenario "$scenario" --out "$work/log.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }
"$ftsense" run --config "$config" --input "$work/log.csv" --output "$work/run.csv" \
  ${THRESHOLDS:+--thresholds "$THRESHOLDS"} > /dev/null || { echo "FAIL: run"; exit 1; }
"$ftsense" report --run "$work/run.csv" --truth "$work/log.csv" --out "$work/report" --no-figures > "$work/table" || { echo "FAIL: report"; exit 1; }
cat "$work/table"
"$ftsense" plugins --fault-types > "$work/fault_types" || { echo "FAIL: plugins --fault-types"; exit 1; }
/usr/bin/python3 - "$work/report/metrics.json" "$work/run.csv" "$work/log.csv" "$work/fault_types" "$@" <<'PY'
import csv, json, re, sys
metrics = json.load(open(sys.argv[1]))
expect = {a.split(":")[0]: (a.split(":")[1], float(a.split(":")[2])) for a in sys.argv[5:]}
# Code -> name, from the fault type table (include/ftsense/fault_type.hpp).
names = {int(m.group(1)): m.group(2) for m in re.finditer(r"^\| (\d+) \| `(\w+)` \|", open(sys.argv[4]).read(), re.M)}
assert names.get(0) == "none", "no fault type table from ftsense plugins --fault-types"
# The type shown most while the truth says the fault is active.
run = csv.DictReader(open(sys.argv[2])); log = csv.DictReader(open(sys.argv[3]))
counts = {}
for r, l in zip(run, log):
    for ch in expect:
        if float(l[f"truth/{ch}/fault"]) != 0:
            counts.setdefault(ch, {}).setdefault(int(float(r[f"{ch}/fault_type"])), 0)
            counts[ch][int(float(r[f"{ch}/fault_type"]))] += 1
passed = failed = 0
for m in metrics["channels"]:
    ch = m["channel"]
    if m["false_alarms"] != 0:
        print(f"FAIL {ch}: {m['false_alarms']} false alarms"); failed += 1
    else:
        passed += 1
    if ch in expect:
        want_type, max_delay = expect[ch]
        delay = m["detection_delay_s"]
        if delay is None or delay > max_delay:
            print(f"FAIL {ch}: detection delay {delay} s, expected <= {max_delay} s"); failed += 1
        else:
            passed += 1
        seen = dict(counts.get(ch, {0: 1}))
        if want_type == "saturation":
            # A clipped channel reads its true force below the ceiling: only the clipped ticks
            # show a fault, so the type is judged over the flagged ticks.
            seen = {k: v for k, v in seen.items() if k != 0} or {0: 1}
        shown = names[max(seen, key=seen.get)]
        if shown != want_type:
            print(f"FAIL {ch}: type shown most {shown}, expected {want_type} ({counts.get(ch)})"); failed += 1
        else:
            passed += 1
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
PY
