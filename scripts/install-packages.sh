#!/usr/bin/env bash
# Installs the Debian packages Acetate needs, and any named as arguments, when missing.
# Used by setup.sh (the build and the tests) and sanitize.sh (adds clang and its runtimes).
set -euo pipefail
# Build: compilers, CMake, the libraries. Tests: GoogleTest, Benchmark, clang-format (the
# format check), git and debootstrap (scripts/fresh-machine.sh's own tests), xmllint (the
# JUnit schema test), slurm-wlm, munge and python3-kubernetes (the `cluster` tests: a real
# one-node Slurm, the Kubernetes manifests against the API's models). Run time: openssh-client
# (ssh-keygen signs and verifies maintainers' sign-offs).
packages=(
  cmake g++ make pkg-config git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-dev glslang-tools
  libopenimageio-dev openimageio-tools libimath-dev libpng-dev libopenexr-dev
  libboost-dev libboost-filesystem-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libglm-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev clang-format debootstrap libxml2-utils
  openssh-client slurm-wlm munge python3 python3-kubernetes
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== Installing Debian packages: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  # Where no init system runs (a container, a chroot such as CI's fresh root), a package must
  # not start its daemon (munged, slurmd): the cluster tests start their own, privately, and a
  # daemon started here would outlive the root. Debian's way: a policy-rc.d that refuses every
  # start (exit 101), in place only while apt runs.
  policy=/usr/sbin/policy-rc.d
  if [ ! -d /run/systemd/system ] && [ ! -e "$policy" ]; then
    printf '#!/bin/sh\n# Written by Acetate scripts/install-packages.sh while apt runs.\nexit 101\n' |
      "${sudo_cmd[@]}" tee "$policy" >/dev/null
    "${sudo_cmd[@]}" chmod 755 "$policy"
    trap '"${sudo_cmd[@]}" rm -f "$policy"' EXIT
  fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi
