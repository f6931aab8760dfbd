#!/usr/bin/env bash
# check_plot_run.sh FTSENSE PYTHON PYTHONPATH SOURCE_DIR
# Runs python/examples/plot_run.py on a simulated walk with an offset and checks that it draws
# the flagged channel (and only it) into a PNG.
set -eu
ftsense=$1
python=$2
pythonpath=$3
source=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$ftsense" simulate --scenario "$source/python/tests/offset_walk.json" --out "$work/log.csv" --quiet > /dev/null
PYTHONPATH="$pythonpath" "$python" "$source/python/examples/plot_run.py" "$source/configs/suralp_robust.json" \
  "$work/log.csv" --out "$work/run.png" > "$work/stdout"
cat "$work/stdout"
grep -qx "wrote $work/run.png (channels: r_foot/p2)" "$work/stdout" || { echo "FAIL: expected the flagged channel r_foot/p2 alone"; exit 1; }
[ "$(head -c 8 "$work/run.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "FAIL: $work/run.png is not a PNG"; exit 1; }
[ "$(stat -c %s "$work/run.png")" -gt 20000 ] || { echo "FAIL: $work/run.png is nearly empty"; exit 1; }
echo "ok: plot_run.py drew r_foot/p2 ($(stat -c %s "$work/run.png") bytes)"
