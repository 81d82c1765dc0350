#!/usr/bin/env bash
# OpenFOAM v1912 from Debian 12 for the adapter: the solvers and libraries (binary packages) and, because
# Debian ships no headers, the matching source package's headers flattened into one folder per library
# (what wmake's lnInclude folders would hold: .H and the template .C files that NoRepository includes).
# Idempotent: a stamp file marks a finished header tree. Usage: scripts/install-openfoam.sh [DEST]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dest="${1:-$root/.deps/openfoam-1912}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# lbzip2: tar unpacks the source package's .orig.tar.bz2 with it (minimal Debian has no bzip2 program:
# "tar (child): lbzip2: Cannot exec").
need=()
for p in openfoam libopenfoam openmpi-bin lbzip2; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "[install-openfoam] installing ${need[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

if [ -f "$dest/include/.complete" ]; then
  echo "[install-openfoam] headers present in $dest/include"
  exit 0
fi

# The source package needs a deb-src entry next to the deb one (same mirrors).
if ! grep -rqs "deb-src" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  src=/etc/apt/sources.list.d/debian.sources
  if [ -f "$src" ]; then
    sed -e 's/^Types: deb$/Types: deb-src/' "$src" | $SUDO tee /etc/apt/sources.list.d/fsi-debian-src.sources >/dev/null
  else
    grep -E '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' | $SUDO tee /etc/apt/sources.list.d/fsi-debian-src.list >/dev/null
  fi
  $SUDO apt-get update -qq
fi

work="$dest/source"
mkdir -p "$work"
( cd "$work" && [ -n "$(ls openfoam_*.orig.tar.* 2>/dev/null)" ] || apt-get source --download-only -qq openfoam )
echo "[install-openfoam] extracting headers"
tarball="$(ls "$work"/openfoam_*.orig.tar.* | head -n 1)"
tar xf "$tarball" -C "$work" --wildcards '*/src/*'
srcdir="$(ls -d "$work"/openfoam-*/src | head -n 1)"
rm -rf "$dest/include"
for lib in OpenFOAM OSspecific/POSIX finiteVolume meshTools dynamicMesh dynamicFvMesh fvMotionSolver \
           fileFormats surfMesh TurbulenceModels/turbulenceModels TurbulenceModels/incompressible \
           transportModels functionObjects/forces; do
  out="$dest/include/$(echo "$lib" | tr / _)"
  mkdir -p "$out"
  find "$srcdir/$lib" -type f \( -name '*.H' -o -name '*.C' -o -name '*.hxx' \) -not -path '*/lnInclude/*' \
    -exec cp -t "$out" {} +
done
# transportModels is also used with its folder structure (transportModels/incompressible/...).
mkdir -p "$dest/include/tree"
cp -r "$srcdir/transportModels" "$dest/include/tree/"
rm -rf "$work"/openfoam-*/
touch "$dest/include/.complete"
echo "[install-openfoam] headers in $dest/include"
