#!/usr/bin/env bash
# Installs every build/run/test dependency from Debian 12 packages.
# Idempotent: when every package is already present it only runs dpkg-query (< 1 s).
# gmsh: the command that meshes .geo scripts into the .msh files fsi reads (fsi itself does not link the Gmsh
# library; tests/data/gmsh/generate.sh uses the command to regenerate test meshes).
set -euo pipefail

packages=(
  cmake g++ ninja-build pkg-config
  libeigen3-dev libyaml-cpp-dev libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  libhdf5-dev hdf5-tools gmsh libnanoflann-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-matplotlib python3-h5py python3-yaml python3-scipy
)
# python3-yaml: cases/coupled/summarize.py reads the coupled cases' reference.yaml.
# python3-scipy: studies/sail/sail_theory.py (linear algebra and root finding of the sail reference; test sail.theory).

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

root="$(cd "$(dirname "$0")/.." && pwd)"
if [ ${#missing[@]} -eq 0 ]; then
  echo "[install-deps] all ${#packages[@]} packages present"
  "$root/scripts/install-openfoam.sh"
  exit 0
fi

echo "[install-deps] installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
"$root/scripts/install-openfoam.sh"
echo "[install-deps] done"
