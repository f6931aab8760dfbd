#!/usr/bin/env bash
# check_calibrated.sh FTSENSE CONFIG CALIBRATION_SCENARIO RESOLUTION SCENARIO [CHANNEL:TYPE:MAX_DELAY_S ...]
# As a user with a new sensor suite: leave the sensors' noise and resolution open in CONFIG
# (contact_force_fdi's noise_std_N and resolution_N are taken out; signal_validator has none),
# simulate a fault-free CALIBRATION_SCENARIO, `ftsense calibrate` CONFIG on it, and check that
# every stage measuring the sensors found their quantisation step RESOLUTION and a noise within
# a factor 1.5 of the scenario's (signal_validator's noise_margin: the factor its tests hold
# their false-alarm targets within), below half a step where the scenario's is; then
# check_robust.sh on SCENARIO (another log) with those thresholds and parameters.
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
/usr/bin/python3 - "$config" "$work/config.json" <<'PY' || { echo "FAIL: config"; exit 1; }
import json, os, sys
config = json.load(open(sys.argv[1]))
for stage in config["stages"]:
    params = stage.get("params", {})
    if stage["plugin"] == "contact_force_fdi":
        for key in ("noise_std_N", "resolution_N"):
            params.pop(key, None)  # left to calibrate
    # A file the config names relative to itself (a URDF) stays found from the copy.
    if isinstance(params.get("urdf"), str) and not os.path.isabs(params["urdf"]):
        params["urdf"] = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), params["urdf"])
config.pop("$schema", None)
json.dump(config, open(sys.argv[2], "w"), indent=1)
PY
"$ftsense" simulate --scenario "$calibration" --out "$work/calibration.csv" --quiet > /dev/null || { echo "FAIL: simulate"; exit 1; }
"$ftsense" calibrate --config "$work/config.json" --input "$work/calibration.csv" --output "$work/thresholds.json" || { echo "FAIL: calibrate"; exit 1; }
/usr/bin/python3 - "$work/config.json" "$work/thresholds.json" "$resolution" "$calibration" <<'PY' || exit 1
import json, sys
config = json.load(open(sys.argv[1]))
calibrated = json.load(open(sys.argv[2]))["stages"]
want = float(sys.argv[3])
noise = json.load(open(sys.argv[4]))["sensors"]["force"]["noise_std_N"]
keys = {"signal_validator": ("resolution", "noise_std"), "contact_force_fdi": ("resolution_N", "noise_std_N")}
stages = [(s["name"], keys[s["plugin"]]) for s in config["stages"] if s["plugin"] in keys]
assert stages, "no signal_validator or contact_force_fdi stage in the config"
for name, (resolution_key, noise_key) in stages:
    params = calibrated[name]["params"]
    as_list = lambda v: v if isinstance(v, list) else [v]
    found, noise_found = as_list(params[resolution_key]), as_list(params[noise_key])
    if any(abs(q - want) > 1e-9 * max(want, 1.0) for q in found):
        print(f"FAIL: {name} {resolution_key} {found}, expected {want} on every channel"); sys.exit(1)
    if any(not (noise / 1.5 <= n <= 1.5 * noise) for n in noise_found):
        print(f"FAIL: {name} {noise_key} {noise_found}, expected within a factor 1.5 of {noise}"); sys.exit(1)
    # Where the scenario quantises coarser than its noise, what calibrate measures must say so.
    if noise < want / 2 and any(not (0 < n < want / 2) for n in noise_found):
        print(f"FAIL: {name} {noise_key} {noise_found}, expected in (0, {want / 2}) (below half a step)"); sys.exit(1)
    print(f"{name}: {resolution_key} {params[resolution_key]}, {noise_key} {params[noise_key]}")
PY
THRESHOLDS="$work/thresholds.json" bash "$here/check_robust.sh" "$ftsense" "$work/config.json" "$scenario" "$@"
