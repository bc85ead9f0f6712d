#!/usr/bin/env bash
# Sets up, builds, and runs the main job on a sample part: its medial axis, as JSON and as a
# picture, in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/cli/laytracks medial samples/bracket.json --json out/bracket-medial.json --svg out/bracket-medial.svg
echo "wrote out/bracket-medial.json and out/bracket-medial.svg"
