#!/usr/bin/env bash
# Sets up, builds, and runs the main job on a sample part: its all-quad mesh (Gmsh .msh and
# VTK .vtu, checked by quality.md before writing, with its quality report), its medial axis,
# its tracks and its quads (pictures), in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/cli/laytracks mesh samples/bracket.json -o out/bracket.msh --report out/bracket-quality.json
build/cli/laytracks mesh samples/bracket.json -o out/bracket.vtu --quiet
build/cli/laytracks medial samples/bracket.json --json out/bracket-medial.json --svg out/bracket-medial.svg
build/cli/laytracks check-loops samples/bracket.json --json out/bracket-rails.json
build/cli/laytracks draw samples/bracket.json --stage tracks -o out/bracket-tracks.svg
build/cli/laytracks draw samples/bracket.json --stage mesh -o out/bracket-mesh.svg
echo "wrote out/bracket.msh, out/bracket.vtu (open in Gmsh or ParaView), out/bracket-quality.json,"
echo "      out/bracket-medial.json, out/bracket-medial.svg, out/bracket-rails.json, out/bracket-tracks.svg,"
echo "      out/bracket-mesh.svg (the quads coloured by scaled Jacobian)"
