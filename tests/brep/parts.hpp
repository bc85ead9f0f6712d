// Small parts written in C++ for the brep tests, and helpers to check error messages.
#pragma once

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "laytracks/brep/build.hpp"
#include "laytracks/brep/dual_graph.hpp"
#include "laytracks/brep/error.hpp"

namespace laytracks::test {

using Loops = std::vector<std::vector<std::int64_t>>;

inline RawPatch patch(const std::string& name, Loops loops) {
  RawPatch p;
  p.name = name;
  p.loops = std::move(loops);
  return p;
}

inline RawPatch unnamed(Loops loops) {
  RawPatch p;
  p.loops = std::move(loops);
  return p;
}

inline RawPart make_part(std::vector<Vec3> vertices,
                         std::vector<RawPatch> patches,
                         std::vector<RawArc> arcs = {}) {
  RawPart raw;
  raw.vertices = std::move(vertices);
  raw.patches = std::move(patches);
  raw.arcs = std::move(arcs);
  return raw;
}

/// The example of ../shared/spec/brep-json.md: a floor with a round hole (four arcs), a wall.
inline RawPart spec_example() {
  RawPart raw =
      make_part({{0, 0, 0},
                 {40, 0, 0},
                 {40, 20, 0},
                 {0, 20, 0},
                 {40, 0, 15},
                 {40, 20, 15},
                 {10, 8, 0},
                 {12, 10, 0},
                 {10, 12, 0},
                 {8, 10, 0}},
                {patch("floor", {{0, 1, 2, 3}, {6, 9, 8, 7}}), patch("wall", {{1, 4, 5, 2}})},
                {{6, 7, {11.414213562373096, 8.585786437626904, 0}},
                 {7, 8, {11.414213562373096, 11.414213562373096, 0}},
                 {8, 9, {8.585786437626904, 11.414213562373096, 0}},
                 {9, 6, {8.585786437626904, 8.585786437626904, 0}}});
  raw.mesh.size = 2.0;
  return raw;
}

/// A closed 10 mm cube, as ../shared/cases/closed_cube.json.
inline RawPart cube() {
  return make_part({{0, 0, 0},
                    {0, 10, 0},
                    {10, 10, 0},
                    {10, 0, 0},
                    {0, 0, 10},
                    {10, 0, 10},
                    {10, 10, 10},
                    {0, 10, 10}},
                   {patch("bottom", {{0, 1, 2, 3}}), patch("top", {{4, 5, 6, 7}}),
                    patch("front", {{0, 3, 5, 4}}), patch("right", {{3, 2, 6, 5}}),
                    patch("back", {{2, 1, 7, 6}}), patch("left", {{1, 0, 4, 7}})});
}

/// A rib standing on a plate: edge 1-2 shared by three patches.
inline RawPart t_junction() {
  return make_part({{0, 0, 0},
                    {10, 0, 0},
                    {10, 12, 0},
                    {0, 12, 0},
                    {24, 0, 0},
                    {24, 12, 0},
                    {10, 12, 5},
                    {10, 0, 5}},
                   {patch("plate_left", {{0, 1, 2, 3}}), patch("plate_right", {{1, 4, 5, 2}}),
                    patch("rib", {{1, 2, 6, 7}})});
}

/// Two coplanar patches sharing an arc edge 1-2, which the second runs the other way.
inline RawPart shared_arc() {
  return make_part({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {20, 0, 0}, {20, 10, 0}},
                   {patch("left", {{0, 1, 2, 3}}), patch("right", {{1, 4, 5, 2}})},
                   {{1, 2, {12, 5, 0}}});
}

/// A 10 x 10 square patch "plate" in z = 0 with the given holes (vertex 4 onwards).
inline RawPart square_with_holes(std::vector<Vec3> hole_vertices, Loops holes) {
  std::vector<Vec3> v = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  v.insert(v.end(), hole_vertices.begin(), hole_vertices.end());
  Loops loops = {{0, 1, 2, 3}};
  loops.insert(loops.end(), holes.begin(), holes.end());
  return make_part(v, {patch("plate", loops)});
}

/// The message of the InputError that building `raw` throws; fails the test when none is.
inline std::string error_of(const RawPart& raw, const BuildOptions& options = {}) {
  try {
    build_part(raw, options);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("build_part accepted a part it should refuse");
  return "";
}

}  // namespace laytracks::test
