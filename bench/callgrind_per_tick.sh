#!/usr/bin/env bash
# Instructions per whole tick of configs/suralp.json (or CONFIG, one that reads some of its inputs, by name), counted by valgrind's callgrind (deterministic:
# the same binary and inputs give the same count on a busy or idle machine). Runs the benchmark
# binary for N1 and N2 ticks and divides the difference, so set-up (the simulated walk, building
# the pipeline) cancels out; then the same difference per function (self cost, the 15 largest).
# Usage: bench/callgrind_per_tick.sh [BUILD_DIR] [CONFIG, e.g. configs/suralp_robust.json]
set -eu
build=${1:-build}
config=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count() {
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.$1" "$build/bin/ftsense-bench" --ticks "$1" $config \
    > "$work/out.$1" 2> "$work/log.$1"
  # A run that failed part-way still reports its instructions: check that it ran every tick.
  if ! grep -q "^ran $1 ticks" "$work/out.$1"; then
    echo "ftsense-bench --ticks $1 failed under valgrind:" >&2
    grep -v "^==" "$work/log.$1" >&2
    exit 1
  fi
  grep -E "Collected" "$work/log.$1" | awk '{print $NF}' | tr -d ','
}
n1=20000
n2=40000
c1=$(count $n1)
c2=$(count $n2)
echo "config: ${config:-configs/suralp.json}"
echo "instructions: $c1 for $n1 ticks, $c2 for $n2 ticks"
echo "per tick: $(( (c2 - c1) / (n2 - n1) )) instructions"
echo "per tick by function (self instructions, largest first):"
for n in $n1 $n2; do
  callgrind_annotate --inclusive=no --threshold=100 "$work/cg.$n" > "$work/annotate.$n" 2> /dev/null
done
/usr/bin/python3 - "$work/annotate.$n1" "$work/annotate.$n2" $((n2 - n1)) <<'PY'
import re, sys
def costs(path):
    out = {}
    for line in open(path):
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(\S.*?)(?: \[.*\])?$", line)
        if m and "PROGRAM TOTALS" not in line:
            name = m.group(2).split(":", 1)[-1]
            out[name] = out.get(name, 0) + int(m.group(1).replace(",", ""))
    return out
a, b = costs(sys.argv[1]), costs(sys.argv[2])
ticks = int(sys.argv[3])
per_tick = sorted(((b.get(f, 0) - a.get(f, 0)) / ticks, f) for f in b)
for cost, name in reversed(per_tick[-15:]):
    print(f"  {cost:8.0f}  {name}")
PY
