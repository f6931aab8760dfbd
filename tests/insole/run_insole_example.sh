#!/usr/bin/env bash
# Installs the build into a prefix, then builds examples/insole_fdi against it with
# find_package(ftsense) the way a user would, and runs it: its own tests (plugin contract, model,
# fit), the check that the config's coefficients are those the fit gives, and the evaluation on
# the real insole walk (which exits non-zero on a missed fault or a false alarm). The build stays
# in WORK_DIR for the insole_example_verbs test (examples/insole_fdi/tests/test_insole_verbs.sh).
#
# usage: run_insole_example.sh BUILD_DIR EXAMPLE_DIR WORK_DIR [FLAGS]
set -eu
build=$1
example=$2
work=$3
flags=${4:-}  # extra compiler and linker flags (the sanitizers, when the build under test uses them)
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/install" > "$work/install.log"
cmake -S "$example" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/install" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
      > "$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/build" > "$work/build.log" || { cat "$work/build.log"; exit 1; }
"$work/build/insole_tests" --gtest_brief=1
"$work/build/insole_fdi" fit --config "$example/config/insole_fdi.json" --input "$example/data/GaCo01_01.csv"
"$work/build/insole_fdi" evaluate --config "$example/config/insole_fdi.json" --input "$example/data/GaCo01_01.csv"
