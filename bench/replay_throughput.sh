#!/usr/bin/env bash
# Replay throughput of `ftsense run` end to end (CSV parsing, pipeline, CSV writing) over a
# 120 s simulated walk (120,000 ticks), against a floor measured in the same invocation:
# ftsense-replay-floor (bench/replay_floor.cpp) reads the same log on one thread and writes as many
# rows and columns with the same number formatting, without the pipeline. Three rounds, each runs
# both; prints every run, the best of each and the ratio of the bests.
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
best=""
best_floor=""
for run in 1 2 3; do
  t=$(seconds "$build/bin/ftsense" run --config "$root/configs/suralp.json" --input "$work/long.csv" --output "$work/out.csv")
  columns=$(head -1 "$work/out.csv" | tr ',' '\n' | wc -l)
  f=$(seconds "$build/bin/ftsense-replay-floor" "$work/long.csv" "$work/floor.csv" "$columns")
  printf 'run %d: ftsense run %.3f s, floor %.3f s\n' "$run" "$t" "$f"
  if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" -eq 1 ]; then best=$t; fi
  if [ -z "$best_floor" ] || [ "$(echo "$f < $best_floor" | bc -l)" -eq 1 ]; then best_floor=$f; fi
done
echo "output: ftsense run $(($(wc -l < "$work/out.csv") - 1)) rows x $columns columns, $(du -m "$work/out.csv" | cut -f1) MB;" \
     "floor $(($(wc -l < "$work/floor.csv") - 1)) rows x $columns columns, $(du -m "$work/floor.csv" | cut -f1) MB"
printf 'best of 3: %.3f s, %.0f ticks per second (%.0f times real time at 1 kHz)\n' "$best" \
  "$(echo "$ticks / $best" | bc -l)" "$(echo "$ticks / $best / 1000" | bc -l)"
printf 'floor, best of 3: %.3f s, %.0f ticks per second\n' "$best_floor" "$(echo "$ticks / $best_floor" | bc -l)"
printf 'ftsense run / floor: %.2f\n' "$(echo "$best / $best_floor" | bc -l)"
