#!/usr/bin/env bash
# Installs the Debian 12 packages beamid needs, and only those that are missing.
# Quiet and fast (one dpkg-query) when everything is present; uses sudo when not root.
# The list follows ../shared/docs/toolchain.md, without the packages beamid does not use
# (matplotlib, MPI, yaml-cpp, nlohmann-json, fmt).
set -euo pipefail

packages=(
  g++ make cmake pkgconf git
  libeigen3-dev libsundials-dev libnlopt-cxx-dev libceres-dev libfftw3-dev libtomlplusplus-dev
  libcli11-dev libgtest-dev libbenchmark-dev libmatio-dev zlib1g-dev
  python3 python3-numpy python3-markdown   # the README's .npy example; REPORT.html
  pybind11-dev python3-dev python3-setuptools python3-venv python3-pytest python3-matplotlib   # the Python package
  gnuplot-nox
  chromium   # the REPORT.html check opens the page in headless Chromium
)

# `deps.sh fuzz`: the packages `make fuzz` needs as well (clang with libFuzzer).
if [ "${1:-}" = fuzz ]; then packages+=(clang libclang-rt-14-dev); fi
# `deps.sh slurm`: a single-node Slurm for `make test-slurm`.
if [ "${1:-}" = slurm ]; then packages+=(slurm-wlm munge); fi
# `deps.sh bench`: the NumPy/SciPy peers of `make bench` (Debian's python3, not a pip one).
if [ "${1:-}" = bench ]; then packages+=(python3 python3-numpy python3-scipy); fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "deps: installing missing Debian packages: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "deps: not root and no sudo: install these packages by hand: ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q >&2
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
