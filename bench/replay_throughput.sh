#!/usr/bin/env bash
# Replay throughput of `ftsense run` end to end (CSV parsing, pipeline, CSV writing) over a
# 120 s simulated walk (120,000 ticks). Usage: bench/replay_throughput.sh [BUILD_DIR]
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
best=""
for run in 1 2 3; do
  start=$(date +%s.%N)
  "$build/bin/ftsense" run --config "$root/configs/suralp.json" --input "$work/long.csv" --output "$work/out.csv" > /dev/null
  end=$(date +%s.%N)
  seconds=$(echo "$end - $start" | bc -l)
  echo "run $run: $seconds s wall"
  if [ -z "$best" ] || [ "$(echo "$seconds < $best" | bc -l)" -eq 1 ]; then best=$seconds; fi
done
printf 'best of 3: %.3f s, %.0f ticks per second (%.0f times real time at 1 kHz)\n' "$best" \
  "$(echo "$ticks / $best" | bc -l)" "$(echo "$ticks / $best / 1000" | bc -l)"
