#!/usr/bin/env bash
# Twinlight set-up for Debian 12 (bookworm). Idempotent: says what it will change, installs
# only what is missing, upgrades lavapipe from bookworm-backports when the installed one has
# no ray tracing (on Debian 12 only: the backports source is bookworm's), then configures and
# builds the Release tree in build/ with warnings as errors.
#
#   scripts/setup.sh            install + configure + build, then build the fuzz targets
#                               (build/fuzz-ci/: clang, ASan, UBSan) the full suite runs
#   scripts/setup.sh --no-fuzz  the same without the fuzz targets (the quick test tier)
#   scripts/setup.sh --no-build install only
#   scripts/setup.sh --packages print the Debian packages needed, one line, and change nothing
#
# Without root (no sudo): install the printed packages some other way, then build by hand:
#   cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release && cmake --build build
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${TWINLIGHT_BUILD_DIR:-$root/build}"

# Everything the build, the run and the tests need, from Debian's archive only.
packages=(
  build-essential cmake ninja-build pkg-config ccache
  # The fuzz targets (fuzz/, the default suite's fuzz.bounded): clang with libFuzzer and the sanitizers.
  clang libclang-rt-dev
  libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools spirv-tools
  libglfw3-dev libimgui-dev libglm-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenimageio-dev openimageio-tools
  libmeshoptimizer-dev libxxhash-dev libsqlite3-dev libcli11-dev libspdlog-dev libfmt-dev
  librenderdoc-dev renderdoccmd libgtest-dev libgmock-dev
  xvfb xauth
  mesa-vulkan-drivers
  # The job-array tests (tests/cli/cluster_slurm.sh, kubernetes_jobs.py): a private single-node
  # Slurm with its own munge (the system services these packages install are not used), table
  # checks, the deploy scripts' lint, the manifests' parser.
  slurmctld slurmd slurm-client munge sqlite3 shellcheck python3 python3-yaml
)
# Lavapipe gained VK_KHR_acceleration_structure / ray_tracing_pipeline / ray_query in Mesa 24.1.
min_mesa="24.1"

if [ "${1:-}" = "--packages" ]; then
  echo "${packages[*]}"
  exit 0
fi

# The package names and the backports source are Debian 12's.
os_id="" os_version=""
if [ -r /etc/os-release ]; then
  os_id="$(. /etc/os-release && echo "${ID:-}")"
  os_version="$(. /etc/os-release && echo "${VERSION_ID:-}")"
fi
debian12=0
if [ "$os_id" = "debian" ] && [ "$os_version" = "12" ]; then debian12=1; fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "setup: not root and no sudo: install these packages yourself, then build with" >&2
    echo "  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release && cmake --build build" >&2
    echo "  ${packages[*]}" >&2
    exit 1
  fi
  sudo_cmd=(sudo)
fi
apt_get() { DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get -y -q "$@"; }

is_installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

missing=()
for p in "${packages[@]}"; do is_installed "$p" || missing+=("$p"); done
updated=0
if [ "${#missing[@]}" -gt 0 ]; then
  if [ "$debian12" -ne 1 ]; then
    echo "setup: warning: this is ${os_id:-an unknown system} ${os_version}, not Debian 12: package names may differ" >&2
  fi
  echo "setup: will run apt-get update and install (${#missing[@]} missing): ${missing[*]}"
  apt_get update
  updated=1
  apt_get install --no-install-recommends "${missing[@]}"
fi

mesa_version="$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || echo 0)"
if dpkg --compare-versions "$mesa_version" lt "$min_mesa"; then
  if [ "$debian12" -ne 1 ]; then
    echo "setup: mesa-vulkan-drivers $mesa_version has no ray tracing in lavapipe (needs $min_mesa)." >&2
    echo "setup: the bookworm-backports source is for Debian 12 only; this is ${os_id:-unknown} ${os_version}:" >&2
    echo "setup: not adding it. Install Mesa >= $min_mesa from your distribution; the rt and reference paths need it." >&2
    exit 1
  fi
  list=/etc/apt/sources.list.d/twinlight-bookworm-backports.list
  if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    echo "setup: mesa-vulkan-drivers $mesa_version has no ray tracing in lavapipe (needs $min_mesa): will add"
    echo "setup:   $list (deb http://deb.debian.org/debian bookworm-backports main),"
    echo "setup:   run apt-get update and install mesa-vulkan-drivers from bookworm-backports"
    echo "deb http://deb.debian.org/debian bookworm-backports main" | "${sudo_cmd[@]}" tee "$list" >/dev/null
  else
    echo "setup: mesa-vulkan-drivers $mesa_version has no ray tracing in lavapipe (needs $min_mesa): will run"
    echo "setup:   apt-get update and install mesa-vulkan-drivers from bookworm-backports (already a source)"
  fi
  apt_get update
  apt_get install --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
elif [ "$updated" -eq 0 ]; then
  : # nothing to do
fi

if [ "${1:-}" = "--no-build" ]; then exit 0; fi

# Compiler warnings are errors (TWINLIGHT_WERROR=OFF in the environment turns that off). A
# tree configured earlier is configured again with the same switch, keeping its generator
# and build type: one configured without -Werror does not stay that way.
werror="${TWINLIGHT_WERROR:-ON}"
if [ -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build_dir" -DTWINLIGHT_WERROR="$werror" >/dev/null
else
  cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTWINLIGHT_WERROR="$werror"
fi
cmake --build "$build_dir"

# The fuzz targets the full suite's fuzz.bounded runs (fuzz/ci.sh): built here, not inside a
# test, so the suite's time is the tests'. Incremental after the first build.
if [ "${1:-}" != "--no-fuzz" ]; then
  "$root/fuzz/ci.sh" build "$build_dir/fuzz-ci"
fi
