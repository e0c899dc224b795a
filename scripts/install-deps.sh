#!/usr/bin/env bash
# Installs every Debian package the project builds, tests or runs with.
# Why each is here (keep this list short and true):
#   cmake ninja-build g++ clang       build; clang (with libclang-rt) for libFuzzer and sanitizers
#   lld                               the linker (cmake/Linker.cmake): links the big binaries 3x faster than ld
#   libeigen3-dev                     mixtures of Gaussians and linear algebra in the verifier
#   libserialport-dev                 the Pioneer's serial port (ARIA-compatible, 8N1)
#   liblcm-dev liblcm-bin             inter-robot team link over UDP multicast; lcm-gen at build time
#   doctest-dev                       unit and hardware-in-the-loop tests
#   libsodium-dev                     authenticating team messages with the team key
#   libyaml-cpp-dev                   mission, world and robot-model files
#   nlohmann-json3-dev                --json output
#   libcli11-dev                      command-line parsing of every binary
#   gnuplot-nox                       report figures (PNG and SVG)
#   can-utils busybox-static user-mode-linux   real SocketCAN tests inside a user-mode Linux kernel
#   python3                           small test drivers (stdlib only)
#   qemu-system-x86                   the serial rig: a real 8250 driver on an emulated 16550 UART
#                                     (scripts/run-serial-tests.sh; libserialport refuses ptys)
#   munge slurmctld slurmd slurm-client   a real single-node Slurm (cluster/slurm-local-up.sh) for the CI test of
#                                     sharded validation: labs run big campaigns on Slurm (docs/cluster.md)
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  cmake ninja-build g++ clang libclang-rt-14-dev lld pkg-config git
  libeigen3-dev libserialport-dev liblcm-dev liblcm-bin doctest-dev libsodium-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev gnuplot-nox
  can-utils busybox-static user-mode-linux python3 procps iproute2
  qemu-system-x86
  munge slurmctld slurmd slurm-client
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all ${#PACKAGES[@]} packages present"
fi
