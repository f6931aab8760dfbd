#!/usr/bin/env bash
# Physically absurd parameters (docs/reliability.md, issue 15 finding 12): a value within a
# parameter's hard bounds but outside its plausible range (params.hpp) is a warning with its JSON
# Pointer. `ftsense check` prints it and still exits 0 (the pipeline can run); `ftsense run` prints
# it once to stderr and runs. One table row per case, each a shipped config with one value changed.
#   usage: check_plausibility.sh FTSENSE SOURCE_DIR
set -u
ftsense=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0

# with CONFIG JSON_POINTER VALUE OUT: CONFIG with the value at JSON_POINTER replaced. A "$ref" on
# the way is replaced by a copy of its definition first, so only that place changes.
with() {
  /usr/bin/python3 - "$@" <<'PY'
import copy, json, sys
config, pointer, value, out = sys.argv[1:5]
doc = json.load(open(config))
node = doc
keys = [int(k) if k.isdigit() else k for k in pointer.split("/")[1:]]
for k in keys[:-1]:
    child = node[k]
    if isinstance(child, dict) and set(child) == {"$ref"}:
        target = doc
        for part in child["$ref"].split("/")[1:]:
            target = target[part]
        node[k] = child = copy.deepcopy(target)
    node = child
node[keys[-1]] = json.loads(value)
json.dump(doc, open(out, "w"), indent=1)
PY
}

# name | config | JSON Pointer | value | expected warning (ERE, after "warning: <config>:")
row() {
  local name=$1 config=$2 pointer=$3 value=$4 message=$5
  local out="$work/$name.json" status ok=1 count
  with "$src/$config" "$pointer" "$value" "$out"
  timeout 20 "$ftsense" check --config "$out" > "$work/out" 2> "$work/err"
  status=$?
  [ "$status" -eq 0 ] || { echo "FAIL $name: exit $status, expected 0 (a warning is not an error)"; ok=0; }
  grep -q "^ok: " "$work/out" || { echo "FAIL $name: no 'ok:' line on stdout"; ok=0; }
  count=$(grep -cE -- "^warning: $out:$pointer = $message" "$work/err")
  [ "$count" -eq 1 ] || { echo "FAIL $name: 'warning: ...$pointer = $message' $count times in stderr:"; sed 's/^/    /' "$work/err" | head -5; ok=0; }
  [ "$(wc -l < "$work/err")" -eq 1 ] || { echo "FAIL $name: more than the one warning:"; sed 's/^/    /' "$work/err" | head -5; ok=0; }
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

# The four values of the finding.
row mass_in_grams configs/suralp.json /stages/1/params/mass_kg 0.001 \
    "0.001 is outside the plausible range 0.5 \.\. 1000 kg \(robot mass: 1 kg toys to 300 kg machines\); check the unit or the value"
row com_height_tiny configs/suralp.json /stages/0/params/com_height_m 1e-300 \
    "1e-300 is outside the plausible range 0.05 \.\. 3 m \(CoM height: 0.1 m toys to 2 m machines\); check the unit or the value"
row cutoff_tiny configs/suralp.json /stages/7/params/cutoff_hz 1e-300 \
    "1e-300 is outside the plausible range 0.001 \.\. 5000 Hz \(.*\); check the unit or the value"
row warmup_huge configs/suralp.json /stages/8/params/warmup_s 1e300 \
    "1e\+300 is outside the plausible range 0 \.\. 600 s \(.*\); check the unit or the value"
# The same kinds in the robust pipeline and the pipeline's own tick period.
row robust_mass_in_grams configs/suralp_robust.json /stages/0/params/mass_kg 0.001 "0.001 is outside the plausible range 0.5 \.\. 1000 kg"
row robust_sum_cutoff_tiny configs/suralp_robust.json /stages/3/params/sum_cutoff_hz 1e-300 "1e-300 is outside the plausible range 0.001 \.\. 5000 Hz"
row robust_points_in_millimetres configs/suralp_robust.json /stages/2/params/points/0/0 120 "120 is outside the plausible range -1 \.\. 1 m"
row sample_period_tiny tests/cli/good.json /sample_period_s 1e-9 "1e-09 is outside the plausible range 1e-05 \.\. 1 s \(control loops tick at 1 Hz to 100 kHz\)"

# Hard bounds are still errors (exit 2), not warnings.
with "$src/configs/suralp.json" /stages/1/params/mass_kg -1 "$work/negative_mass.json"
"$ftsense" check --config "$work/negative_mass.json" > "$work/out" 2> "$work/err"
status=$?
if [ "$status" -eq 2 ] && grep -q "/stages/1/params/mass_kg = -1 violates >= 0" "$work/err" && ! grep -q "^warning:" "$work/err"; then
  passes=$((passes + 1)); echo "ok   negative_mass_is_an_error"
else
  failures=$((failures + 1)); echo "FAIL negative_mass_is_an_error: exit $status"; sed 's/^/    /' "$work/err" | head -5
fi

# `run` prints the warning once, then runs the pipeline to the end (exit 0).
with "$src/tests/cli/good.json" /stages/1/params/cutoff_hz 1e-300 "$work/run_tiny_cutoff.json"
awk 'BEGIN { print "time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N";
  for (k = 0; k < 500; k++) printf "%.3f,1,1,1,1,1,1\n", k / 1000 }' > "$work/log.csv"
"$ftsense" run --config "$work/run_tiny_cutoff.json" --input "$work/log.csv" --output "$work/run.csv" > "$work/out" 2> "$work/err"
status=$?
count=$(grep -c "^warning: .*/stages/1/params/cutoff_hz = 1e-300 is outside the plausible range" "$work/err")
if [ "$status" -eq 0 ] && [ "$count" -eq 1 ] && [ "$(wc -l < "$work/run.csv")" -eq 501 ]; then
  passes=$((passes + 1)); echo "ok   run_warns_once_and_runs"
else
  failures=$((failures + 1)); echo "FAIL run_warns_once_and_runs: exit $status, warning $count times"; sed 's/^/    /' "$work/err" | head -5
fi

echo "plausibility: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
