#!/usr/bin/env bash
# check_told_sensors.sh FTSENSE CONFIG SCENARIO [CHANNEL:TYPE:MAX_DELAY_S ...]
# check_robust.sh with CONFIG told the scenario's force sensors as a user would: its
# contact_force_fdi stage gets the scenario's noise_std_N and resolution_N, and the config the
# scenario's log period (log_period_s, when given).
set -u
here=$(cd "$(dirname "$0")" && pwd)
ftsense=$1
config=$2
scenario=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$config" "$scenario" "$work/config.json" <<'PY' || { echo "FAIL: config"; exit 1; }
import json, sys
config = json.load(open(sys.argv[1]))
scenario = json.load(open(sys.argv[2]))
force = scenario["sensors"]["force"]
stages = [s for s in config["stages"] if s["plugin"] == "contact_force_fdi"]
assert len(stages) == 1, "one contact_force_fdi stage expected"
for key in ("noise_std_N", "resolution_N"):
    stages[0]["params"][key] = force[key]
if "log_period_s" in scenario:
    config["sample_period_s"] = scenario["log_period_s"]
config.pop("$schema", None)
json.dump(config, open(sys.argv[3], "w"), indent=1)
PY
bash "$here/check_robust.sh" "$ftsense" "$work/config.json" "$scenario" "$@"
