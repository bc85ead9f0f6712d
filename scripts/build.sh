#!/usr/bin/env bash
# Sets up the dependencies, then configures and builds laytracks in build/ (Release).
# Extra CMake options may be passed as arguments, e.g. scripts/build.sh -DLAYTRACKS_WERROR=ON
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j "$(nproc)"
