#!/usr/bin/env bash
# Installs the Debian 12 packages laytracks builds against, and only those that are missing.
# Non-interactive and idempotent: when everything is present it changes nothing.
set -euo pipefail

packages=(
  cmake g++ make            # the toolchain (already on a fresh machine; listed to be sure)
  libcgal-dev libgmp-dev libmpfr-dev   # segment Voronoi diagram, exact predicates
  libopenmesh-dev           # polygon mesh and its I/O
  libboost-graph-dev        # dual graph and CUT-GRAPH
  nlohmann-json3-dev        # the B-Rep JSON reader
  catch2                    # tests (v2)
  python3-meshio gmsh       # mesh-writer tests: meshio reads every format back, gmsh opens .msh
  assimp-utils              # and assimp reads .obj and .off (meshio reads OFF only as triangles)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# Refresh the package lists when some missing package is unknown to them (a fresh machine).
for p in "${missing[@]}"; do
  if ! apt-cache show "$p" >/dev/null 2>&1; then
    echo "setup: apt-get update"
    $sudo apt-get update -q
    break
  fi
done

echo "setup: installing ${missing[*]} (libopenmesh-dev alone brings about 80 packages)"
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
