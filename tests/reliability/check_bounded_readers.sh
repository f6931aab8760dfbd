#!/usr/bin/env bash
# Every reader bounded (docs/reliability.md, issue 15 findings 2 and 11): a device, a directory,
# a loop of symbolic links or a huge file given as a config, URDF, thresholds, faults file,
# scenario or log is refused at once (exit 2) with what it is, before anything is read into
# memory. One table row per case; each command must end within 20 s.
#   usage: check_bounded_readers.sh FTSENSE SOURCE_DIR
set -u
ftsense=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
cfg="$src/tests/cli/good.json"
printf 'time_s,cell/c1/force_N,cell/c2/force_N,cell/c3/force_N,model/c1/force_N,model/c2/force_N,model/c3/force_N\n0,1,1,1,1,1,1\n0.001,1,1,1,1,1,1\n' > "$work/log.csv"
ln -s loop_b "$work/loop_a"
ln -s loop_a "$work/loop_b"
truncate -s 65M "$work/huge.json"  # sparse: costs no disk
sed 's#"urdf": "[^"]*"#"urdf": "/dev/zero"#' "$src/configs/icub.json" > "$work/icub_dev_zero.json"
sed 's#"urdf": "[^"]*"#"urdf": "'"$work"'"#' "$src/configs/icub.json" > "$work/icub_dir.json"

# name | message (ERE) | command...
row() {
  local name=$1 message=$2
  shift 2
  local status ok=1
  timeout 20 "$@" > "$work/out" 2> "$work/err"
  status=$?
  [ "$status" -eq 2 ] || { echo "FAIL $name: exit $status, expected 2"; ok=0; }
  grep -qE -- "$message" "$work/err" || { echo "FAIL $name: '$message' not in stderr:"; sed 's/^/    /' "$work/err" | head -5; ok=0; }
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

row config_is_a_device "/dev/zero: is not a regular file" "$ftsense" check --config /dev/zero
row config_is_a_directory "is a directory, not a config file" "$ftsense" check --config "$work"
row config_is_a_link_loop "loop of symbolic links" "$ftsense" check --config "$work/loop_a"
row config_is_huge "huge.json: is 68157440 bytes; a config file is at most 64 MiB" "$ftsense" check --config "$work/huge.json"
row urdf_is_a_device "/dev/zero: is not a regular file" "$ftsense" check --config "$work/icub_dev_zero.json"
row urdf_is_a_directory "is a directory, not a URDF" "$ftsense" check --config "$work/icub_dir.json"
row thresholds_is_a_device "/dev/zero: is not a regular file" \
    "$ftsense" run --config "$cfg" --thresholds /dev/zero --input "$work/log.csv"
row log_is_a_device "/dev/zero: is not a regular file or a pipe" "$ftsense" run --config "$cfg" --input /dev/zero
row log_is_a_directory "is a directory, not a log file" "$ftsense" run --config "$cfg" --input "$work"
row log_is_a_link_loop "loop of symbolic links" "$ftsense" run --config "$cfg" --input "$work/loop_a"
row faults_is_a_device "/dev/zero: is not a regular file" \
    "$ftsense" inject --input "$work/log.csv" --faults /dev/zero --output "$work/o.csv"

# Scenarios go through the same strict JSON reader as configs (finding 1; 11: 1e400).
awk 'BEGIN { for (i = 0; i < 100000; i++) printf "["; for (i = 0; i < 100000; i++) printf "]"; print "" }' > "$work/deep.json"
printf '{"duration_s": 5, "duration_s": 3600, "gait": {}, "faults": []}\n' > "$work/duplicate.json"
printf '{"duration_s": 1e400, "gait": {}, "faults": []}\n' > "$work/overflow.json"
row scenario_nested_deep "deep.json:1:101: not valid JSON: nested deeper than 100" \
    "$ftsense" simulate --scenario "$work/deep.json" --out "$work/sim.csv" --quiet
row scenario_duplicate_key "/duration_s: duplicate key 'duration_s'" \
    "$ftsense" simulate --scenario "$work/duplicate.json" --out "$work/sim.csv" --quiet
row scenario_number_overflow "overflow.json:1:16: not valid JSON: number overflow parsing '1e400'" \
    "$ftsense" simulate --scenario "$work/overflow.json" --out "$work/sim.csv" --quiet
row scenario_is_a_device "/dev/zero: is not a regular file" \
    "$ftsense" simulate --scenario /dev/zero --out "$work/sim.csv" --quiet
[ ! -e "$work/sim.csv" ] && { passes=$((passes + 1)); echo "ok   refused_scenarios_wrote_nothing"; } \
  || { failures=$((failures + 1)); echo "FAIL refused_scenarios_wrote_nothing"; }

echo "bounded readers: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
