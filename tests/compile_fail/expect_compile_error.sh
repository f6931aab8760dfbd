#!/usr/bin/env bash
# expect_compile_error.sh SOURCE "expected message" COMPILER FLAGS...
# Passes when compiling SOURCE fails with the expected message.
set -u
source=$1
expected=$2
shift 2
if output=$("$@" -fsyntax-only "$source" 2>&1); then
  echo "FAIL: $source compiled, but it must not"
  exit 1
fi
if grep -qF -- "$expected" <<< "$output"; then
  echo "ok: $(basename "$source") fails with: $expected"
  exit 0
fi
echo "FAIL: $source failed to compile without the message: $expected"
echo "$output" | head -40
exit 1
