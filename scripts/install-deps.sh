#!/usr/bin/env bash
# Installs every Debian bookworm package sdflow needs to build, test and benchmark. Idempotent:
# apt-get skips what is already installed. Run as root or with sudo available.
#   scripts/install-deps.sh            toolbox, CLI, tests, the Python module (pybind11, numpy, scipy,
#                                      pytest, matplotlib for its example)
#   scripts/install-deps.sh --bench    also the benchmark peers (CGAL, Surface Evolver, hyperfine)
#   scripts/install-deps.sh --paraview also ParaView and pvpython (large) for scripts/check-paraview.sh
#   scripts/install-deps.sh --meshlab  also what the MeshLab plugin needs: Debian's MeshLab, Qt 5,
#                                      GLEW, dpkg-dev (to unpack MeshLab's source package for its
#                                      headers) and Xvfb (meshlabserver needs an X server)
#   scripts/install-deps.sh --screenshots  also xdotool and ImageMagick, to drive MeshLab under Xvfb
#                                      and capture docs/images/meshlab-surface-diffusion.png
#   scripts/install-deps.sh --fuzz     also clang and its libFuzzer/sanitizer runtime (scripts/fuzz.sh)
# Flags combine.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libopenmesh-dev libeigen3-dev
  libsuitesparse-dev libmetis-dev libopenblas-dev
  libtet1.5-dev
  libgtest-dev libgmock-dev libbenchmark-dev libgmp-dev
  libnanoflann-dev libcli11-dev libtomlplusplus-dev libspdlog-dev libfmt-dev libmuparser-dev libtbb-dev libexpat1-dev
  gnuplot-nox help2man
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-scipy python3-pytest python3-matplotlib
)
if [[ " $* " == *" --bench "* ]]; then
  packages+=(libcgal-dev evolver-nox hyperfine)
fi
if [[ " $* " == *" --paraview "* ]]; then
  packages+=(paraview python3-paraview)
fi
if [[ " $* " == *" --meshlab "* ]]; then
  packages+=(meshlab qtbase5-dev libqt5opengl5-dev libglew-dev dpkg-dev xvfb xauth)
fi
if [[ " $* " == *" --fuzz "* ]]; then
  packages+=(clang libclang-rt-14-dev)
fi
if [[ " $* " == *" --screenshots "* ]]; then
  packages+=(xdotool imagemagick)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
