#!/usr/bin/env bash
# One-time set-up on a fresh Debian bookworm machine: packages, the LAMMPS headers that
# liblammps-dev does not ship (from the Debian source package of the same version), the build.
# Idempotent: re-running skips what is already there.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$top/build}
sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"

packages=(build-essential cmake dpkg-dev pkg-config
          lammps liblammps-dev libopenmpi-dev openmpi-bin
          libgtest-dev libgmock-dev libbenchmark-dev libsiconos-numerics-dev libfclib-dev
          libfftw3-dev libgsl-dev libeigen3-dev zlib1g-dev gnuplot-nox hyperfine
          liggghts clang-format flake8)

need_install=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need_install+=("$p")
done

src_list=/etc/apt/sources.list.d/lammps-src.sources
if [ ! -f "$src_list" ]; then
  $sudo_cmd tee "$src_list" >/dev/null <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  fresh_sources=1
fi

if [ ${#need_install[@]} -gt 0 ] || [ -n "${fresh_sources:-}" ]; then
  $sudo_cmd apt-get update -q
fi
if [ ${#need_install[@]} -gt 0 ]; then
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${need_install[@]}"
fi

# LAMMPS headers missing from liblammps-dev, taken from the matching source package.
headers=$build/lammps-headers
if [ ! -f "$headers/.complete" ]; then
  tmp=$(mktemp -d)
  (cd "$tmp" && apt-get source -q --download-only lammps >/dev/null)
  tarball=$(ls "$tmp"/lammps_*.orig.tar.* | head -n1)
  tar -xf "$tarball" -C "$tmp" --wildcards '*/src/*.h'
  source_dir=$(dirname "$(ls -d "$tmp"/*/src/fmt)")
  mkdir -p "$headers/fmt"
  cp "$source_dir"/fmt/*.h "$headers/fmt/"
  cp "$source_dir"/*.h "$headers/"
  touch "$headers/.complete"
  rm -rf "$tmp"
fi

cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release -DLAMMPS_EXTRA_HEADERS="$headers"
cmake --build "$build" -j "$(nproc)"
