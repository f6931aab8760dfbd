#!/usr/bin/env bash
# Every pipeline config shipped in configs/ and examples/*/ (not the simulator scenarios under
# configs/scenarios/) passes `ftsense check`.
set -u
ftsense=$1
root=$2
passes=0
failures=0
for config in "$root"/configs/*.json "$root"/examples/*/*.json; do
  [ -e "$config" ] || continue
  if "$ftsense" check --config "$config"; then passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAIL $config"; fi
done
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ] && [ "$passes" -gt 0 ]
