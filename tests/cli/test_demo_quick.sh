#!/usr/bin/env bash
# The paper's experiment end to end on short walks: simulate (MuJoCo), calibrate, run the
# reference pipeline and the measured-ZMP variant, report. Checks the artefacts and the columns.
set -u
ftsense=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
passes=0
failures=0
ok() { passes=$((passes + 1)); echo "ok   $1"; }
bad() { failures=$((failures + 1)); echo "FAIL $1"; }

"$ftsense" demo --quick --out "$out" > "$out/stdout" 2> "$out/stderr"
status=$?
[ $status -eq 0 ] && ok "demo exits 0" || { bad "demo exit $status"; tail -20 "$out/stderr"; }
for f in report.md metrics.json clean.csv clean_fast.csv paper.csv mixed.csv thresholds_reference.json \
         reference_paper/fig4_virtual_vs_true.png reference_paper/fig5_fault_estimate.png \
         reference_paper/fig6_recovered.png reference_paper/fig7_detection_flags.png reference_paper/report.md \
         robust_paper/fig4_virtual_vs_true.png robust_paper/fig7_detection_flags.png robust_paper/report.md \
         robust_gains_bursts/report.md measured_zmp_paper/report.md thresholds_reference_band.json \
         reference_band_paper/fig7_detection_flags.png reference_band_paper/report.md; do
  [ -s "$out/$f" ] && ok "$f written" || bad "$f missing"
done
# The output columns of design.md, for all 8 SURALP channels.
for run in paper_run_reference.csv paper_run_reference_band.csv paper_run_robust.csv; do
header=$(head -1 "$out/$run")
for ch in l_foot/p1 l_foot/p2 l_foot/p3 l_foot/p4 r_foot/p1 r_foot/p2 r_foot/p3 r_foot/p4; do
  for q in measured_N virtual_N fault_estimate_N recovered_N fault fault_type; do
    case ",$header," in *",$ch/$q,"*) ;; *) bad "column $ch/$q missing"; continue 2;; esac
  done
  ok "columns of $ch in $run"
done
done
# Progress counts to its total, walks are named by their length, and no carriage return reaches
# a redirected log.
last=$(grep -oE '^\[[0-9]+/[0-9]+\]' "$out/stdout" | tail -1)
[ "$last" = "[11/11]" ] && ok "progress ends at [11/11]" || bad "progress ends at $last"
[ -s "$out/clean_9s_seed1_scenario.json" ] && [ ! -e "$out/clean_60s_seed1_scenario.json" ] && ok "quick walks named 9s" || bad "quick walks not named by their length"
if grep -q $'\r' "$out/stderr" "$out/stdout"; then bad "a carriage return in the redirected output"; else ok "no carriage return in redirected output"; fi
rows=$(($(wc -l < "$out/paper_run_reference.csv") - 1))
[ "$rows" -eq 9000 ] && ok "9000 rows" || bad "rows: $rows"
# The terminal summary: the paper scenario per channel, then every scenario side by side.
grep -q "r_foot/p2   offset" "$out/stdout" && ok "per-channel table" || bad "per-channel table"
grep -q "^gains_bursts " "$out/stdout" && ok "side-by-side table" || bad "side-by-side table"
# The robust pipeline finds the paper's four faults even in the quick run.
grep -E "^paper .*4/4 det, 4/4 type" "$out/stdout" > /dev/null && ok "robust: paper faults" || bad "robust: paper faults"
# The centred-band calibration wrote a centre per channel, and the demo printed that pipeline's rows.
grep -q '"centers"' "$out/thresholds_reference_band.json" && ok "band thresholds have centres" || bad "band thresholds have no centres"
grep -q "paper pipeline with centred bands" "$out/stdout" && ok "band pipeline summary" || bad "band pipeline summary"
# Every number in the metrics is finite or null (never NaN text).
grep -qi "nan" "$out/metrics.json" && bad "NaN in metrics.json" || ok "metrics.json has no NaN"
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
