#!/usr/bin/env bash
# `ftsense demo --no-logs` keeps what people read (metrics, reports, figures, HTML) and deletes
# the simulated logs and the runs' CSV once they are scored (issue 16: demo options to keep less).
set -u
ftsense=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$ftsense" demo --quick --no-logs --output "$out" > "$out/stdout" 2> "$out/stderr" || { tail -20 "$out/stderr"; exit 1; }
failures=0
bad() { failures=$((failures + 1)); echo "FAIL $1"; }
left=$(find "$out" -name '*.csv' | wc -l)
[ "$left" -eq 0 ] || bad "$left CSV files left: $(find "$out" -name '*.csv' | head -3)"
for f in metrics.json report.md report.html confusion_matrix.png robust_paper/report.html robust_paper/fig4_virtual_vs_true.png \
         reference_mixed/metrics.json; do
  [ -s "$out/$f" ] || bad "$f missing or empty"
done
grep -q -- "--no-logs: deleted the logs and runs' CSV, [1-9][0-9]* MB" "$out/stdout" || bad "no line saying what was deleted"
# The numbers do not depend on it: the paper scenario's summary line is printed as usual.
grep -q "paper " "$out/stdout" || bad "no paper row in the summary"
echo "demo --no-logs: $(du -sh "$out" | cut -f1) kept, $failures failures"
exit $((failures > 0))
