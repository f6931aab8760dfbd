#!/usr/bin/env bash
# Where the instructions of `ftsense run` go, counted by valgrind's callgrind (deterministic): a
# 10 s simulated walk (10,000 rows) replayed through configs/suralp.json; per row, the whole run
# and the inclusive cost of writing rows (CsvLogWriter::write_row, std::to_chars inside it), of
# parsing rows (CsvLogReader::next, std::from_chars inside it; on the prefetch thread) and of the
# pipeline (Pipeline::step); then the same for ftsense-replay-floor (bench/replay_floor.cpp) on
# that log, and the ratio. Usage: bench/callgrind_replay.sh [BUILD_DIR]
set -eu
build=${1:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$(cd "$(dirname "$0")/.." && pwd)
/usr/bin/python3 - "$root/configs/scenarios/clean.json" "$work/walk.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); s["duration_s"] = 10.0
json.dump(s, open(sys.argv[2], "w"))
PY
"$build/bin/ftsense" simulate --scenario "$work/walk.json" --out "$work/walk.csv" --quiet > /dev/null
rows=$(($(wc -l < "$work/walk.csv") - 1))
valgrind --tool=callgrind --callgrind-out-file="$work/cg" "$build/bin/ftsense" run --config "$root/configs/suralp.json" \
  --input "$work/walk.csv" --output "$work/out.csv" > /dev/null 2> "$work/log"
callgrind_annotate --inclusive=yes --threshold=100 "$work/cg" > "$work/annotate" 2> /dev/null
columns=$(/usr/bin/python3 "$root/bench/replay_floor_columns.py" "$work/walk.csv" "$work/out.csv")
valgrind --tool=callgrind --callgrind-out-file="$work/cg.floor" "$build/bin/ftsense-replay-floor" "$work/walk.csv" \
  "$work/floor.csv" "$columns" > /dev/null 2> "$work/log.floor"
floor=$(grep -E "Collected" "$work/log.floor" | awk '{print $NF}' | tr -d ',')
/usr/bin/python3 - "$work/annotate" "$rows" "$floor" <<'PY'
import re, sys
rows = int(sys.argv[2])
cost = {}
for line in open(sys.argv[1]):
    m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(\S.*?)(?: \[.*\])?$", line)
    if m:
        name = m.group(2).split(":", 1)[-1] if "PROGRAM TOTALS" not in line else "PROGRAM TOTALS"
        cost.setdefault(name, int(m.group(1).replace(",", "")))
def find(prefix):
    hits = [v for k, v in cost.items() if k.startswith(prefix)]
    return max(hits) if hits else 0
total = cost["PROGRAM TOTALS"]
print(f"{rows} rows; per row: {total / rows:.0f} instructions in all")
for label, prefix in [("writing rows (CsvLogWriter::write_row)", "ftsense::io::CsvLogWriter::write_row"),
                      ("  of which std::to_chars", "std::to_chars(char*, char*, double)"),
                      ("parsing rows (CsvLogReader::next)", "ftsense::io::CsvLogReader::next"),
                      ("  of which std::from_chars", "std::from_chars(char const*, char const*, double&"),
                      ("the pipeline (Pipeline::step)", "ftsense::Pipeline::step")]:
    c = find(prefix)
    print(f"  {label:42s} {c / rows:8.0f} per row  {100.0 * c / total:5.1f} %")
floor = int(sys.argv[3])
print(f"ftsense-replay-floor: {floor / rows:.0f} instructions per row; ftsense run / floor: {total / floor:.2f}")
PY
