#!/usr/bin/env bash
# Instructions per whole tick of configs/suralp.json, counted by valgrind's callgrind (deterministic:
# the same binary and inputs give the same count on a busy or idle machine). Runs the benchmark
# binary for N1 and N2 ticks and divides the difference, so set-up (the simulated walk, building
# the pipeline) cancels out. Usage: bench/callgrind_per_tick.sh [BUILD_DIR]
set -eu
build=${1:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count() {
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.$1" "$build/bin/ftsense-bench" --ticks "$1" > /dev/null 2> "$work/log.$1"
  grep -E "Collected" "$work/log.$1" | awk '{print $NF}' | tr -d ','
}
n1=20000
n2=40000
c1=$(count $n1)
c2=$(count $n2)
echo "instructions: $c1 for $n1 ticks, $c2 for $n2 ticks"
echo "per tick: $(( (c2 - c1) / (n2 - n1) )) instructions"
