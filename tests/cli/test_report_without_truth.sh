#!/usr/bin/env bash
# `ftsense report` without --truth (every real log): the alarms are listed, not scored, and the
# figures draw the flagged channels (issue 16 acceptance 3).
#   1. A simulated walk with faults on r_foot/p2 and r_foot/p4 (the 6th and 8th of 8 channels),
#      run by the robust pipeline and reported without its truth: the wording, the alarm rows,
#      and figures.json / figures.gp draw exactly the flagged channels, filled up to 4 panels with
#      channels marked "not flagged".
#   2. The real iCub log (clean), paper pipeline with calibrated thresholds: "No channel flagged".
# usage: test_report_without_truth.sh FTSENSE ROOT
set -u
ftsense=$1
root=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passes=0
failures=0
ok() { passes=$((passes + 1)); echo "ok   $1"; }
bad() { failures=$((failures + 1)); echo "FAIL $1"; }

"$ftsense" simulate --scenario "$root/tests/robust/saturation_offset_in_air.json" --out "$work/log.csv" --quiet > /dev/null \
  || { echo "FAIL: simulate"; exit 1; }
"$ftsense" run --config "$root/configs/suralp_robust.json" --input "$work/log.csv" --output "$work/run.csv" > /dev/null \
  || { echo "FAIL: run"; exit 1; }
"$ftsense" report --run "$work/run.csv" --out "$work/report" > "$work/stdout" 2> "$work/stderr" \
  && ok "report without truth exits 0" || { bad "report exit $?"; cat "$work/stderr"; }
cat "$work/stdout"

# Wording: listed, not scored; never "detected 0 of 0" nor false alarms.
grep -q "^No truth given: the alarms are listed, not scored.$" "$work/stdout" && ok "stdout says not scored" || bad "stdout wording"
grep -Eq "^[0-9]+ alarms? on [0-9]+ of 8 channels after the 2 s warm-up; not scored" "$work/stdout" \
  && ok "stdout closing line counts alarms" || bad "stdout closing line"
for f in "$work/stdout" "$work/report/report.md" "$work/report/report.html"; do
  if grep -Eqi "faulty channels|false alarms after|detected [0-9]+ of" "$f"; then bad "scored wording in $(basename "$f")"
  else ok "no scored wording in $(basename "$f")"; fi
done
grep -q "| channel | alarm from \[s\] | to \[s\] | duration \[s\] | type named |" "$work/report/report.md" \
  && ok "report.md lists the alarms" || bad "report.md alarm table"

# The alarms, the flagged channels and what the figures draw, from the files themselves.
/usr/bin/python3 - "$work/report" <<'PY' && ok "figures draw the flagged channels" || bad "figures' channel choice"
import json, re, sys
d = sys.argv[1]
metrics = json.load(open(f"{d}/metrics.json"))
manifest = json.load(open(f"{d}/figures.json"))
md = open(f"{d}/report.md").read()
script = open(f"{d}/figures.gp").read()
fail = []
assert metrics["summary"]["scored"] is False, metrics["summary"]
flagged = sorted({a["channel"] for a in metrics["alarms"]})
print("flagged:", flagged)
if not {"r_foot/p2", "r_foot/p4"} <= set(flagged): fail.append(f"the faulty channels are not all flagged: {flagged}")
for a in metrics["alarms"]:
    row = re.search(r"^\| %s \| %.3f \| [^|]+ \| [^|]+ \| (\w+) \|$" % (re.escape(a["channel"]), a["start_s"]), md, re.M)
    if not row: fail.append(f"no report.md row for alarm {a}")
    elif row.group(1) != a["type"] or a["type"] in ("none", "-"): fail.append(f"type named {row.group(1)} vs {a['type']}")
if manifest["truth"] is not False: fail.append("figures.json says truth")
kinds = {f["kind"]: f for f in manifest["figures"]}
if set(kinds) != {"virtual_sensor", "fault_estimate", "recovered", "flags", "fault_types"}: fail.append(f"kinds {sorted(kinds)}")
v = kinds["virtual_sensor"]
if v["file"] != "fig4_virtual_vs_measured.png" or not v["title"].startswith("Virtual vs measured"): fail.append(f"fig4: {v}")
if not kinds["fault_estimate"]["title"].startswith("Estimated fault"): fail.append(f"fig5: {kinds['fault_estimate']['title']}")
expected_panels = max(4, len(flagged))
for k in ("virtual_sensor", "fault_estimate", "recovered"):
    ch = kinds[k]["channels"]
    if len(ch) != expected_panels: fail.append(f"{k}: {len(ch)} panels, expected {expected_panels}")
    if not set(flagged) <= set(ch): fail.append(f"{k}: flagged {flagged} not all drawn: {ch}")
    for c in ch:
        why = kinds[k]["why"][c]
        if (c in flagged) != why.startswith("flagged"): fail.append(f"{k}: {c}: why '{why}'")
    # The script draws those panels, titled by channel, and no truth series.
    titles = re.findall(r"^set title '([^ ]+) \(", script, re.M)
    if not all(c in titles for c in ch): fail.append(f"figures.gp titles {titles} lack {ch}")
if ch == ["l_foot/p1", "l_foot/p2", "l_foot/p3", "l_foot/p4"]: fail.append("draws the first four channels")
if re.search(r"title '(true|injected \(measured - true\))'", script): fail.append("figures.gp draws a truth series")
print("\n".join(fail))
sys.exit(1 if fail else 0)
PY
for png in fig4_virtual_vs_measured.png fig5_fault_estimate.png fig6_recovered_vs_measured.png fig7_detection_flags.png fig8_fault_types.png; do
  [ "$(head -c 8 "$work/report/$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] && ok "$png is a PNG" || bad "$png"
done
[ ! -e "$work/report/fig4_virtual_vs_true.png" ] && ok "no 'virtual vs true' figure" || bad "fig4_virtual_vs_true.png written without truth"
grep -q '<img alt="Virtual vs measured' "$work/report/report.html" && ok "report.html embeds the figures" || bad "report.html"

# A real log, clean: nothing flagged, said so.
log="$root/data/icub_walking/icub_walking.csv"
"$ftsense" calibrate --config "$root/configs/icub.json" --input "$log" --output "$work/thresholds.json" > /dev/null 2>&1
"$ftsense" run --config "$root/configs/icub.json" --thresholds "$work/thresholds.json" --input "$log" \
  --output "$work/icub_run.csv" > /dev/null 2>&1
"$ftsense" report --run "$work/icub_run.csv" --thresholds "$work/thresholds.json" --out "$work/icub" > "$work/icub_stdout" 2>&1
grep -q "^No channel flagged after the 2 s warm-up (2 channels).$" "$work/icub_stdout" && ok "iCub: no channel flagged" \
  || { bad "iCub wording"; cat "$work/icub_stdout"; }
grep -q '"channels_flagged": 0' "$work/icub/metrics.json" && ok "iCub: metrics say 0 flagged" || bad "iCub metrics"
grep -q "threshold +-\|band " "$work/icub/figures.gp" && ok "iCub: the thresholds are drawn" || bad "iCub: no threshold lines"
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
