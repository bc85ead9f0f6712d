#!/usr/bin/env bash
# Sets up, builds with warnings as errors, and runs every test through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh -DLAYTRACKS_WERROR=ON
ctest --test-dir build --output-on-failure -j "$(nproc)"
