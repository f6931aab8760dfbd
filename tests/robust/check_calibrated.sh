#!/usr/bin/env bash
# check_calibrated.sh FTSENSE CONFIG CALIBRATION_SCENARIO RESOLUTION SCENARIO [CHANNEL:TYPE:MAX_DELAY_S ...]
# As a user with a new sensor suite: simulate a fault-free CALIBRATION_SCENARIO, `ftsense
# calibrate` CONFIG on it, check that every signal_validator stage found the sensors'
# quantisation step RESOLUTION and a noise below half of it, then check_robust.sh on SCENARIO (another log) with those
# thresholds and parameters.
set -u
here=$(cd "$(dirname "$0")" && pwd)
ftsense=$1
config=$2
calibration=$3
resolution=$4
scenario=$5
shift 5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$ftsense" simulate --scenario "$calibration" --out "$work/calibration.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }
"$ftsense" calibrate --config "$config" --input "$work/calibration.csv" --output "$work/thresholds.json" || { echo "FAIL: calibrate"; exit 1; }
/usr/bin/python3 - "$config" "$work/thresholds.json" "$resolution" <<'PY' || exit 1
import json, sys
config = json.load(open(sys.argv[1]))
calibrated = json.load(open(sys.argv[2]))["stages"]
want = float(sys.argv[3])
stages = [s["name"] for s in config["stages"] if s["plugin"] == "signal_validator"]
assert stages, "no signal_validator stage in the config"
for name in stages:
    params = calibrated[name]["params"]
    found = params["resolution"]
    if any(abs(q - want) > 1e-9 * max(want, 1.0) for q in found):
        print(f"FAIL: {name} resolution {found}, expected {want} on every channel"); sys.exit(1)
    # The scenarios quantise coarser than the noise: what calibrate measures must say so.
    if want > 0 and any(not (0 < n < want / 2) for n in params["noise_std"]):
        print(f"FAIL: {name} noise_std {params['noise_std']}, expected in (0, {want / 2}) (below half a step)"); sys.exit(1)
    print(f"{name}: resolution {found}, noise_std {params['noise_std']}")
PY
THRESHOLDS="$work/thresholds.json" bash "$here/check_robust.sh" "$ftsense" "$config" "$scenario" "$@"
