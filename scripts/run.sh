#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs packages, builds (Release), then
#   scripts/run.sh demo [demo args...]   runs the main job (writes demo-out/index.html)
#   scripts/run.sh test [ctest args...]  runs every test (ctest)
#   scripts/run.sh build                 only builds
#   scripts/run.sh bench                 runs the Google Benchmark programs
# Environment: BUILD_DIR (default build), JOBS (default nproc), CI=true turns warnings into errors.
# `test` with SANITIZE=1 also builds ASan + UBSan (TOPOPLAN_SANITIZE, with float-cast-overflow,
# at -O1) in ASAN_BUILD_DIR (default build-asan) and runs the unit and property test programs of
# topology, planning and planning/physics there, JOBS at a time; any sanitizer report fails.
# (.ci/run sets SANITIZE=1.)
# ccache is used when it is installed (not required).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD_DIR=${BUILD_DIR:-$ROOT/build}
JOBS=${JOBS:-$(nproc)}
cmd=${1:-demo}
shift || true

case "$cmd" in
  demo|test|build|bench) ;;
  -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "run.sh: unknown command '$cmd' (demo, test, build, bench)" >&2; exit 2 ;;
esac

# The demo needs neither the test frameworks nor the Python module (scripts/setup.sh --demo).
if [[ "$cmd" == "demo" ]]; then bash scripts/setup.sh --demo; else bash scripts/setup.sh; fi
# Warnings are errors in CI; elsewhere the cached setting is kept (so that `demo` after `test`
# does not rebuild everything with other flags).
werror=()
[[ "${CI:-}" == "true" ]] && werror=(-DTOPOPLAN_WERROR=ON)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# Everything but the demo must build the tests and benchmarks: a missing framework is an error.
require=()
[[ "$cmd" != "demo" ]] && require=(-DTOPOPLAN_REQUIRE_TESTS=ON)
# Ninja for a new build directory (it keeps both cores busy across libraries, where Make builds
# one library after another: ~50 s less for a cold build of the demo's target on two cores); an
# existing directory keeps the generator it was made with.
generator() { [[ ! -f "$1/CMakeCache.txt" ]] && command -v ninja >/dev/null && echo "-GNinja"; true; }
cmake -S "$ROOT" -B "$BUILD_DIR" $(generator "$BUILD_DIR") -DCMAKE_BUILD_TYPE=Release \
  "${werror[@]}" "${launcher[@]}" "${require[@]}" >/dev/null
# The demo needs only the topoplan binary; the other commands build everything (tests, benchmarks).
targets=()
[[ "$cmd" == "demo" ]] && targets=(--target topoplan)
cmake --build "$BUILD_DIR" -j "$JOBS" "${targets[@]}"

case "$cmd" in
  demo) "$BUILD_DIR/app/topoplan" demo -o "$ROOT/demo-out" "$@" ;;
  test)
    (cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" "$@")
    if [[ "${SANITIZE:-0}" == "1" ]]; then
      sanitize_start=$SECONDS
      ASAN_BUILD_DIR=${ASAN_BUILD_DIR:-$ROOT/build-asan}
      # -O1 (the usual level for ASan) compiles in about half the time of -O3; no benchmarks, no
      # Python module, and only the targets below are built.
      cmake -S "$ROOT" -B "$ASAN_BUILD_DIR" $(generator "$ASAN_BUILD_DIR") \
        -DCMAKE_BUILD_TYPE=Release -DTOPOPLAN_SANITIZE=ON \
        "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" -DTOPOPLAN_BUILD_BENCHMARKS=OFF \
        -DTOPOPLAN_BUILD_PYTHON=OFF "${werror[@]}" "${launcher[@]}" >/dev/null
      # The unit and property test programs of the numeric libraries (topology, planning,
      # planning/physics): the code that reads files and numbers and runs the solvers; no GL.
      sanitized=(base_test topology_test robot_io_test kinematics_test collision_test srdf_test
        mesh_collision_test mesh_limits_test planning_rrt_test planning_aico_test
        planning_aico_step_test planning_rrt_step_test planning_feature_test
        planning_scenario_test planning_grasp_test grasp_quality_test planning_success_test
        planning_replan_test grasp_simulation_test stability_step_test hand_builder_test
        human_hand_test grasp_trials_test exact_confirm_test freeze_test
        planning_robot_collection_test planning_cost_units_test grasp_study_test
        grasp_study_physics_test planning_scenario_new_test)
      cmake --build "$ASAN_BUILD_DIR" -j "$JOBS" --target "${sanitized[@]}"
      echo "run.sh: sanitizer build took $((SECONDS - sanitize_start)) s"
      # JOBS programs at a time, each one's output in ASAN_BUILD_DIR/sanitized-logs. Leak checking
      # is off: ODE keeps process-lifetime allocations.
      logs=$ASAN_BUILD_DIR/sanitized-logs
      mkdir -p "$logs"
      run_sanitized() {
        local exe rc=0
        exe=$(find "$ASAN_BUILD_DIR/tests" -name "$1" -type f -executable | head -n 1)
        if [[ -z $exe ]]; then
          echo "run.sh: $1 was not built" >"$logs/$1.log"
          rc=1
        else
          (cd "$(dirname "$exe")" &&
            ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
            UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 "$exe" --gtest_brief=1) \
            >"$logs/$1.log" 2>&1 || rc=$?
        fi
        echo "$rc" >"$logs/$1.rc"
      }
      tests_start=$SECONDS
      failed=()
      rm -f "$logs"/*.rc
      for t in "${sanitized[@]}"; do
        while (($(jobs -rp | wc -l) >= JOBS)); do wait -n || true; done
        run_sanitized "$t" &
      done
      wait
      for t in "${sanitized[@]}"; do
        if [[ "$(cat "$logs/$t.rc" 2>/dev/null)" == "0" ]]; then
          echo "run.sh: sanitized $t: ok"
        else
          failed+=("$t")
          echo "run.sh: sanitized $t: FAILED"
          tail -n 60 "$logs/$t.log"
        fi
      done
      echo "run.sh: sanitized tests took $((SECONDS - tests_start)) s"
      if ((${#failed[@]})); then
        echo "run.sh: sanitized tests failed: ${failed[*]} (logs: $logs)" >&2
        exit 1
      fi
      echo "run.sh: sanitizer stage (build + sanitized tests) took $((SECONDS - sanitize_start)) s"
    fi ;;
  bench)
    for b in "$BUILD_DIR"/tests/bench/bench_*; do
      [[ -x "$b" ]] && "$b" "$@"
    done ;;
  build) ;;
esac
