#!/usr/bin/env bash
# Installs every Debian package topoplan needs to build, test and run its demo.
# Idempotent: packages already present are skipped. Uses sudo when not run as root.
# Usage: scripts/setup.sh [--minimal | --fuzz]   (--minimal skips optional tools: ffmpeg, OMPL, MuJoCo;
#        --fuzz adds clang and libFuzzer for scripts/fuzz.sh)
set -euo pipefail

REQUIRED=(
  build-essential cmake pkg-config git            # toolchain
  libeigen3-dev libsleef-dev                      # linear algebra, vectorised atan2 (topology)
  libcli11-dev nlohmann-json3-dev                 # command line, JSON
  libosmesa6-dev libegl-dev libgl-dev             # offscreen GL (OSMesa, EGL surfaceless), window GL
  libglfw3-dev libimgui-dev libstb-dev            # interactive window, UI, image I/O
  libpng-dev zlib1g-dev                           # fast PNG encoder for frame sequences
  libplplot-dev plplot-driver-cairo               # plots
  libcairo2-dev                                   # PDF figures (heatmaps)
  fonts-dejavu-core                               # font for labels
  locales                                         # locale definitions (tests: a comma-decimal locale)
  libassimp-dev liburdfdom-dev libtinyxml-dev     # meshes, URDF (+ TinyXML, used directly)
  libfcl-dev libccd-dev libqhull-dev              # collision, convex hulls (meshes, grasp quality)
  libode-dev                                      # physics
  libgtest-dev libgmock-dev libbenchmark-dev      # tests, benchmarks
  pybind11-dev python3-dev python3-pybind11       # Python module (python/)
  python3-numpy python3-pytest                    # its arrays and tests
  python3-matplotlib                              # the README's Python example (plots)
  python3-dask python3-distributed                # sweeps on Dask (topoplan.sweep)
  xvfb xauth xdotool imagemagick                  # headless window tests
)
# Optional: ffmpeg (frame videos), OMPL (ompl-* planners), MuJoCo 2.2 (the second physics engine
# of `bench grasp`: its stability verdict next to ODE's).
OPTIONAL=(ffmpeg libompl-dev libmujoco-dev)
FUZZ=(clang libclang-rt-14-dev libfuzzer-14-dev)     # scripts/fuzz.sh only

minimal=0
fuzz=0
[[ "${1:-}" == "--minimal" ]] && minimal=1
[[ "${1:-}" == "--fuzz" ]] && fuzz=1

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install as root: ${REQUIRED[*]}" >&2; exit 3; }
  SUDO="sudo"
fi

missing=()
want=("${REQUIRED[@]}")
[[ $minimal -eq 0 ]] && want+=("${OPTIONAL[@]}")
[[ $fuzz -eq 1 ]] && want+=("${FUZZ[@]}")
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#want[@]} Debian packages present"
  exit 0
fi
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
