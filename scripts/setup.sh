#!/usr/bin/env bash
# Installs the Debian packages topoplan needs, each group saying what it is for.
# Idempotent: packages already present are skipped. Uses sudo when not run as root.
# Usage: scripts/setup.sh [--demo | --minimal | --fuzz]
#   (none)     everything: build, tests, benchmarks, the Python module, optional tools
#   --demo     what building `topoplan` and running `topoplan demo` need: no test frameworks,
#              no Python module, no headless-window tools (scripts/run.sh demo)
#   --minimal  everything but the optional tools (ffmpeg, OMPL, MuJoCo)
#   --fuzz     everything plus clang and libFuzzer for scripts/fuzz.sh
set -euo pipefail

# The topoplan binary: what it compiles and links against, and the font its figures use.
BUILD=(
  build-essential cmake ninja-build pkg-config git  # toolchain
  libeigen3-dev libsleef-dev                      # linear algebra, vectorised atan2 (topology)
  libcli11-dev nlohmann-json3-dev                 # command line, JSON
  libosmesa6-dev libegl-dev libgl-dev             # offscreen GL (OSMesa, EGL surfaceless), window GL
  libglfw3-dev libimgui-dev libstb-dev            # interactive window, UI, image I/O
  libpng-dev zlib1g-dev                           # fast PNG encoder for frame sequences
  libplplot-dev plplot-driver-cairo               # plots
  libcairo2-dev                                   # PDF figures (heatmaps)
  fonts-dejavu-core                               # font for labels
  libassimp-dev liburdfdom-dev libtinyxml-dev     # meshes, URDF (+ TinyXML, used directly)
  libfcl-dev libccd-dev libqhull-dev              # collision, convex hulls (meshes, grasp quality)
  libode-dev                                      # physics
)
# The tests and benchmarks (scripts/run.sh test): not needed to build or run the binary.
TESTS=(
  libgtest-dev libgmock-dev libbenchmark-dev      # tests, benchmarks
  locales                                         # locale definitions (tests: a comma-decimal locale)
  pybind11-dev python3-dev python3-pybind11       # Python module (python/)
  python3-numpy python3-pytest                    # its arrays and tests
  python3-matplotlib                              # the README's Python example (plots)
  python3-dask python3-distributed                # sweeps on Dask (topoplan.sweep)
  xvfb xauth xdotool imagemagick                  # headless window tests
)
# Optional: ffmpeg (frame videos; the demo makes some), OMPL (ompl-* planners; the demo's Fig. 4.5
# runs them), MuJoCo 2.2 (the second physics engine of `bench grasp`: its stability verdict next to
# ODE's).
OPTIONAL=(ffmpeg libompl-dev libmujoco-dev)
FUZZ=(clang libclang-rt-14-dev libfuzzer-14-dev)     # scripts/fuzz.sh only

want=("${BUILD[@]}")
case "${1:-}" in
  "") want+=("${TESTS[@]}" "${OPTIONAL[@]}") ;;
  --demo) want+=("${OPTIONAL[@]}") ;;
  --minimal) want+=("${TESTS[@]}") ;;
  --fuzz) want+=("${TESTS[@]}" "${OPTIONAL[@]}" "${FUZZ[@]}") ;;
  -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "setup: unknown option '$1' (--demo, --minimal, --fuzz)" >&2; exit 2 ;;
esac

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#want[@]} Debian packages present"
  exit 0
fi
SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install as root: ${missing[*]}" >&2; exit 3; }
  SUDO="sudo"
fi

echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
