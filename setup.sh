#!/usr/bin/env bash
# Rigid set-up: installs the Debian dependencies (idempotent), builds, then runs what you ask for.
#   bash setup.sh demo    install, build, run the main job (the demo)
#   bash setup.sh test    install, build, run every test but the long physics runs (what CI runs)
#   bash setup.sh long    install, build, run only the long physics runs (ctest -L long, ~3 min
#                         plus a few minutes of the contact solve's convergence study, docs/accuracy.md;
#                         list and reasons in tests/labels.cmake)
#   bash setup.sh build   install and build only
#   bash setup.sh sanitize  install, build the engine libraries and a representative subset of
#                         the test executables with AddressSanitizer + UndefinedBehaviorSanitizer
#                         (in build-sanitize) and run their tests (ctest -L sanitize; CI runs it
#                         after `test`; 11 of the 13 `stability` cases, tests/labels.cmake), then
#                         fuzzes the PLY and OBJ readers for 20 s each (clang, in build-fuzz)
# Environment: BUILD_DIR (default build), JOBS (default nproc), RIGID_CMAKE_ARGS (extra cmake args).
set -euo pipefail
cd "$(dirname "$0")"
action=${1:-build}
if [[ $action == demo ]]; then
  cat <<'EOF_INTRO'
Rigid demo: what happens now, and how long it takes (2 cores)
  1. install the Debian packages that are missing (first time only: a few minutes)
  2. build the rigid executable (first time: about 10 minutes; then seconds)
  3. a fragility campaign on 2 MPI ranks: 5 bundled rocks (6 with ../shared/scans) x 9 records x
     10 PGA scales x 2 rotations (about a minute)
  4. fragility maps, fitted fragilities (CSV, OpenQuake NRML) and one rock tested against a
     hazard curve (seconds)
  5. one run drawn and animated; rigidpy (the Python API) installed into out/venv (seconds)
EOF_INTRO
fi
build_dir=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}

packages=(build-essential cmake git pkg-config
  openmpi-bin libopenmpi-dev libeigen3-dev libhdf5-dev hdf5-tools libcli11-dev
  nettle-dev zlib1g-dev nlohmann-json3-dev libspdlog-dev libassimp-dev
  googletest libgtest-dev libtomlplusplus-dev libbenchmark-dev libode-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-scipy
  python3-xarray python3-h5netcdf python3-netcdf4 python3-pandas python3-statsmodels python3-pytest
  pybind11-dev python3-dev python3-setuptools python3-wheel python3-venv python3-pip python3-pil
  python3-nbformat python3-nbclient python3-ipykernel
  slurm-wlm munge
  clang libclang-rt-dev clang-format libcgal-dev libgmp-dev libmpfr-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [[ $(id -u) -ne 0 ]] && sudo="sudo"
  echo "setup: installing ${missing[*]}"
  # no service may start during the install (munge's postinst would, on machines without systemd);
  # the Slurm test brings up its own daemons (slurm/local-cluster.sh)
  made_policy=0
  if [[ ! -e /usr/sbin/policy-rc.d ]]; then
    printf '#!/bin/sh\nexit 101\n' | $sudo tee /usr/sbin/policy-rc.d >/dev/null
    $sudo chmod 755 /usr/sbin/policy-rc.d
    made_policy=1
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  if ((made_policy)); then $sudo rm -f /usr/sbin/policy-rc.d; fi
fi

# Open MPI refuses root unless told (CI and containers run as root).
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

cmake_args=(-DCMAKE_BUILD_TYPE=Release)
targets=()
if [[ $action == sanitize ]]; then
  # -O2 with line tables only (-g1): reports still name file:line, and the build takes ~20 % less
  # than with -g. Not -O1: it halves the compile but the instrumented Eigen code then runs the
  # stability suite ~18x slower than Release (22 min of CPU)
  build_dir=${BUILD_DIR:-build-sanitize}
  # NDEBUG is not defined, so the engine's invariant asserts run under the sanitizers too
  # (EIGEN_NO_DEBUG keeps Eigen's own per-access index checks out: they would double the time)
  cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DEIGEN_NO_DEBUG"
              -DRIGID_SANITIZE=ON)
  # only the subset's executables and the engine libraries they link (tests/CMakeLists.txt,
  # RIGID_SANITIZE_TESTS, says why they are representative): no rigid_campaign, no app
  targets=(--target sanitize_tests)
  # any finding fails the test. Leak detection is off: Open MPI keeps allocations in plugins it
  # has already unloaded at exit, which LeakSanitizer reports as "unknown module" (no suppression
  # can name them); ASan's other checks (overflows, use after free) stay on
  export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=0}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/lsan_suppressions.txt:print_suppressions=0}
fi
if [[ $action == demo ]]; then
  # the demo runs the executable and rigidpy's extension (docs/python.md); `test` builds the rest
  targets=(--target rigid _engine)
fi
start=$SECONDS
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" "${cmake_args[@]}" ${RIGID_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j "$jobs" "${targets[@]}"
echo "setup: $action: build ($build_dir) took $((SECONDS - start)) s"
start=$SECONDS

case "$action" in
  build) ;;
  test)
    # everything but label `long` (the long physics runs, bash setup.sh long)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" -LE long
    echo "setup: test: ctest took $((SECONDS - start)) s"
    ;;
  long)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" -L long
    echo "setup: long: ctest took $((SECONDS - start)) s"
    ;;
  sanitize)
    # the tests of the subset (label `sanitize`; the long runs never carry it, nor the 300 s and
    # 10,000-facet stability runs: tests/labels.cmake says why; they run in the Release suite)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" -L sanitize
    echo "setup: sanitize: ctest took $((SECONDS - start)) s"
    # the mesh readers under libFuzzer (clang, tests/fuzz): a fixed time each from the seed files
    # (tests/data/ply, tests/data/obj), 2 GB and 10 s per input; a crash, a sanitizer report or an
    # exception other than rigid::InputError fails the step and leaves the input in $fuzz_dir
    start=$SECONDS
    fuzz_dir=${FUZZ_BUILD_DIR:-build-fuzz}
    # shellcheck disable=SC2086
    cmake -S . -B "$fuzz_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRIGID_FUZZ=ON \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ ${RIGID_CMAKE_ARGS:-} >/dev/null
    cmake --build "$fuzz_dir" -j "$jobs" --target ply_fuzz obj_fuzz
    for format in ply obj; do
      corpus="$fuzz_dir/corpus_$format"
      mkdir -p "$corpus"
      "$fuzz_dir/tests/${format}_fuzz" -max_total_time="${FUZZ_SECONDS:-20}" -max_len=4096 -rss_limit_mb=2048 \
        -timeout=10 -print_final_stats=1 -artifact_prefix="$fuzz_dir/${format}_" "$corpus" "tests/data/$format"
    done
    echo "setup: sanitize: mesh reader fuzzing took $((SECONDS - start)) s"
    ;;
  demo)
    # The main job: a small real campaign on the bundled models and generated waveforms, on two
    # ranks. It resumes if interrupted (run the command again); delete out/ to start over.
    rigid="$build_dir/bin/rigid"
    # a real scanned rock (../shared/scans, beside the checkout, never in the repository): imported
    # when present, and the demo's optional object sp1_rock then runs too
    scan=../shared/scans/sp1_rock.obj
    if [[ -f $scan ]]; then
      "$rigid" model import "$scan" --out models/scans/sp1_rock/sp1_rock --flatten-base 0.005
    fi
    "$rigid" campaign jobs/demo.toml --dry-run
    mpirun --oversubscribe -np 2 "$rigid" campaign jobs/demo.toml
    # what people look at: fragility maps per object and the scenario table (objects x records)
    "$rigid" plot maps out/demo.h5 --out out/demo_plots
    "$rigid" plot table out/demo.h5 --out out/demo_plots/scenario_table.md  # prints it too
    # what hazard codes read: fitted fragilities with intervals (CSV, OpenQuake NRML, /fragility in
    # the cube), and the survival test of the alpha = 0.3 block against a synthetic hazard curve
    "$rigid" fragility out/demo.h5 --csv out/demo_plots/fragility.csv --nrml out/demo_plots/fragility_nrml.xml
    "$rigid" hazard out/demo.h5 --object block_a03 --curve models/hazard/synthetic_pga_curve.csv --age 10000 \
      --plot out/demo_plots/hazard_block_a03.png
    # one run of the alpha = 0.3 block watched: its time history drawn and animated
    "$rigid" run models/library/block_a03/block_a03.toml --motion waveforms/demo/mp_pulse_1s-X.AT2 --target-pga 0.6 \
      --rotation 30 --plot out/demo_plots/run_block_a03.png --animate out/demo_plots/run_block_a03.gif
    # rigidpy, the Python API, installed as a user installs it (docs/python.md) into out/venv, a
    # virtual environment over Debian's packages, with the extension just built; then used from out/
    /usr/bin/python3 -m venv --system-site-packages out/venv
    engine=$(ls "$build_dir"/python/rigidpy/_engine*.so)
    RIGID_PREBUILT_ENGINE=$PWD/$engine out/venv/bin/pip install -q --no-build-isolation --no-index \
      --disable-pip-version-check .
    (cd out && venv/bin/python -c "import rigidpy; ds = rigidpy.open_cube('demo.h5'); print(ds.outcome.sel(scale=0.3))")
    ;;
  *) echo "usage: bash setup.sh demo|test|long|sanitize|build" >&2; exit 2 ;;
esac
if [[ $action == demo ]]; then
  cat <<'EOF_OUTRO'

Done. Open:
  out/demo_plots/                     fragility maps per rock (PNG) and the scenario table
  out/demo_plots/fragility.csv        fitted fragilities with intervals; fragility_nrml.xml for OpenQuake
  out/demo_plots/hazard_block_a03.png the alpha = 0.3 block under a synthetic hazard curve
  out/demo_plots/run_block_a03.png    one run of it: tilt, slip and table acceleration (and .gif)
  out/demo.h5                         the fragility cube (HDF5; docs/cube.md)
  out/venv/bin/python                 Python with rigidpy installed: docs/python.md,
                                      docs/notebooks/first_steps.ipynb
Next: your own rock and records, as the README's quick start shows.
EOF_OUTRO
fi
