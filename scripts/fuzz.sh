#!/usr/bin/env bash
# Fuzzes every input reader with libFuzzer (targets in tests/fuzz/fuzz_targets.h).
#   scripts/fuzz.sh [SECONDS] [TARGET...]   (default 600 s per target, every target)
# Configures FUZZ_BUILD_DIR (default build-fuzz) with clang and TOPOPLAN_FUZZ=ON (ASan + UBSan +
# libFuzzer), builds the fuzz_* programs, then runs each target for SECONDS on its corpus
# (FUZZ_BUILD_DIR/corpus/TARGET, kept between runs, seeded from assets/, snapshots/ and
# tests/fuzz/{seeds,regressions}/TARGET; the mesh target's seeds are the meshes of assets/ and
# tests/planning/data with their extension on a first line) with tests/fuzz/dict/TARGET.dict. Every crash, leak,
# timeout or out-of-memory input is copied to tests/fuzz/regressions/TARGET/, where the ctest
# fuzz_replay of the normal build replays it. Prints executions per second per target.
# Environment: FUZZ_BUILD_DIR, JOBS (build, default nproc), FUZZ_PARALLEL (targets run at once,
# default 1), FUZZ_INPUT_TIMEOUT (seconds per input, default 10), FUZZ_RSS_MB (default 2048),
# NICE (default 10), FUZZ_SKIP_BUILD=1 (run the programs already built). Exit 0 when no target
# found anything, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SECONDS_PER_TARGET=${1:-600}
shift || true
BUILD=${FUZZ_BUILD_DIR:-$ROOT/build-fuzz}
JOBS=${JOBS:-$(nproc)}
PARALLEL=${FUZZ_PARALLEL:-1}
ALL_TARGETS=(chain_csv scene_json scenario_json urdf chains_sidecar srdf grasp grasp_objects mesh
             png script flags)
TARGETS=("$@")
[[ ${#TARGETS[@]} -eq 0 ]] && TARGETS=("${ALL_TARGETS[@]}")

if [[ "${FUZZ_SKIP_BUILD:-0}" != "1" ]]; then
  bash scripts/setup.sh --fuzz
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
    -DTOPOPLAN_FUZZ=ON -DTOPOPLAN_BUILD_TESTS=OFF -DTOPOPLAN_BUILD_BENCHMARKS=OFF \
    -DTOPOPLAN_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
  cmake --build "$BUILD" -j "$JOBS" --target "${TARGETS[@]/#/fuzz_}"
fi

# Seed files of a target (one path a line).
seeds() {
  case "$1" in
    chain_csv) ls assets/chains/*.csv ;;
    scene_json) ls assets/scenes/*.json ;;
    scenario_json) ls assets/scenarios/*.json ;;
    urdf) find assets tests -name '*.urdf' ;;
    chains_sidecar) find assets -name '*.chains.json' ;;
    srdf) find assets tests -name '*.srdf' ;;
    grasp) ls assets/grasps/*.json assets/grasps/specs/*.json | grep -v objects.json ;;
    grasp_objects) ls assets/grasps/objects.json ;;
    mesh)  # the mesh target's input: the extension on the first line, then the file
      mkdir -p "$BUILD/mesh-seeds"
      find assets tests/planning/data \( -name '*.stl' -o -name '*.obj' -o -name '*.dae' \) |
        while read -r f; do
          local out=$BUILD/mesh-seeds/$(echo "$f" | tr / _)
          { echo "${f##*.}"; cat "$f"; } >"$out"
          echo "$out"
        done ;;
    png) find snapshots -name '*.png' -size -64k ;;
    script|flags) ;;
  esac
  for d in tests/fuzz/seeds/"$1" tests/fuzz/regressions/"$1"; do
    [[ -d $d ]] && find "$d" -type f ! -name '.*'
  done
  return 0
}

run_target() {
  local t=$1 corpus=$BUILD/corpus/$1 artifacts=$BUILD/artifacts/$1 log=$BUILD/logs/$1.log
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  seeds "$t" | while read -r f; do cp -n "$f" "$corpus/seed-$(basename "$f")"; done
  local dict=()
  [[ -f tests/fuzz/dict/$t.dict ]] && dict=(-dict="$ROOT/tests/fuzz/dict/$t.dict")
  local start end rc=0
  start=$(date +%s)
  # Leak checks stay on (libFuzzer's default) except for the library leaks listed in
  # tests/fuzz/lsan.supp; -close_fd_mask=3 silences the readers' stdout/err.
  LSAN_OPTIONS=suppressions=$ROOT/tests/fuzz/lsan.supp:print_suppressions=0 \
    nice -n "${NICE:-10}" "$BUILD/tests/fuzz/fuzz_$t" "$corpus" "${dict[@]}" \
    -max_total_time="$SECONDS_PER_TARGET" -timeout="${FUZZ_INPUT_TIMEOUT:-10}" \
    -rss_limit_mb="${FUZZ_RSS_MB:-2048}" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    -close_fd_mask=3 >"$log" 2>&1 || rc=$?
  end=$(date +%s)
  local runs eps
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  local found=0
  for a in "$artifacts"/*; do
    [[ -f $a ]] || continue
    mkdir -p "tests/fuzz/regressions/$t"
    cp "$a" "tests/fuzz/regressions/$t/"
    rm "$a"
    found=$((found + 1))
  done
  printf '%-15s %6d s %12s runs %8s exec/s  corpus %5d  findings %d  rc %d  (%s)\n' "$t" \
    $((end - start)) "${runs:-?}" "${eps:-?}" "$(ls "$corpus" | wc -l)" "$found" "$rc" "$log" |
    tee -a "$BUILD/logs/summary.txt"
  [[ $found -eq 0 && $rc -eq 0 ]]
}

mkdir -p "$BUILD/logs"
echo "fuzz: ${#TARGETS[@]} targets, $SECONDS_PER_TARGET s each, $PARALLEL at a time" |
  tee -a "$BUILD/logs/summary.txt"
status=0
pids=()
for t in "${TARGETS[@]}"; do
  run_target "$t" &
  pids+=($!)
  if [[ ${#pids[@]} -ge $PARALLEL ]]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
[[ $status -eq 0 ]] && echo "fuzz: no findings" ||
  echo "fuzz: findings copied to tests/fuzz/regressions/ (replay: build/tests/fuzz/fuzz_replay)"
exit $status
