#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds and runs a consumer project against it
# with find_package(ftsense).
set -eu
build=$1
source=$2
flags=${3:-}  # extra compiler and linker flags (the sanitizers, when the build under test uses them)
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/install" > "$prefix/install.log"
cmake -S "$source" -B "$prefix/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix/install" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
      > "$prefix/configure.log" || { cat "$prefix/configure.log"; exit 1; }
cmake --build "$prefix/build" || exit 1
"$prefix/build/consumer"
