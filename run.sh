#!/usr/bin/env bash
# Set-up and entry point for a fresh Debian 12 machine.
#   ./run.sh bench [--quick]   install, build, run the benchmark over all scenes -> results/
#   ./run.sh test              install, build, run the test suite (ctest)
#   ./run.sh field [--quick]   install, build, sweep the field problems (problems/field/)
#                              on every backend -> results/field-suite.md, .json
#   ./run.sh docs              install, build, build the documentation site (runs the
#                              tutorials, warnings are errors) -> build/docs/html
#   ./run.sh perf-check        short benchmark compared with bench/baseline.json (CI)
#   ./run.sh baseline          re-record bench/baseline.json (on purpose only)
#   ./run.sh sanitize          the test suite under ASan + UBSan (clang), then every
#                              fuzzer, FUZZ_SECONDS (60) shared between them (CI)
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(cmake g++ make pkg-config libeigen3-dev libspectra-dev libceres-dev libnlopt-cxx-dev libnlopt-dev
  coinor-libipopt-dev libsuitesparse-dev libfftw3-dev libbenchmark-dev libgtest-dev
  libcminpack-dev libcli11-dev nlohmann-json3-dev libtoml11-dev python3 python3-matplotlib
  python3-dev pybind11-dev python3-numpy python3-scipy python3-pytest
  libopenmpi-dev openmpi-bin
  python3-sphinx python3-myst-parser python3-breathe doxygen
  python3-venv python3-pip python3-setuptools python3-wheel libhdf5-dev python3-h5py
  clang libclang-rt-14-dev ccache)

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# The compiler cache keys paths relative to the sources, so that the library
# compiled for the command (build/) serves the pip install of the Python module
# (build-python/, setup.py, tested by ./run.sh test) instead of a third build.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"

build() {
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
  cmake --build build -j"$(nproc)"
}

# Its own build directory: clang with ASan + UBSan and libFuzzer, only what
# the tests need (no benchmark, no Python module, the optional backends off),
# eight source files to a compilation unit (Eigen's headers parsed once per
# eight: 6 min instead of 10 on two cores; the release build keeps one file a
# unit, whose objects the Python module's build takes from the cache).
sanitize_build() {
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DEQHB_SANITIZE=ON -DEQHB_FUZZ=ON -DEQHB_BUILD_BENCH=OFF -DEQHB_BUILD_PYTHON=OFF -DEQHB_INSTALL=OFF \
    -DEQHB_WITH_CERES=OFF -DEQHB_WITH_IPOPT=OFF -DEQHB_WITH_NLOPT=OFF -DEQHB_WITH_MPI=OFF \
    -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 "${launcher[@]}" >/dev/null
  cmake --build build-sanitize -j"$(nproc)"
}

case "${1:-}" in
  test)
    install_packages
    build
    ctest --test-dir build --output-on-failure -j2
    ;;
  bench)
    shift
    install_packages
    build
    mkdir -p results
    quick=""
    for a in "$@"; do [ "$a" = "--quick" ] && quick="--quick"; done
    ./build/eqhb-bench --out results "$@" | tee results/summary.txt
    # Damper curves: peak vs normal load per forcing level (exit 1 = some
    # samples failed; they are listed in the report).
    rm -rf results/damper
    ./build/eqhb study problems/friction-1d.toml --vary forcing[0].cos=10:30:3 --vary law.muN=0.5:50:100 \
      --peak --from 0.3 --to 2.0 --out results/damper | tee results/damper.txt || [ "${PIPESTATUS[0]}" -eq 1 ]
    /usr/bin/python3 bench/damper_chart.py results/damper results/report.md
    # The same on a blade: five elastic (Jenkins) dampers on a beam, loaded
    # together, peak of the tip's transverse motion (DOF 119).
    loads="law[0].muN,law[1].muN,law[2].muN,law[3].muN,law[4].muN"
    rm -rf results/damper-beam
    ./build/eqhb study problems/beam-damper-elastic.toml --vary forcing[0].cos=0.5:2:4 --vary "$loads=0.01:4:40" \
      --peak --dof 119 --from 2.8 --to 8 --coarse-points 100 --out results/damper-beam | tee results/damper-beam.txt \
      || [ "${PIPESTATUS[0]}" -eq 1 ]
    /usr/bin/python3 bench/damper_chart.py results/damper-beam results/report.md forcing[0].cos "$loads" 119 \
      beam-damper-elastic
    # The lap joint across its first bending mode at three forcing levels,
    # microslip to macroslip: chart results/lap_joint.png and a table.
    for f in 3 15 50; do
      ./build/eqhb sweep problems/lap-joint.toml --arclength --set "forcing[0].cos=$f" --quiet \
        --out "results/lap-joint-$f.csv" | tee -a results/lap-joint.txt
    done
    { printf '\n## Lap joint (problems/lap-joint.toml, arclength sweeps)\n\n'
      /usr/bin/python3 bench/lap_joint_chart.py results/lap_joint w20 3=results/lap-joint-3.csv \
        15=results/lap-joint-15.csv 50=results/lap-joint-50.csv; } >> results/report.md
    # Backbones of the friction scenes, the beams and the lap joint, with the
    # forced response each mode predicts against the forced sweep (charts
    # results/modes_*.png and a section of the report).
    /usr/bin/python3 bench/modes_section.py build/eqhb results results/report.md
    ./build/eqhb-convergence --out results $quick | tee results/convergence.txt
    ./build/eqhb-orbits --out results $quick >/dev/null
    # Work-precision against the exact orbits and the rates in H: CSV, JSON,
    # charts precision_SCENE.*, and a section appended to the report.
    ./build/eqhb-precision --out results $quick >/dev/null
    /usr/bin/python3 bench/precision_charts.py results results/report.md >/dev/null
    ./build/eqhb-hill --out results $quick >/dev/null
    ./build/eqhb-micro --benchmark_min_time=0.02 --benchmark_out=results/micro.json \
      --benchmark_out_format=json >/dev/null
    /usr/bin/python3 bench/micro_slopes.py results/micro.json results/micro.md
    /usr/bin/python3 bench/charts.py results
    /usr/bin/python3 bench/report_charts.py results  # every chart embedded in report.md
    echo "report: results/report.md (and micro.md, convergence.txt, charts *.png/*.svg)"
    ;;
  field)
    shift
    install_packages
    build
    mkdir -p results
    /usr/bin/python3 bench/field_suite.py --eqhb build/eqhb --out results "$@"
    ;;
  docs)
    install_packages
    build
    cmake --build build --target docs
    echo "site: build/docs/html/index.html"
    ;;
  perf-check)
    install_packages
    build
    ./build/eqhb-bench --quick --out build/perf >/dev/null
    /usr/bin/python3 bench/perf_check.py bench/baseline.json build/perf/bench.json
    ;;
  sanitize)
    install_packages
    sanitize_build
    export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    ctest --test-dir build-sanitize --output-on-failure -j2
    # Each fuzzer with its seed corpus; FUZZ_SECONDS is shared between them.
    # New inputs go to a scratch copy; a finding is written to build-sanitize/fuzz-findings/NAME/.
    fuzzers=("scene:tests/fuzz/corpus" "sparse:tests/fuzz/corpus-sparse"
             "matrix-market:tests/fuzz/corpus-matrix-market")
    seconds=$(( ${FUZZ_SECONDS:-60} / ${#fuzzers[@]} ))
    [ "$seconds" -ge 1 ] || seconds=1
    rm -rf build-sanitize/fuzz-corpus build-sanitize/fuzz-findings
    failed=0
    for entry in "${fuzzers[@]}"; do
      name=${entry%%:*} seeds=${entry#*:}
      mkdir -p "build-sanitize/fuzz-corpus/$name" "build-sanitize/fuzz-findings/$name"
      status=0
      "./build-sanitize/eqhb-$name-fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=3072 \
        -print_final_stats=1 -artifact_prefix="build-sanitize/fuzz-findings/$name/" \
        "build-sanitize/fuzz-corpus/$name" "$seeds" >"build-sanitize/fuzz-$name.log" 2>&1 || status=$?
      grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb|Done )" \
        "build-sanitize/fuzz-$name.log" || true
      if [ "$status" -ne 0 ] || [ -n "$(ls -A "build-sanitize/fuzz-findings/$name")" ]; then
        tail -n 60 "build-sanitize/fuzz-$name.log"
        echo "$name fuzzer: finding in build-sanitize/fuzz-findings/$name/" >&2
        failed=1
      else
        echo "$name fuzzer: no crash (${seconds} s)"
      fi
    done
    exit "$failed"
    ;;
  baseline)
    install_packages
    build
    ./build/eqhb-bench --quick --out build/perf >/dev/null
    cp build/perf/bench.json bench/baseline.json
    echo "bench/baseline.json re-recorded: commit it with the reason"
    ;;
  *)
    echo "usage: $0 test | bench [--quick] | field [--quick] | docs | perf-check | baseline | sanitize" >&2
    exit 2
    ;;
esac
