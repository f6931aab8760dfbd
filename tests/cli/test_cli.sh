#!/usr/bin/env bash
# The command-line contract of build/bin/ftsense (design.md): exit codes 0/2/1, one line per
# problem on stderr, the config checked before any input file is opened.
set -u
here=$1
ftsense=${FTSENSE:?set FTSENSE to the ftsense binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0

check() {  # check NAME EXPECTED_STATUS ACTUAL_STATUS [grep-pattern file]...
  local name=$1 expected=$2 actual=$3
  shift 3
  local ok=1
  [ "$actual" -eq "$expected" ] || { echo "FAIL $name: exit $actual, expected $expected"; ok=0; }
  while [ $# -ge 2 ]; do
    grep -qE -- "$1" "$2" || { echo "FAIL $name: '$1' not in $(basename "$2"):"; sed 's/^/    /' "$2"; ok=0; }
    shift 2
  done
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

# A 3 s log for the minimal pipeline: c2 gets +20 N from t = 1 s.
awk 'BEGIN { print "time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N,unused";
  for (k = 0; k < 3000; k++) { t = k / 1000; l = 100 + 20 * sin(3.14159265 * t);
    printf "%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,0\n", t, l, l + (t >= 1 ? 20 : 0), l, l, l, l } }' > "$work/log.csv"
good="$here/good.json"

"$ftsense" --help > "$work/out" 2> "$work/err"; check help 0 $? "run" "$work/out"
"$ftsense" --version > "$work/out" 2> "$work/err"; check version 0 $? "^ftsense [0-9]+\.[0-9]+\.[0-9]+$" "$work/out"
"$ftsense" run --version > "$work/out" 2> "$work/err"; check verb_version 0 $? "^ftsense [0-9]+\.[0-9]+\.[0-9]+$" "$work/out"
"$ftsense" > "$work/out" 2> "$work/err"; check no_verb 2 $?
"$ftsense" rnu > "$work/out" 2> "$work/err"; check unknown_verb 2 $? "did you mean 'run'" "$work/err"
"$ftsense" run --help > "$work/out" 2> "$work/err"; check run_help 0 $? "--config" "$work/out"
"$ftsense" run > "$work/out" 2> "$work/err"
check run_missing_options 2 $? "missing required option --config" "$work/err" "missing required option --input" "$work/err"
"$ftsense" run --config "$here/good.json" --input "$work/log.csv" > "$work/out" 2> "$work/err"
check run_without_output_prints_the_summary 0 $? "3000 ticks, 3 channels -> \(no --output: nothing written\)" "$work/out" "c2: fault first flagged" "$work/out"
"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/o.csv" --ouput x > "$work/out" 2> "$work/err"
check unknown_option 2 $? "unknown option --ouput; did you mean 'output'" "$work/err"

# A config with three problems and an input file that does not exist: all three problems are
# listed, one per line, and the input is never opened.
sed -e 's/"cutoff_hz": 2.0/"cutoff_hz": -1/' -e 's/"threshold_detector"/"treshold_detector"/' \
    -e 's/"sample_period_s": 0.001/"sample_period_s": 0/' "$good" > "$work/bad.json"
"$ftsense" run --config "$work/bad.json" --input "$work/missing.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check bad_config 2 $? "bad.json:/stages/1/params/cutoff_hz = -1 violates > 0" "$work/err" \
    "bad.json:/stages/2/plugin: unknown plugin 'treshold_detector'; did you mean 'threshold_detector'" "$work/err" \
    "bad.json:/sample_period_s = 0 violates > 0" "$work/err"
lines=$(wc -l < "$work/err"); errors=$(grep -c '^error: ' "$work/err")
[ "$lines" -eq 3 ] && [ "$errors" -eq 3 ] && { passes=$((passes + 1)); echo "ok   bad_config_one_line_each"; } \
  || { failures=$((failures + 1)); echo "FAIL bad_config_one_line_each: $lines lines, $errors errors"; cat "$work/err"; }
grep -q "missing.csv" "$work/err" && { failures=$((failures + 1)); echo "FAIL config_checked_first: the input was looked at"; } \
  || { passes=$((passes + 1)); echo "ok   config_checked_first"; }

printf '{"sample_period_s": 0.001,\n "inputs": {,}\n' > "$work/syntax.json"
"$ftsense" run --config "$work/syntax.json" --input "$work/log.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check config_not_json 2 $? "syntax.json:2:13: not valid JSON" "$work/err"
"$ftsense" run --config "$work/nope.json" --input "$work/log.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check config_missing 2 $? "^error: ftsense run: --config \(-c\) .*/nope.json: no such file; check the path \(--config wants: pipeline config" "$work/err"
# A missing input file is named with its option once the config is known good.
"$ftsense" run --config "$good" --input "$work/missing.csv" > "$work/out" 2> "$work/err"
check input_missing 2 $? "^error: ftsense run: --input \(-i\) .*/missing.csv: no such file; check the path" "$work/err"
"$ftsense" calibrate --config "$good" --input "$work/log.csv,$work/missing.csv" --output "$work/x.json" > "$work/out" 2> "$work/err"
check calibrate_input_missing 2 $? "^error: ftsense calibrate: --input \(-i\) .*/missing.csv: no such file" "$work/err"
[ ! -e "$work/x.json" ] && { passes=$((passes + 1)); echo "ok   calibrate_input_missing_writes_nothing"; } \
  || { failures=$((failures + 1)); echo "FAIL calibrate_input_missing_writes_nothing"; }
"$ftsense" report --run "$work/missing.csv" --output "$work/rep" > "$work/out" 2> "$work/err"
check report_run_missing 2 $? "^error: ftsense report: --run .*/missing.csv: no such file" "$work/err"

"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check run_ok 0 $? "3000 ticks, 3 channels" "$work/out" "c2: fault first flagged at t = 1\.0[0-9]* s; fault type unclassified$" "$work/out"
grep -q "no channel flagged" "$work/out" && { failures=$((failures + 1)); echo "FAIL run_ok_says_no_channel_flagged"; } \
  || { passes=$((passes + 1)); echo "ok   run_ok_flagged_is_not_no_channel_flagged"; }

# One spelling per option, short flags for the common ones, the old spelling a silent alias.
"$ftsense" run -c "$good" -i "$work/log.csv" -o "$work/short.csv" > "$work/out" 2> "$work/err"
check short_flags 0 $? "3000 ticks, 3 channels -> .*short.csv" "$work/out"
cmp -s "$work/o.csv" "$work/short.csv" && { passes=$((passes + 1)); echo "ok   short_flags_same_output"; } \
  || { failures=$((failures + 1)); echo "FAIL short_flags_same_output"; }
"$ftsense" run --config="$good" --input "$work/log.csv" --out "$work/alias.csv" > "$work/out" 2> "$work/err"
status=$?; [ -s "$work/err" ] && status=98  # 98: the alias printed something
check out_is_a_silent_alias_of_output 0 $status "3000 ticks, 3 channels -> .*alias.csv" "$work/out"
"$ftsense" run -c "$good" -i "$work/log.csv" -o "$work/a.csv" --output "$work/b.csv" > "$work/out" 2> "$work/err"
check option_and_its_short_flag_twice 2 $? "option --output is given twice" "$work/err"
"$ftsense" run -c "$good" -x 1 > "$work/out" 2> "$work/err"
check unknown_short_flag 2 $? "unknown option -x; its short flags are -c \(--config\), -i \(--input\), -o \(--output\)" "$work/err"
verbs="run check calibrate report plugins"
"$ftsense" --help | grep -q "^  inject " && verbs="$verbs inject"  # with the simulator's fault models
for verb in $verbs; do
  "$ftsense" $verb --help > "$work/out" 2> "$work/err"
  check help_$verb 0 $? "^  -h, --help" "$work/out"
done
"$ftsense" run --help > "$work/out"; check help_shows_short_flags 0 $? "^  -c, --config" "$work/out" "^  -i, --input" "$work/out" "^  -o, --output" "$work/out"
"$ftsense" report --help > "$work/out"; check help_report_flags 0 $? "^  -t, --truth" "$work/out" "^  -o, --output" "$work/out" "usage: ftsense report --run FILE \[--truth FILE\] --output DIR" "$work/out"
head -1 "$work/o.csv" > "$work/header"
check run_output_header 0 0 "^time_s,c1/measured_N,c1/virtual_N,c1/fault_estimate_N,c1/recovered_N,c1/fault,c1/fault_type,c1/cannot_judge,c2/measured_N" "$work/header"
rows=$(($(wc -l < "$work/o.csv") - 1))
[ "$rows" -eq 3000 ] && { passes=$((passes + 1)); echo "ok   run_output_rows"; } || { failures=$((failures + 1)); echo "FAIL run_output_rows: $rows"; }
grep -q "c1: fault" "$work/out" && { failures=$((failures + 1)); echo "FAIL run_no_false_alarm"; } || { passes=$((passes + 1)); echo "ok   run_no_false_alarm"; }

# Missing columns: every one named, exit 2.
sed '1s/cell\/c1\/force_N/cell\/c1\/forc_N/; 1s/model\/c3\/force_N/m3/' "$work/log.csv" > "$work/renamed.csv"
"$ftsense" run --config "$good" --input "$work/renamed.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check missing_columns 2 $? "/inputs/measured/columns/0: column 'cell/c1/force_N' is not in .*renamed.csv; did you mean 'cell/c1/forc_N'" "$work/err" \
    "/inputs/reference/columns/2: column 'model/c3/force_N' is not in" "$work/err"

# A malformed row: runtime failure with file and line.
sed '101s/^\([^,]*\),[^,]*/\1,abc/' "$work/log.csv" > "$work/badrow.csv"
"$ftsense" run --config "$good" --input "$work/badrow.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check malformed_row 1 $? "badrow.csv:101: column 'cell/c1/force_N' \(field 2\) = 'abc' is not a number" "$work/err"
# The same far into the log (rows after the first 50 are parsed on a second thread, in blocks):
# the error names its line, and no partial output is left that could pass for a whole one.
sed '2901s/^\([^,]*\),[^,]*/\1,abc/' "$work/log.csv" > "$work/badrow_late.csv"
"$ftsense" run --config "$good" --input "$work/badrow_late.csv" --output "$work/late.csv" > "$work/out" 2> "$work/err"
status=$?
[ ! -e "$work/late.csv" ] || { echo "a partial late.csv was left: $(wc -l < "$work/late.csv") lines"; status=99; }
check malformed_row_late 1 $status "badrow_late.csv:2901: column 'cell/c1/force_N' \(field 2\) = 'abc' is not a number" "$work/err"

"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/no/such/dir/o.csv" > "$work/out" 2> "$work/err"
check output_unwritable 2 $? "cannot create the output file" "$work/err"

"$ftsense" check --config "$good" > "$work/out" 2> "$work/err"; check check_ok 0 $? "^ok: " "$work/out"
"$ftsense" check --config "$work/bad.json" > "$work/out" 2> "$work/err"; check check_bad 2 $? "unknown plugin" "$work/err"
"$ftsense" plugins > "$work/out" 2> "$work/err"; check plugins 0 $? "^low_pass" "$work/out"

# The log's clock (docs/reliability.md): no data rows, another sample rate, gaps, jitter.
head -1 "$work/log.csv" > "$work/header_only.csv"
"$ftsense" run --config "$good" --input "$work/header_only.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check header_only 1 $? "header_only.csv:2: the log has a header but no data rows" "$work/err"
awk -F, -v OFS=, 'NR == 1 { print; next } { $1 = sprintf("%.3f", (NR - 2) / 100); print }' "$work/log.csv" > "$work/100hz.csv"
"$ftsense" run --config "$good" --input "$work/100hz.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check sample_rate_mismatch 1 $? "100hz.csv: the log is sampled every 0.01 s \(100 Hz" "$work/err" \
    "sample_period_s is 0.001 s \(1000 Hz\); set sample_period_s to 0.01 or resample" "$work/err"
# c2 is off by +20 N from 1 s to 2 s, then the logger stops for 0.5 s: after the gap the
# pipeline starts afresh (no stale +20 N in the low-pass), unless --gap-reset says the gap is none.
awk -F, -v OFS=, 'NR == 1 { print; next } { t = $1 + 0; if (t >= 2.0 && t < 2.5) next; if (t >= 2.0) $3 = $2; print }' \
    "$work/log.csv" > "$work/gap.csv"
"$ftsense" run --config "$good" --input "$work/gap.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check gap_reset_reported 0 $? "gap.csv: 1 time gap longer than 10 T = 0.01 s \(first at line 2002: 0.501 s\); the pipeline was reset" "$work/err"
flag_after_gap=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "c2/fault") c = i; next } $1 + 0 == 2.5 { print $c }' "$work/o.csv")
[ "$flag_after_gap" = "0" ] && { passes=$((passes + 1)); echo "ok   gap_resets_the_filters"; } \
  || { failures=$((failures + 1)); echo "FAIL gap_resets_the_filters: c2/fault at 2.5 s = '$flag_after_gap'"; }
"$ftsense" run --config "$good" --input "$work/gap.csv" --output "$work/o.csv" --gap-reset 1000 > "$work/out" 2> "$work/err"
check gap_not_reset_when_allowed 0 $? "1 rows are not T = 0.001 s after the previous one \(first at line 2002, dt = 0.501 s\)" "$work/err"
flag_after_gap=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "c2/fault") c = i; next } $1 + 0 == 2.5 { print $c }' "$work/o.csv")
[ "$flag_after_gap" = "1" ] && { passes=$((passes + 1)); echo "ok   gap_bridged_without_reset"; } \
  || { failures=$((failures + 1)); echo "FAIL gap_bridged_without_reset: c2/fault at 2.5 s = '$flag_after_gap'"; }
sed '501d' "$work/log.csv" > "$work/dropped.csv"
"$ftsense" run --config "$good" --input "$work/dropped.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check one_dropped_sample_is_jitter 0 $? "1 rows are not T = 0.001 s after the previous one \(first at line 501, dt = 0.002 s\)" "$work/err"
grep -q "gap" "$work/err" && { failures=$((failures + 1)); echo "FAIL one_dropped_sample_no_reset"; } || { passes=$((passes + 1)); echo "ok   one_dropped_sample_no_reset"; }
"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/o.csv" --gap-reset 1 > "$work/out" 2> "$work/err"
check gap_reset_too_small 2 $? "--gap-reset 1: give a number of sample periods >= 1.5" "$work/err"

# A thresholds file that does not fit the config names the file and the stage.
printf '{"stages": {"detekt": {"thresholds": [1.0]}}}\n' > "$work/thresholds.json"
"$ftsense" run --config "$good" --thresholds "$work/thresholds.json" --input "$work/log.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check thresholds_do_not_fit 2 $? "thresholds.json:/stages/detekt: the config has no stage named 'detekt'" "$work/err"

# Calibration. A virtual sensor biased by +30 N on c1 (fault-free residual in [25, 35]): the
# paper's |s| <= 1.25 max |s| (43.75) hides a -20 N fault; a centred band (calibrate --band, over
# two fault-free logs) has centre 30 and half-width 1.25 x 5 and shows it.
# c2 and c3 carry a small error (0.5 N at 7 rad/s) like any real sensor: calibrate refuses a
# detector input that never varies (its threshold would be 0).
biased_log() {  # biased_log AMPLITUDE FAULT_N FILE: c1 reads model + 30 + AMPLITUDE sin(pi t), plus FAULT_N from t = 1 s
  awk -v amp="$1" -v fault="$2" 'BEGIN { print "time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N";
    for (k = 0; k < 3000; k++) { t = k / 1000; l = 100; e = 0.5 * sin(7 * t);
      printf "%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", t, l + 30 + amp * sin(3.14159265 * t) + (t >= 1 ? fault : 0), l + e, l - e, l, l, l } }' > "$3"
}
biased_log 5 0 "$work/clean_a.csv"; biased_log 3 0 "$work/clean_b.csv"; biased_log 0 -20 "$work/faulty.csv"
"$ftsense" calibrate --config "$good" --input "$work/clean_a.csv" --output "$work/plain.json" > "$work/out" 2> "$work/err"
check calibrate_plain 0 $? "detector|detect: thresholds 4[0-9]\.[0-9]" "$work/out"
"$ftsense" calibrate --config "$good" --input "$work/clean_a.csv,$work/clean_b.csv" --output "$work/band.json" --band > "$work/out" 2> "$work/err"
check calibrate_band_two_logs 0 $? "detect: thresholds [0-9.]+ .*; centres 30" "$work/out" '"ticks": 6000' "$work/band.json"
"$ftsense" run --config "$good" --input "$work/faulty.csv" --output "$work/o.csv" --thresholds "$work/plain.json" > "$work/out" 2> "$work/err"
status=$?; grep -q "fault first flagged" "$work/out" && status=99  # 99: a channel was flagged
check plain_threshold_hides_the_negative_fault 0 $status "3000 ticks, 3 channels" "$work/out" "^  no channel flagged$" "$work/out"
"$ftsense" run --config "$good" --input "$work/faulty.csv" --output "$work/o.csv" --thresholds "$work/band.json" > "$work/out" 2> "$work/err"
check band_shows_the_negative_fault 0 $? "c1: fault first flagged at t = 1\.[0-9]* s" "$work/out"
# A calibration states the rate it was measured at; a config at another rate refuses it (a
# filtered residual's peak and a window's step are other numbers there).
grep -q '"sample_period_s": 0.001' "$work/plain.json" && sed 's/"sample_period_s": 0.001/"sample_period_s": 0.005/' "$good" > "$work/good_200hz.json"
"$ftsense" run --config "$work/good_200hz.json" --input "$work/faulty.csv" --output "$work/o.csv" --thresholds "$work/plain.json" > "$work/out" 2> "$work/err"
check calibration_at_another_rate 2 $? "plain.json:/sample_period_s: = 0.001 s, but the config runs at 0.005 s: .*calibrate on a fault-free log at 0.005 s" "$work/err"
"$ftsense" calibrate --config "$good" --input "$work/clean_a.csv," --output "$work/x.json" > "$work/out" 2> "$work/err"
check calibrate_empty_log_path 2 $? "has an empty log path" "$work/err"

# Calibrated parameters: fault-free statistics of a stage's inputs (calibration.hpp). The model
# l = 100 + 50 sin(2 pi t) N moves like a gait; c1 = l + 0.5 + 4 n, c2 = l + n, c3 = l - n, with
# n_k = frac(0.618... k) - 0.5 (uniform, lag-one correlation < 0: white). Over the 22 s: c1's
# residual has centre 0.4998, standard deviation 4 / sqrt(12) = 1.155 and, its means over the 11
# whole 2 s windows being about 0.5, noise density sqrt(2 mean(m_i^2)) = 0.7068 N sqrt(s) (a
# density needs 10 windows); no memory, so correlation time 0. The validator's noise from second
# differences, median(|d2|) / (0.67449 sqrt 6), is 2.421 (c1) and 0.6047 (c2, c3) on these
# readings (n is anticorrelated, not Gaussian: the values are these formulas over the CSV,
# computed apart with Python's statistics module). Calibrated, the CUSUM stays quiet on the clean
# log and flags a -20 N offset on c1 from 1 s, which the classifier names.
stat_log() {  # stat_log FAULT_N FILE
  awk -v fault="$1" 'BEGIN { print "time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N";
    for (k = 0; k < 22000; k++) { t = k / 1000; l = 100 + 50 * sin(6.28318531 * t); u = 0.6180339887 * k; n = u - int(u) - 0.5;
      printf "%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", t, l + 0.5 + 4 * n + (t >= 1 ? fault : 0), l + n, l - n, l, l, l } }' > "$2"
}
stat_log 0 "$work/stat_clean.csv"; stat_log -20 "$work/stat_faulty.csv"
cat > "$work/statistics.json" <<'JSON'
{
 "sample_period_s": 0.001,
 "inputs": {
  "cell": {
   "columns": [
    "cell/c1/force_N",
    "cell/c2/force_N",
    "cell/c3/force_N"
   ],
   "unit": "N"
  },
  "model": {
   "columns": [
    "model/c1/force_N",
    "model/c2/force_N",
    "model/c3/force_N"
   ],
   "unit": "N"
  }
 },
 "stages": [
  {
   "name": "residual",
   "plugin": "difference_residual",
   "inputs": {
    "measured": "input.cell",
    "virtual": "input.model"
   }
  },
  {
   "name": "validate",
   "plugin": "signal_validator",
   "inputs": {
    "signal": "input.cell"
   }
  },
  {
   "name": "cusum",
   "plugin": "cusum_detector",
   "params": {
    "min_change": [
     10.0,
     1.0,
     1.0
    ]
   },
   "inputs": {
    "residual": "residual.residual"
   }
  },
  {
   "name": "classify",
   "plugin": "fault_classifier",
   "inputs": {
    "fault": "cusum.fault",
    "measured": "input.cell",
    "virtual": "input.model"
   }
  },
  {
   "name": "recover",
   "plugin": "fault_recovery",
   "params": {
    "correction": "when_flagged"
   },
   "inputs": {
    "measured": "input.cell",
    "fault_estimate": "classify.fault_estimate",
    "virtual": "input.model",
    "fault": "cusum.fault",
    "fault_type": "classify.fault_type"
   }
  }
 ],
 "monitor": {
  "channels": [
   "c1",
   "c2",
   "c3"
  ],
  "measured": "input.cell",
  "virtual": "input.model",
  "fault": "cusum.fault",
  "fault_type": "classify.fault_type",
  "fault_estimate": "classify.fault_estimate",
  "recovered": "recover.recovered"
 }
}
JSON
"$ftsense" calibrate --config "$work/statistics.json" --input "$work/stat_clean.csv" --output "$work/statistics_cal.json" > "$work/out" 2> "$work/err"
check calibrate_statistics 0 $? "^ftsense calibrate: cusum: noise_std 1\.155 0\.2887 0\.2887$" "$work/out" \
  "^ftsense calibrate: validate: noise_std 2\.421 0\.6047 0\.6047$" "$work/out" \
  "^ftsense calibrate: cusum: centers 0\.4998 " "$work/out" "^ftsense calibrate: cusum: correlation_time_s 0$" "$work/out" \
  "^ftsense calibrate: classify: residual_noise_density 0\.7068 " "$work/out" '"residual_noise_density"' "$work/statistics_cal.json"
"$ftsense" run --config "$work/statistics.json" --thresholds "$work/statistics_cal.json" --input "$work/stat_clean.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check run_with_calibrated_statistics 0 $? "^  no channel flagged$" "$work/out"
"$ftsense" run --config "$work/statistics.json" --thresholds "$work/statistics_cal.json" --input "$work/stat_faulty.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check calibrated_cusum_flags_and_the_classifier_types 0 $? "c1: fault first flagged at t = 1 s; fault types unclassified, offset$" "$work/out"
printf '{"stages": {"cusum": {"centres": [1.0]}}}\n' > "$work/bad_cal.json"
"$ftsense" run --config "$work/statistics.json" --thresholds "$work/bad_cal.json" --input "$work/stat_clean.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check calibration_entry_without_values 2 $? 'bad_cal.json:/stages/cusum: has neither "thresholds" nor "params"' "$work/err"
# c2 read exactly as its model: a zero noise level would flag any change, so nothing is written.
awk -F, 'BEGIN { OFS = "," } NR > 1 { $3 = $6 } { print }' "$work/stat_clean.csv" > "$work/stat_exact.csv"
"$ftsense" calibrate --config "$work/statistics.json" --input "$work/stat_exact.csv" --output "$work/x.json" > "$work/out" 2> "$work/err"
check calibrate_refuses_a_constant_residual 1 $? "cusum noise_std channel 1: is 0: the signal did not vary" "$work/err" \
  "classify residual_noise_density channel 1: is 0" "$work/err" "nothing written" "$work/err"
[ ! -e "$work/x.json" ] && { passes=$((passes + 1)); echo "ok   calibrate_refusal_writes_nothing"; } \
  || { failures=$((failures + 1)); echo "FAIL calibrate_refusal_writes_nothing"; }
# A bad value in a calibration file is reported as coming from it.
printf '{"stages": {"cusum": {"params": {"noise_std": [-1.0]}}}}\n' > "$work/negative_cal.json"
"$ftsense" run --config "$work/statistics.json" --thresholds "$work/negative_cal.json" --input "$work/stat_clean.csv" --output "$work/o.csv" > "$work/out" 2> "$work/err"
check calibration_value_blamed_on_its_file 2 $? "statistics.json:/stages/2/params/noise_std/0 = -1\.0 violates > 0 .*\(the value comes from .*negative_cal.json; calibrate again or fix it there\)" "$work/err"
# What the config gives is the user's: kept, not measured (the way out of a refusal).
sed 's/"plugin": "signal_validator",/"plugin": "signal_validator", "params": {"noise_std": [2.0], "resolution": [0.0]},/' "$work/statistics.json" > "$work/given.json"
"$ftsense" calibrate --config "$work/given.json" --input "$work/stat_clean.csv" --output "$work/given_cal.json" > "$work/out" 2> "$work/err"
check calibrate_keeps_what_the_config_gives 0 $? "^ftsense calibrate: validate: noise_std given in the config, kept$" "$work/out"
grep -q '"validate"' "$work/given_cal.json" && { failures=$((failures + 1)); echo "FAIL calibrate_keeps_writes_no_entry"; } \
  || { passes=$((passes + 1)); echo "ok   calibrate_keeps_writes_no_entry"; }
# A step isolator with a guard (step_isolator.hpp): calibrate measures how far each residual row
# moves across the guards (guard_step_std). A log with no guard writes 0 (steps inside a guard
# are not judged) with a warning, rather than refusing the rest.
guard_log() {  # guard_log PERIOD_TICKS FILE: the clean log with a guard on every channel, on for
  # 50 ticks of every PERIOD_TICKS (0: never)
  awk -F, -v period="$1" 'NR == 1 { print $0 ",guard/c1,guard/c2,guard/c3"; next }
    { k = NR - 2; g = (period > 0 && k % period < 50) ? 1 : 0; print $0 "," g "," g "," g }' "$work/stat_clean.csv" > "$2"
}
guard_log 0 "$work/guard_never.csv"; guard_log 500 "$work/guard_often.csv"
cat > "$work/guarded.json" <<'JSON'
{
 "sample_period_s": 0.001,
 "inputs": {
  "cell": {"columns": ["cell/c1/force_N", "cell/c2/force_N", "cell/c3/force_N"], "unit": "N"},
  "model": {"columns": ["model/c1/force_N", "model/c2/force_N", "model/c3/force_N"], "unit": "N"},
  "guard": {"columns": ["guard/c1", "guard/c2", "guard/c3"], "unit": "1"}
 },
 "stages": [
  {"name": "residual", "plugin": "difference_residual", "inputs": {"measured": "input.cell", "virtual": "input.model"}},
  {"name": "detect", "plugin": "threshold_detector", "inputs": {"signal": "residual.residual"}},
  {"name": "step", "plugin": "step_isolator", "params": {"guard": true},
   "inputs": {"signal": "input.cell", "residual": "residual.residual", "alarm": "detect.fault", "guard": "input.guard"}}
 ],
 "monitor": {"channels": ["c1", "c2", "c3"], "measured": "input.cell", "virtual": "input.model",
             "fault_estimate": "step.fault_estimate", "recovered": "input.model", "fault": "step.fault",
             "fault_type": "step.fault_type"}
}
JSON
"$ftsense" calibrate --config "$work/guarded.json" --input "$work/guard_never.csv" --output "$work/guard_never_cal.json" > "$work/out" 2> "$work/err"
check calibrate_without_guards_writes_zero 0 $? \
  "^warning: ftsense calibrate: step guard_step_std channel 0: no guard \(input guard nonzero\) with 10 finite unguarded samples on each side after the warm-up; written as 0" "$work/err" \
  "^ftsense calibrate: step: guard_step_std 0 0 0$" "$work/out"
"$ftsense" calibrate --config "$work/guarded.json" --input "$work/guard_often.csv" --output "$work/guard_often_cal.json" > "$work/out" 2> "$work/err"
check calibrate_with_guards_measures_them 0 $? "^ftsense calibrate: step: guard_step_std [0-9.]+ [0-9.]+ [0-9.]+$" "$work/out"
grep -q "guard_step_std 0 " "$work/out" && { failures=$((failures + 1)); echo "FAIL calibrate_with_guards_nonzero"; } \
  || { passes=$((passes + 1)); echo "ok   calibrate_with_guards_nonzero"; }
# Calibrated on a second run with the first run's values in place: a range test at its default
# noise (1 N) flags a healthy 3 N reading at rest below its floor (0 N) on about 0.2 % of the
# ticks, which a CUSUM watching those flags would take for their centre; on the second run, with
# the reading's noise measured, nothing is flagged and the centre is exactly 0.
awk 'BEGIN { srand(7); print "time_s,pad/p1/force_N,pad/p2/force_N";
  for (k = 0; k < 20000; k++) { printf "%.3f", k / 1000;
    for (j = 0; j < 2; j++) { u = rand(); v = rand(); if (u < 1e-12) u = 1e-12;
      printf ",%.6f", 3 * sqrt(-2 * log(u)) * cos(6.283185307 * v) }
    printf "\n" } }' > "$work/rest.csv"
cat > "$work/second_run.json" <<'JSON'
{
 "sample_period_s": 0.001,
 "inputs": {"pad": {"columns": ["pad/p1/force_N", "pad/p2/force_N"], "unit": "N"}},
 "stages": [
  {"name": "pressed", "plugin": "physical_range_detector", "params": {"floor": [0.0]},
   "inputs": {"signal": "input.pad"}},
  {"name": "watch", "plugin": "cusum_detector",
   "params": {"noise_std": [1.0], "correlation_time_s": 0.0, "min_change": [0.5]},
   "inputs": {"residual": "pressed.fault"}}
 ]
}
JSON
"$ftsense" calibrate --config "$work/second_run.json" --input "$work/rest.csv" --output "$work/second_run_cal.json" > "$work/out" 2> "$work/err"
check calibrate_measures_on_a_second_run 0 $? "^ftsense calibrate: watch: centers 0 0$" "$work/out" \
  "^ftsense calibrate: pressed: noise_std (2\.9|3\.0)[0-9]* (2\.9|3\.0)[0-9]*$" "$work/out" \
  "^ftsense calibrate: measured again with the first run's values in place: largest change 100 % \(watch centers channel [01]\)$" "$work/out"
# A density needs 10 whole windows of 2 s: a 3 s log is refused, saying how long a log it takes.
head -3001 "$work/stat_clean.csv" > "$work/stat_short.csv"
"$ftsense" calibrate --config "$work/statistics.json" --input "$work/stat_short.csv" --output "$work/x.json" > "$work/out" 2> "$work/err"
check calibrate_refuses_a_short_density 1 $? "classify residual_noise_density channel 0: 1 whole windows of 2 s after the warm-up, fewer than 10; calibrate on at least 20 s" "$work/err"

# Determinism: the same log and config give byte-identical output.
"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/d1.csv" > /dev/null 2>&1
"$ftsense" run --config "$good" --input "$work/log.csv" --output "$work/d2.csv" > /dev/null 2>&1
cmp -s "$work/d1.csv" "$work/d2.csv" && { passes=$((passes + 1)); echo "ok   run_is_deterministic"; } \
  || { failures=$((failures + 1)); echo "FAIL run_is_deterministic: two runs differ"; }

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
