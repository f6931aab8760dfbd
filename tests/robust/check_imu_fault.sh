#!/usr/bin/env bash
# check_imu_fault.sh FTSENSE CONFIG SCENARIO ONSET_S MAX_DELAY_S
# A fault of the virtual sensor's own input (the IMU), or one no channel can be isolated for, must be
# reported as such (fdi.unisolated)
# within MAX_DELAY_S of ONSET_S, and no force channel may be flagged.
set -u
ftsense=$1; config=$2; scenario=$3; onset=$4; max_delay=$5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$ftsense" simulate --scenario "$scenario" --out "$work/log.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }
"$ftsense" run --config "$config" --input "$work/log.csv" --output "$work/run.csv" --record fdi.unisolated > /dev/null || { echo "FAIL: run"; exit 1; }
/usr/bin/python3 - "$work/run.csv" "$onset" "$max_delay" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
onset, max_delay = float(sys.argv[2]), float(sys.argv[3])
first = next((float(r["time_s"]) for r in rows if float(r["fdi.unisolated"]) > 0 and float(r["time_s"]) >= 2.0), None)
flags = sum(float(r[k]) for r in rows for k in r if k.endswith("/fault"))
passed = failed = 0
if first is not None and onset <= first <= onset + max_delay:
    print(f"ok   unisolated raised {first - onset:.3f} s after the onset"); passed += 1
else:
    print(f"FAIL unisolated first raised at {first}, expected within {max_delay} s of {onset}"); failed += 1
if flags == 0:
    print("ok   no force channel blamed"); passed += 1
else:
    print(f"FAIL {flags:.0f} channel-ticks flagged"); failed += 1
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
PY
