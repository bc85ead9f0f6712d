#!/usr/bin/env bash
# Sets up, builds, and runs the main job on a sample part: its medial axis (JSON and picture)
# and its rails and tracks (check-loops report and picture), in out/. The mesh comes next.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/cli/laytracks medial samples/bracket.json --json out/bracket-medial.json --svg out/bracket-medial.svg
build/cli/laytracks check-loops samples/bracket.json --json out/bracket-rails.json
build/cli/laytracks draw samples/bracket.json --stage tracks -o out/bracket-tracks.svg
echo "wrote out/bracket-medial.json, out/bracket-medial.svg, out/bracket-rails.json and out/bracket-tracks.svg"
