#!/usr/bin/env bash
# SURALP's pads through the generic FDI parts alone (configs/suralp_generic.json, an experiment)
# beside the robust pipeline (configs/suralp_robust.json), on the demo's SURALP walks logged at
# 1 kHz without quantisation. The generic config is calibrated first, as its user would, on the
# demo's two fault-free walks (`ftsense calibrate`: the sensors' and the leave-one-out forces'
# noise, the residuals' statistics); the robust one is told its sensors (noise_std_N 2). Each walk
# is run and scored against the simulator's truth (`ftsense report`), and one row per walk is
# printed: false alarms, faults detected, types shown right, the worst recovered RMSE.
#
#   tools/suralp_generic.sh BUILD_BIN DEMO_DIR [WORK_DIR]
#
# BUILD_BIN holds ftsense (e.g. build/bin); DEMO_DIR is the output of `ftsense demo --output
# DEMO_DIR` (with its logs: not --no-logs); WORK_DIR (default: a temporary directory, removed)
# keeps the calibration, the runs and the reports. About a minute.
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
ftsense="$1/ftsense"
demo=$2
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -ge 3 ]; then
  work=$3
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
[ -x "$ftsense" ] || { echo "error: $ftsense is not an executable; build first (make demo)" >&2; exit 2; }
for log in clean clean_fast; do
  [ -f "$demo/$log.csv" ] || {
    echo "error: $demo/$log.csv is missing; run 'ftsense demo --output $demo' (without --no-logs) first" >&2
    exit 2
  }
done
generic="$root/configs/suralp_generic.json"
robust="$root/configs/suralp_robust.json"
"$ftsense" calibrate --config "$generic" --input "$demo/clean.csv,$demo/clean_fast.csv" \
  --output "$work/calibration.json" > "$work/calibrate.log"
walks=(clean clean_fast paper offsets drifts_frozen gains_bursts mixed frozen_noisy intermittent heal_after)
for walk in "${walks[@]}"; do
  [ -f "$demo/$walk.csv" ] || { echo "skipped $walk: $demo/$walk.csv is missing" >&2; continue; }
  "$ftsense" run --config "$generic" --input "$demo/$walk.csv" --thresholds "$work/calibration.json" \
    --output "$work/generic_$walk.csv" > /dev/null
  "$ftsense" report --run "$work/generic_$walk.csv" --truth "$demo/$walk.csv" --output "$work/generic_$walk" \
    --no-figures > /dev/null
  "$ftsense" run --config "$robust" --input "$demo/$walk.csv" --output "$work/robust_$walk.csv" > /dev/null
  "$ftsense" report --run "$work/robust_$walk.csv" --truth "$demo/$walk.csv" --output "$work/robust_$walk" \
    --no-figures > /dev/null
done
/usr/bin/python3 - "$work" "${walks[@]}" <<'EOF'
import json
import os
import sys

work, walks = sys.argv[1], sys.argv[2:]


def row(path):
    metrics = json.load(open(path))
    summary = metrics["summary"]
    faulty = [c for c in metrics["channels"] if c["injected_type"] != "-"]
    worst = max((c["recovered_rmse"] for c in faulty if c["recovered_rmse"] is not None), default=None)
    worst_text = "-" if worst is None else f"{worst:.1f}"
    detected = f"{summary['detected']}/{summary['faulty_channels']}" if faulty else "-"
    types = f"{summary['types_correct']}/{summary['faulty_channels']}" if faulty else "-"
    return f"{summary['false_alarms_after_warmup']} | {detected} | {types} | {worst_text}"


print("| walk | generic: false alarms | detected | types right | worst recovered RMSE [N] "
      "| robust: false alarms | detected | types right | worst recovered RMSE [N] |")
print("|---|---|---|---|---|---|---|---|---|")
for walk in walks:
    generic = os.path.join(work, f"generic_{walk}", "metrics.json")
    robust = os.path.join(work, f"robust_{walk}", "metrics.json")
    if os.path.exists(generic) and os.path.exists(robust):
        print(f"| {walk} | {row(generic)} | {row(robust)} |")
EOF
