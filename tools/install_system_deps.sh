#!/usr/bin/env bash
# System packages dvoronoi needs to build (Eigen, libpng for PNG maps, and OpenMP through the compiler) and to test
# (CGAL as the exact oracle, doctest, nlohmann-json and CLI11 for the CLI, OpenMPI for MPI runs).
# Debian/Ubuntu; runs apt-get update first. Pass --build-only to skip the test-only packages.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PKGS="build-essential cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libpng-dev"
if [ "${1:-}" != "--build-only" ]; then
  PKGS="$PKGS libcgal-dev libgmp-dev libmpfr-dev doctest-dev openmpi-bin libopenmpi-dev"
fi
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $PKGS >/dev/null
