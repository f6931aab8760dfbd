#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and runs each for a
# bounded time on a copy of the committed seed corpus.
#
#   fuzz/run_fuzzers.sh [SECONDS_PER_TARGET]     (default 60)
#
# Environment: FUZZ_TARGETS (default "fuzz_config fuzz_csv_log"), FUZZ_BUILD_DIR (default
# build-fuzz), FUZZ_WORK_DIR (default build-fuzz/run: corpus copies, logs, crash artifacts),
# JOBS (build parallelism, default 2). Installs clang and the libFuzzer runtime if missing.
# Exits non-zero on any crash, leak, timeout, out-of-memory or sanitizer report; prints one
# summary line per target.
set -euo pipefail

seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "usage: $0 [SECONDS_PER_TARGET]" >&2
  exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${FUZZ_BUILD_DIR:-$root/build-fuzz}"
work="${FUZZ_WORK_DIR:-$build/run}"
targets="${FUZZ_TARGETS:-fuzz_config fuzz_csv_log}"
jobs="${JOBS:-2}"

# --- tools: clang, the libFuzzer runtime (libclang-rt-14-dev on Debian 12), llvm (for
# --- llvm-symbolizer: readable stack traces), cmake, ninja,
# --- and the libraries ftsense builds against.
need=""
have_pkg() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
for p in clang libclang-rt-14-dev llvm cmake ninja-build libeigen3-dev libceres-dev libboost-dev liburdfdom-dev \
         nlohmann-json3-dev; do
  have_pkg "$p" || need="$need $p"
done
if [ -n "$need" ]; then
  echo "run_fuzzers: installing Debian packages:$need"
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get update </dev/null
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends $need </dev/null
fi

# --- build (incremental; never touches build/ or build-sanitize/)
start=$(date +%s)
cmake -S "$root/fuzz" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$build" -j "$jobs"
echo "run_fuzzers: build took $(( $(date +%s) - start )) s"

# --- run
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/fuzz/ubsan.supp${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
mkdir -p "$work"
status=0
summaries=()
for target in $targets; do
  case "$target" in
    fuzz_config)  corpus_name=config; max_len=16384; dict="$root/fuzz/config.dict" ;;
    fuzz_csv_log) corpus_name=csv;    max_len=4096;  dict="$root/fuzz/csv.dict" ;;
    *) echo "run_fuzzers: unknown target $target" >&2; exit 2 ;;
  esac
  corpus="$work/$target-corpus"         # a copy: the committed corpus never grows
  artifacts="$work/$target-artifacts/"
  log="$work/$target.log"
  rm -rf "$corpus" "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  cp "$root/fuzz/corpus/$corpus_name"/* "$corpus"/
  if [ "$target" = fuzz_config ]; then
    # The configs as they are today too (the committed seeds are snapshots).
    for f in "$root"/configs/*.json "$root"/examples/minimal/minimal.json; do
      [ -f "$f" ] && cp "$f" "$corpus/live-$(basename "$f")"
    done
  fi
  seed="${FUZZ_SEED:-1}"  # fixed, so a CI run is repeatable; set FUZZ_SEED for a different walk
  echo "run_fuzzers: $target for $seconds s, seed $seed (log: $log)"
  rc=0
  # Single process (-jobs/-workers unset): the machine is shared. -timeout: one input taking
  # more than 10 s is a hang. -rss_limit_mb: an absurd allocation is a bug, not a slow run.
  "$build/$target" "$corpus" -seed="$seed" -dict="$dict" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
      -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix="$artifacts" \
      </dev/null >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  if [ "$rc" -eq 0 ] && [ -z "$(ls -A "$artifacts")" ]; then
    summaries+=("$target: ${runs:-?} runs in ${took:-$seconds} s, no crash (${cov:-no coverage line})")
  else
    status=1
    summaries+=("$target: FAILED (exit $rc) after ${runs:-?} runs; artifacts in $artifacts; see $log")
    echo "---- $target: last lines of $log" >&2
    tail -n 40 "$log" >&2
  fi
done
for s in "${summaries[@]}"; do echo "$s"; done
exit "$status"
