#!/usr/bin/env bash
# Times two or more ftsense-bench binaries (say, before and after a change) in turns on one core,
# so that a shared machine's slow and fast spells fall on each alike, and prints per binary and
# benchmark the minimum, first quartile and median of every repetition's time [ns] (a busy machine
# only adds time: the minimum and the quartile show the code; the median is the issue's measure).
# Usage: bench/ab_compare.sh ROUNDS FILTER BENCH_BINARY...
#   e.g. bench/ab_compare.sh 3 'stage/fdi|tick/suralp_robust' /tmp/before/ftsense-bench build/bin/ftsense-bench
# Each round runs every binary once: 10 repetitions of --benchmark_min_time=0.1, pinned by taskset -c 1.
set -eu
if [ $# -lt 3 ]; then
  echo "usage: $0 ROUNDS FILTER BENCH_BINARY..." >&2
  exit 2
fi
rounds=$1
filter=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run=0
for _ in $(seq "$rounds"); do
  for bin in "$@"; do
    run=$((run + 1))
    echo "$bin" > "$out/$run.binary"
    taskset -c 1 "$bin" --benchmark_filter="$filter" --benchmark_repetitions=10 --benchmark_min_time=0.1 \
      --benchmark_format=csv > "$out/$run.csv" 2> "$out/$run.err" || { cat "$out/$run.err" >&2; exit 1; }
  done
done
/usr/bin/python3 - "$out" "$run" <<'PY'
import collections, csv, statistics, sys
times = collections.defaultdict(list)
for run in range(1, int(sys.argv[2]) + 1):
    binary = open(f"{sys.argv[1]}/{run}.binary").read().strip()
    for row in csv.DictReader(open(f"{sys.argv[1]}/{run}.csv")):
        if row["name"].endswith(("_mean", "_median", "_stddev", "_cv")) or not row["cpu_time"]:
            continue
        times[(row["name"], binary)].append(float(row["cpu_time"]))
if not times:
    sys.exit("ab_compare.sh: no benchmark matched the filter")
for (name, binary), v in sorted(times.items()):
    v.sort()
    print(f"{name}  {binary}: n={len(v)} min={v[0]:.0f} p25={v[len(v) // 4]:.0f} median={statistics.median(v):.0f} ns (CPU time)")
PY
