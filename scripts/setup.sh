#!/usr/bin/env bash
# Installs the Debian packages the project builds with (idempotent: only what is missing).
# Usage: scripts/setup.sh [app|all]   (as root on Debian 12; uses sudo when not root)
#   app: what the `prs` program needs to build and run (scripts/demo.sh)
#   all: that and everything the tests, benchmarks, fuzzing and the Python package need (default)
set -euo pipefail
set_name=${1:-all}
case "$set_name" in
  app|all) ;;
  *) echo "usage: scripts/setup.sh [app|all]" >&2; exit 2 ;;
esac

# What `prs` needs (scripts/build.sh app).
packages=(
  build-essential cmake ninja-build pkg-config git
  ccache                 # compiler cache: rebuilds and fresh clones reuse earlier objects
  libeigen3-dev          # linear algebra for the geometry core
  libboost-dev           # Boost.Random's Sobol' engine and Boost.Math's normal quantile (headers)
  libfmt-dev             # string formatting in diagnostics and output
  libcli11-dev           # the prs command line
  nlohmann-json3-dev     # scene JSON output and parsing
  libmujoco-dev          # physics for the simulated case study (src/sim), and prs render
  libcpp-httplib-dev     # prs view's local HTTP server
  libtinygltf-dev        # prs export: writes glTF
  libegl-dev libegl-mesa0 libgl1-mesa-dri  # prs render: MuJoCo's renderer on EGL with
                         # Mesa's software rasteriser (llvmpipe), no GPU or display
  libpng-dev             # prs render: PNG files
  libjpeg62-turbo-dev    # prs dataset --jpeg: JPEG pictures (libjpeg-turbo)
  liburdfdom-dev libconsole-bridge-dev libtinyxml-dev  # arms from URDF files (src/kinematics:
                         # `reachable by` in the language); urdfdom logs through console_bridge
                         # and parses with TinyXML, both included directly
  libassimp-dev libqhull-dev libfcl-dev  # mesh shapes (src/shapes): files read with assimp,
                         # convex hulls with qhull, mesh collisions with FCL
  libbullet-extras-dev   # ... and HACD's convex pieces of a mesh for MuJoCo (MJCF export)
)
# What the tests, benchmarks, fuzzing and the Python package add (scripts/test.sh).
[[ $set_name == all ]] && packages+=(
  libgtest-dev libgmock-dev  # unit tests
  libbenchmark-dev       # micro-benchmarks
  clang libclang-rt-14-dev  # libFuzzer for the front-end fuzz target
  chromium               # prs view's end-to-end test (headless, driven by puppeteer-core)
  pybind11-dev python3-dev python3-numpy  # the Python package (python/)
  python3-pip python3-setuptools python3-wheel  # pip install --no-build-isolation . (offline)
  python3-pytest python3-matplotlib  # Python tests and the plotting example
  python3-sklearn        # probrobscene.search(strategy="bo"): Gaussian processes
  python3-distributed    # probrobscene.campaign.run on a Dask cluster, tested on a LocalCluster
  python3-torch python3-pil  # examples/learning: the learned perception (PyTorch on the CPU)
  munge slurmctld slurmd slurm-client  # a real single-node Slurm for tests/slurm/campaign_test.sh
  procps                 # pgrep/pkill in that test (kills a task's prs as a dead node would)
  libsdformat-dev        # prs export tests: SDF read by its own parser (URDF by urdfdom, above)
  python3                # prs test's example controller (examples/controllers/reach_check.py) in the tests
)
# prs view bundles three.js with npm at build time; keep a Node.js that is already installed
# (e.g. NodeSource's, which ships its own npm) and otherwise take Debian's.
command -v npm >/dev/null || packages+=(nodejs npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
