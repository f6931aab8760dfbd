#!/usr/bin/env bash
# Wrong numbers refused (docs/reliability.md, issue 15 finding 9): calibrate, report and run do not
# compute what they cannot honestly compute. One table row per case: command, expected exit
# status, expected message; and the output file must not exist afterwards.
#   usage: check_wrong_numbers.sh FTSENSE SOURCE_DIR
set -u
ftsense=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
cfg="$src/tests/cli/good.json"
header="time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N"
# log NAME ROWS STEP_AFTER_100 C2_EXPRESSION: a 1 kHz log (then STEP s per row), seed 1 noise.
log() {
  awk -v rows="$2" -v step="$3" -v header="$header" "BEGIN { print header; srand(1); t = 0;
    for (k = 0; k < rows; k++) { n = rand() - 0.5; c2 = $4;
      printf \"%.4f,%.4f,%.4f,%.4f,100,100,100\\n\", t, 100 + n, c2, 100 + n; t += (k < 100 ? 0.001 : step) } }" > "$work/$1"
}
log clean.csv 3000 0.001 "100 + n"
log burst.csv 3000 0.001 "100 + n + ((t >= 1.5 && t < 1.7) ? 1e12 : 0)"
log nan.csv 3000 0.001 "\"nan\""
log rate_change.csv 2000 0.002 "100 + n"
"$ftsense" run --config "$cfg" --input "$work/clean.csv" --output "$work/run.csv" > /dev/null
log other.csv 3000 0.001 "100 + n"
sed -i '2s/^0.0000/-0.0005/' "$work/other.csv"  # same rows, another log

row() {  # name | expected status | message on stderr (ERE; - for none) | command...
  local name=$1 status=$2 message=$3
  shift 3
  rm -f "$work/out.json" "$work/out.csv"
  "$@" > "$work/stdout" 2> "$work/err"
  local actual=$? ok=1
  [ "$actual" -eq "$status" ] || { echo "FAIL $name: exit $actual, expected $status"; ok=0; }
  [ "$message" = "-" ] || grep -qE -- "$message" "$work/err" || { echo "FAIL $name: '$message' not in stderr:"; sed 's/^/    /' "$work/err" | head -5; ok=0; }
  if [ -e "$work/out.json" ] || [ -e "$work/out.csv" ]; then echo "FAIL $name: an output was written"; ok=0; fi
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

row calibrate_on_a_burst 1 "channel 1: max \|signal\| .* at t = 1\.[67][0-9]* s is more than 1000 x its median" \
    "$ftsense" calibrate --config "$cfg" --input "$work/burst.csv" --output "$work/out.json"
row calibrate_input_never_varies 1 "channel 1: the signal was 0 throughout, so the threshold would be 0" \
    "$ftsense" calibrate --config "$cfg" --input "$work/nan.csv" --output "$work/out.json"
row calibrate_absurd_margin 2 "--margin = '1e308' violates >= 1 and <= 1000" \
    "$ftsense" calibrate --config "$cfg" --input "$work/clean.csv" --output "$work/out.json" --margin 1e308
row run_rate_changes_mid_log 1 "rate_change.csv:[0-9]+: from this line the log is sampled every 0.002 s" \
    "$ftsense" run --config "$cfg" --input "$work/rate_change.csv" --output "$work/out.csv"
row report_truth_of_another_log 2 "other.csv: row 2 has time_s = (-5e-04|-0.0005) but .*run.csv has 0; give the log the run was made from" \
    "$ftsense" report --run "$work/run.csv" --truth "$work/other.csv" --out "$work/report" --no-figures
printf '%s\n0,1,1,1,1,1,1\n0.001,1,1,1,1,1,1\n0.002,1,1,1,1,1,1\n0.003,1,1,1,1,1,1\n0.004,1,1,1,1,1,1\n0.005,1,1' "$header" > "$work/cut.csv"
row run_last_row_cut 1 "cut.csv:7: the last row has no line end" \
    "$ftsense" run --config "$cfg" --input "$work/cut.csv" --output "$work/out.csv"
# A calibration on the clean log still works (the gates do not refuse honest data).
row calibrate_clean_log_passes 0 - "$ftsense" calibrate --config "$cfg" --input "$work/clean.csv" --output "$work/clean.json"
[ -s "$work/clean.json" ] && { passes=$((passes + 1)); echo "ok   calibrate_clean_log_wrote_thresholds"; } \
  || { failures=$((failures + 1)); echo "FAIL calibrate_clean_log_wrote_thresholds"; }

echo "wrong numbers: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
