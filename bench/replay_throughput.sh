#!/usr/bin/env bash
# Replay throughput of `ftsense run` end to end (CSV parsing, pipeline, CSV writing) over a
# 120 s simulated walk (120,000 ticks), against a floor measured in the same invocation:
# ftsense-replay-floor (bench/replay_floor.cpp) reads the same log on one thread and writes as many
# rows and columns as ftsense run, each column an input column whose numbers are about as long as
# ftsense's in that column (so about as many bytes), with the same number formatting and no
# pipeline. One untimed run of ftsense to pick those columns, then five rounds, each runs both;
# prints every run, the best of each and the ratio of the bests.
# Usage: bench/replay_throughput.sh [BUILD_DIR]
set -eu
build=${1:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$(cd "$(dirname "$0")/.." && pwd)
/usr/bin/python3 - "$root/configs/scenarios/clean.json" "$work/long.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); s["duration_s"] = 120.0
json.dump(s, open(sys.argv[2], "w"))
PY
"$build/bin/ftsense" simulate --scenario "$work/long.json" --out "$work/long.csv" --quiet > /dev/null
ticks=$(($(wc -l < "$work/long.csv") - 1))
echo "log: $ticks ticks, $(du -m "$work/long.csv" | cut -f1) MB, $(head -1 "$work/long.csv" | tr ',' '\n' | wc -l) columns"
seconds() {  # wall time of a command, in seconds
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
"$build/bin/ftsense" run --config "$root/configs/suralp.json" --input "$work/long.csv" --output "$work/out.csv" > /dev/null
columns=$(/usr/bin/python3 "$root/bench/replay_floor_columns.py" "$work/long.csv" "$work/out.csv")
best=""
best_floor=""
for run in 1 2 3 4 5; do
  t=$(seconds "$build/bin/ftsense" run --config "$root/configs/suralp.json" --input "$work/long.csv" --output "$work/out.csv")
  f=$(seconds "$build/bin/ftsense-replay-floor" "$work/long.csv" "$work/floor.csv" "$columns")
  printf 'run %d: ftsense run %.3f s, floor %.3f s\n' "$run" "$t" "$f"
  if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" -eq 1 ]; then best=$t; fi
  if [ -z "$best_floor" ] || [ "$(echo "$f < $best_floor" | bc -l)" -eq 1 ]; then best_floor=$f; fi
done
shape() { echo "$(($(wc -l < "$1") - 1)) rows x $(head -1 "$1" | tr ',' '\n' | wc -l) columns, $(du -m "$1" | cut -f1) MB"; }
echo "output: ftsense run $(shape "$work/out.csv"); floor $(shape "$work/floor.csv")"
printf 'best of 5: %.3f s, %.0f ticks per second (%.0f times real time at 1 kHz)\n' "$best" \
  "$(echo "$ticks / $best" | bc -l)" "$(echo "$ticks / $best / 1000" | bc -l)"
printf 'floor, best of 5: %.3f s, %.0f ticks per second\n' "$best_floor" "$(echo "$ticks / $best_floor" | bc -l)"
printf 'ftsense run / floor: %.2f\n' "$(echo "$best / $best_floor" | bc -l)"
