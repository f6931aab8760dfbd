#!/usr/bin/env bash
# Where a pipeline stands on issue 13's conditions (not a ctest: it prints, it does not judge).
# Simulates each scenario of configs/scenarios/ made for them (quantised forces, 200 / 500 Hz logs,
# frozen outputs that keep their noise, intermittent faults, healthy again after a burst), runs
# the pipeline with its sample period set to the scenario's log period (and the force sensors'
# resolution, when the scenario quantises them), and prints the report's
# summary line per scenario.
# usage: conditions_baseline.sh FTSENSE ROOT WORKDIR [CONFIG]   (CONFIG: configs/suralp_robust.json)
set -euo pipefail
ftsense=$1
root=$2
work=$3
config=${4:-$root/configs/suralp_robust.json}
mkdir -p "$work"
for s in clean_quantised_1N clean_quantised_5N quantised_1N quantised_5N clean_200hz clean_500hz faults_200hz \
         faults_500hz frozen_noisy intermittent heal_after; do
  scenario="$root/configs/scenarios/$s.json"
  period=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('log_period_s', 0.001))" "$scenario")
  /usr/bin/python3 - "$config" "$period" "$work/config_$s.json" "$scenario" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
c["sample_period_s"] = float(sys.argv[2])
# The user knows the sensors' resolution: a quantised scenario's config says it.
resolution = json.load(open(sys.argv[4])).get("sensors", {}).get("force", {}).get("resolution_N")
for st in c["stages"]:
    if resolution and st["plugin"] == "contact_force_fdi":
        st["params"]["resolution_N"] = resolution
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for st in c["stages"]:  # files named in the config stay where they were
    for k, v in st.get("params", {}).items():
        if isinstance(v, str) and v.endswith(".urdf") and not os.path.isabs(v):
            st["params"][k] = os.path.join(base, v)
json.dump(c, open(sys.argv[3], "w"), indent=1)
PY
  "$ftsense" simulate --scenario "$scenario" --output "$work/$s.csv" --quiet > /dev/null
  "$ftsense" run -c "$work/config_$s.json" -i "$work/$s.csv" -o "$work/${s}_run.csv" > /dev/null 2>&1
  "$ftsense" report --run "$work/${s}_run.csv" -t "$work/$s.csv" -o "$work/report_$s" --no-figures > /dev/null
  /usr/bin/python3 - "$work/report_$s/metrics.json" "$s" "$period" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
s = m["summary"]
faulty = [c for c in m["channels"] if c.get("onset_s") is not None]
delays = [c["detection_delay_s"] for c in faulty if c["detection_delay_s"] is not None]
worst = max((c["recovered_rmse"] for c in faulty), default=None)
print(f"{sys.argv[2]:<20} T = {sys.argv[3]:<6} detected {s['detected']}/{s['faulty_channels']}, "
      f"type right {s['types_correct']}/{s['faulty_channels']}, "
      f"longest delay {max(delays):.3f} s, " if delays else f"{sys.argv[2]:<20} T = {sys.argv[3]:<6} ", end="")
print(f"worst recovered RMSE {worst:.1f} N, " if worst is not None else "", end="")
print(f"{s['false_alarms_after_warmup']} false alarms")
PY
done
