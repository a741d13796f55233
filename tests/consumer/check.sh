#!/usr/bin/env bash
# Installs an eqhb build tree into a fresh prefix, then builds and runs this
# consumer project against it twice: through find_package(eqhb) and through
# pkg-config; imports the installed Python package; finally configures it
# with eqhb as a subproject.
# Usage: tests/consumer/check.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "${1:?usage: check.sh BUILD_DIR}" && pwd)"
work="$build/consumer-check"
rm -rf "$work"
mkdir -p "$work"
scene="$here/../../problems/friction-1d.toml"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
echo "installed: $(find "$work/prefix" -type f | wc -l) files in $work/prefix"

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$here" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  "${launcher[@]}" | grep -E "^-- eqhb "
cmake --build "$work/cmake" -j2 >/dev/null
"$work/cmake/consumer" "$scene" dogleg-newton
[ -x "$work/cmake/consumer_minpack" ] && "$work/cmake/consumer_minpack" "$scene"

pc_dir="$(dirname "$(find "$work/prefix" -name eqhb.pc)")"
export PKG_CONFIG_PATH="$pc_dir${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
echo "pkg-config eqhb $(pkg-config --modversion eqhb)"
# shellcheck disable=SC2046
c++ -O2 -o "$work/consumer_pc" "$here/main.cpp" $(pkg-config --cflags --libs eqhb)
"$work/consumer_pc" "$scene" dogleg-newton >/dev/null
echo "consumer built with pkg-config: ok"

# The installed Python package, imported from the prefix (when it was built).
site="$(find "$work/prefix" -path '*-packages/eqhb/__init__.py' | head -1)"
if [ -n "$site" ]; then
  PYTHONPATH="$(dirname "$(dirname "$site")")" /usr/bin/python3 -c \
    "import sys, eqhb; r = eqhb.solve(eqhb.load_scene(sys.argv[1])); assert r['converged']; print('python from the prefix:', eqhb.__file__, eqhb.__version__)" \
    "$scene"
fi

# As a subproject (configure only): no build type forced, no programs built.
cmake -S "$here" -B "$work/subproject" -DEQHB_SOURCE_DIR="$here/../.." | grep -E "^-- eqhb "
