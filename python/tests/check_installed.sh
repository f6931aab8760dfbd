#!/usr/bin/env bash
# check_installed.sh BUILD_DIR PYTHON SITE_DIR SOURCE_DIR
# Installs the build into a temporary prefix and imports ftsense from there alone (PYTHONPATH =
# <prefix>/SITE_DIR, run outside the source and build trees), then builds and runs a pipeline.
set -eu
build=$1
python=$2
site=$3
source=$4
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > "$prefix/install.log" || { cat "$prefix/install.log"; exit 1; }
cd "$prefix"
PYTHONPATH="$prefix/$site" "$python" -c "import ftsense" || { echo "FAIL: python3 -c 'import ftsense' from $prefix/$site"; exit 1; }
PYTHONPATH="$prefix/$site" "$python" - "$prefix" "$source" <<'PY'
import os, sys
import ftsense
prefix, source = sys.argv[1], sys.argv[2]
for module in (ftsense, ftsense._ftsense):
    assert os.path.realpath(module.__file__).startswith(os.path.realpath(prefix)), module.__file__
p = ftsense.Pipeline(os.path.join(source, "configs", "suralp_robust.json"))
out = p.run({port.name: [[0.0] * port.dim] * 3 for port in p.inputs})
assert all(a.shape[0] == 3 for a in out.values()), "three ticks of every output"
print("ok: imported", ftsense.__file__, "and ran", p)
PY
