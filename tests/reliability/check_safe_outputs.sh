#!/usr/bin/env bash
# Nothing lost, nothing broken (docs/reliability.md, issue 15 findings 3-5 and 10): an output that is, or links to, an
# input is refused before anything is written and the input stays intact; a run that fails
# (before its first tick, or at a bad row mid-file) keeps the previous result of the same name;
# an interrupted run (SIGTERM, SIGINT) leaves no file under the final name and no temporary file.
# One table row per case: command, expected exit status, expected message, file that must be
# unchanged (or must not exist).
#   usage: check_safe_outputs.sh FTSENSE SOURCE_DIR
set -u
ftsense=$1
src=$2
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
failures=0
passes=0
cfg="$src/tests/cli/good.json"

awk 'BEGIN { print "time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N";
  for (k = 0; k < 2000; k++) { t = k / 1000; printf "%.3f,100,100,100,100,100,100\n", t } }' > "$work/log.csv"
head -1 "$work/log.csv" > "$work/header_only.csv"
{ head -1001 "$work/log.csv"; echo "1.000,100,oops,100,100,100,100"; tail -n +1002 "$work/log.csv"; } > "$work/bad_row.csv"
ln -s log.csv "$work/link_to_log.csv"
cp "$src/configs/scenarios/clean.json" "$work/scenario.json"
printf '{"seed": 1, "channels": {"c1": "cell/c1/force_N"}, "faults": [{"channel": "c1", "type": "offset", "start_s": 1.0, "offset_N": 50}]}\n' > "$work/faults.json"
echo "previous result" > "$work/previous.csv"

fingerprint() { [ -e "$1" ] && sha256sum < "$1" || echo absent; }

# name | expected status | message on stderr (ERE; - for none) | file that must keep its content | command...
row() {
  local name=$1 status=$2 message=$3 keep=$4
  shift 4
  local before after actual ok=1
  before=$(fingerprint "$keep")
  "$@" > "$work/out" 2> "$work/err"
  actual=$?
  after=$(fingerprint "$keep")
  [ "$actual" -eq "$status" ] || { echo "FAIL $name: exit $actual, expected $status"; ok=0; }
  [ "$message" = "-" ] || grep -qE -- "$message" "$work/err" || { echo "FAIL $name: '$message' not in stderr:"; sed 's/^/    /' "$work/err"; ok=0; }
  [ "$before" = "$after" ] || { echo "FAIL $name: $(basename "$keep") changed"; ok=0; }
  if ls "$work" | grep -q '\.partial-'; then echo "FAIL $name: a temporary file was left: $(ls "$work" | grep '\.partial-')"; ok=0; fi
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

row run_output_is_input 2 "is the input .*log.csv" "$work/log.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/log.csv"
row run_output_links_to_input 2 "is the input" "$work/log.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/link_to_log.csv"
row run_output_is_config 2 "is the input .*good.json" "$cfg" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$cfg"
row run_output_is_directory 2 "is a directory" "$work/log.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work"
row inject_output_is_input 2 "is the input" "$work/log.csv" \
    "$ftsense" inject --input "$work/log.csv" --faults "$work/faults.json" --output "$work/log.csv"
row inject_output_is_faults_file 2 "is the input" "$work/faults.json" \
    "$ftsense" inject --input "$work/log.csv" --faults "$work/faults.json" --output "$work/faults.json"
row calibrate_output_is_input 2 "is the input" "$work/log.csv" \
    "$ftsense" calibrate --config "$cfg" --input "$work/log.csv" --output "$work/log.csv"
row simulate_out_is_scenario 2 "is the input" "$work/scenario.json" \
    "$ftsense" simulate --scenario "$work/scenario.json" --out "$work/scenario.json" --quiet
row run_header_only_keeps_previous_result 1 "no data rows|empty|header" "$work/previous.csv" \
    "$ftsense" run --config "$cfg" --input "$work/header_only.csv" --output "$work/previous.csv"
row run_bad_row_keeps_previous_result 1 "bad_row.csv:1002" "$work/previous.csv" \
    "$ftsense" run --config "$cfg" --input "$work/bad_row.csv" --output "$work/previous.csv"
row run_bad_row_writes_nothing 1 "bad_row.csv:1002" "$work/new.csv" \
    "$ftsense" run --config "$cfg" --input "$work/bad_row.csv" --output "$work/new.csv"
# A full disk, made by a file-size limit of 64 KiB (SIGXFSZ ignored, so write fails with EFBIG as
# it would with ENOSPC): the write fails before the rename, the previous result stays.
row run_disk_full_keeps_previous_result 1 "writing failed \(disk full\?\); nothing was written" "$work/previous.csv" \
    bash -c 'ulimit -f 64; trap "" XFSZ; exec "$@"' full_disk "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/previous.csv"
row run_success_replaces_previous 0 - "$work/log.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/previous.csv"
grep -q "c1/measured_N" "$work/previous.csv" && { passes=$((passes + 1)); echo "ok   run_success_wrote_the_result"; } \
  || { failures=$((failures + 1)); echo "FAIL run_success_wrote_the_result"; }

# Broken outputs (finding 10): nothing is written that ftsense's own reader would refuse.
for bad in 'c,1' 'c\\n1' 'c\\u00001' ' c1'; do
  sed "s#\"channels\": \[\"c1\"#\"channels\": [\"$bad\"#" "$cfg" > "$work/bad_channel.json"
  row "monitor_channel_$(printf '%s' "$bad" | tr -c 'a-z0-9' '_')" 2 "/monitor/channels/0 = .*(comma|control character|space)" \
      "$work/log.csv" "$ftsense" check --config "$work/bad_channel.json"
done
row record_twice 2 "column 'detect.fault/0' twice" "$work/new.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/new.csv" --record detect.fault,detect.fault
printf '{"channels": {"t": "time_s"}, "faults": [{"channel": "t", "type": "offset", "start_s": 1.0, "offset_N": 1}]}\n' > "$work/faults_time.json"
row inject_into_time 2 "is the log's time, not a sensor" "$work/new.csv" \
    "$ftsense" inject --input "$work/log.csv" --faults "$work/faults_time.json" --output "$work/new.csv"
sed '1s#$#,truth/c1/force_N#; 2,$s#$#,100#' "$work/log.csv" > "$work/sim_like.csv"
printf '{"channels": {"c1": "cell/c1/force_N"}, "faults": [{"channel": "c1", "type": "offset", "start_s": 1.0, "offset_N": 1}]}\n' > "$work/faults_c1.json"
row inject_truth_column_exists 2 "already has a column 'truth/c1/force_N'" "$work/new.csv" \
    "$ftsense" inject --input "$work/sim_like.csv" --faults "$work/faults_c1.json" --output "$work/new.csv"
printf '{"channels": {"x": "truth/c1/force_N"}, "faults": [{"channel": "x", "type": "offset", "start_s": 1.0, "offset_N": 1}]}\n' > "$work/faults_truth.json"
row inject_into_truth 2 "is the log's ground truth" "$work/new.csv" \
    "$ftsense" inject --input "$work/sim_like.csv" --faults "$work/faults_truth.json" --output "$work/new.csv"
printf '{"channels": {"c1": "cell/c1/force_N"}, "faults": [{"channel": "c1", "type": "offset", "start_s": 50.0, "offset_N": 1}]}\n' > "$work/faults_late.json"
row inject_fault_after_the_end 2 "/faults/0/start_s = 50 is after the log's last row \(t = 1.999 s\)" "$work/new.csv" \
    "$ftsense" inject --input "$work/log.csv" --faults "$work/faults_late.json" --output "$work/new.csv"

# Messages that name the right cause (finding 11), and standard input and output as '-'.
row output_is_dev_stdout 2 "/dev/stdout: output is not a regular file .* or '-' for standard output" "$work/log.csv" \
    "$ftsense" run --config "$cfg" --input "$work/log.csv" --output /dev/stdout
"$ftsense" run --config "$cfg" --input "$work/log.csv" --output "$work/previous.csv" > /dev/null
row report_out_is_a_file 2 "previous.csv: --output is a folder .* and this is a file" "$work/previous.csv" \
    "$ftsense" report --run "$work/previous.csv" --out "$work/previous.csv" --no-figures
: > "$work/empty.csv"
row run_empty_log 2 "empty.csv:1: the file is empty" "$work/empty.csv" \
    "$ftsense" run --config "$cfg" --input "$work/empty.csv"
"$ftsense" run --config "$cfg" --input - --output - < "$work/log.csv" > "$work/stdout.csv" 2> "$work/err"
status=$?
if [ $status -eq 0 ] && head -1 "$work/stdout.csv" | grep -q '^time_s,c1/measured_N' && [ "$(wc -l < "$work/stdout.csv")" -eq 2001 ] \
   && grep -q "2000 ticks, 3 channels -> -" "$work/err" && cmp -s "$work/stdout.csv" "$work/previous.csv"; then
  passes=$((passes + 1)); echo "ok   stdin_to_stdout_with_the_summary_on_stderr"
else
  failures=$((failures + 1)); echo "FAIL stdin_to_stdout_with_the_summary_on_stderr: status $status"; cat "$work/err"
fi

# Interrupted mid-run: the log arrives through a pipe that stays open, so the run is surely still
# reading when the signal comes; afterwards nothing is under the final name and no temporary file
# is left.
for sig in TERM INT; do
  rm -f "$work/feed" "$work/interrupted.csv"
  mkfifo "$work/feed"
  ( cat "$work/log.csv"; exec sleep 60 ) > "$work/feed" &
  feeder=$!
  "$ftsense" run --config "$cfg" --input "$work/feed" --output "$work/interrupted.csv" > "$work/out" 2> "$work/err" &
  runner=$!
  for _ in $(seq 100); do ls "$work" | grep -q 'interrupted.csv.partial-' && break; sleep 0.05; done
  sleep 0.3
  kill -s "$sig" "$runner"
  wait "$runner"
  status=$?
  kill "$feeder" 2>/dev/null; wait "$feeder" 2>/dev/null
  if [ "$status" -ne 0 ] && [ ! -e "$work/interrupted.csv" ] && ! ls "$work" | grep -q '\.partial-'; then
    passes=$((passes + 1)); echo "ok   run_interrupted_by_SIG${sig}_leaves_nothing"
  else
    failures=$((failures + 1))
    echo "FAIL run_interrupted_by_SIG${sig}: status $status; files: $(ls "$work" | tr '\n' ' ')"
  fi
done

echo "safe outputs: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
