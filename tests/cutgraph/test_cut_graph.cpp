// Rails across patches (Algorithm II), corridors and track rails, on the test parts.
#include <array>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "laytracks/brep/build.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/medial/part_medial.hpp"
#include "test_support.hpp"

using namespace laytracks;
using namespace laytracks::test;

namespace {

struct Laid {
  Part part;
  std::vector<MedialAxis> axes;
  CutGraph graph;
};

Laid lay(const RawPart& raw, double width) {
  Laid l{build_part(raw), {}, {}};
  l.axes = compute_medial_axes(l.part);
  CutGraphOptions o;
  o.track_width = width;
  l.graph = build_cut_graph(l.part, l.axes, o);
  return l;
}

std::map<RailEnd, std::size_t> ends(const CutGraph& g) {
  std::map<RailEnd, std::size_t> m;
  for (const RailChain& c : g.chains) {
    ++m[c.start];
    ++m[c.end];
  }
  return m;
}

/// A closed hexagonal prism: two hexagons and six rectangles.
RawPart hex_prism() {
  RawPart raw;
  raw.source = "hex_prism";
  for (double z : {0.0, 8.0}) {
    for (int i = 0; i < 6; ++i) {
      raw.vertices.push_back({5.0 * std::cos(M_PI * i / 3), 5.0 * std::sin(M_PI * i / 3), z});
    }
  }
  raw.patches.push_back({std::string("bottom"), {{5, 4, 3, 2, 1, 0}}});
  raw.patches.push_back({std::string("top"), {{6, 7, 8, 9, 10, 11}}});
  for (std::int64_t i = 0; i < 6; ++i) {
    const std::int64_t j = (i + 1) % 6;
    raw.patches.push_back({"side" + std::to_string(i), {{i, j, j + 6, i + 6}}});
  }
  return raw;
}

}  // namespace

TEST_CASE("closed cube: rails through the edge midpoints, loops round every corner", "[cutgraph]") {
  const Laid l = lay(read_brep_json(cases_dir() + "/closed_cube.json"), 1.0);
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  // The 12 edge midpoints are the sources; each source chain joins two face centres.
  std::size_t sources = 0;
  for (const GCutVert& g : l.graph.gverts) {
    if (!g.source) continue;
    ++sources;
    CHECK(std::fabs(g.t - 0.5) < 1e-12);
  }
  CHECK(sources == 12);
  std::size_t loops = 0;
  for (const RailChain& c : l.graph.chains) {
    if (c.end == RailEnd::Loop) {
      ++loops;
      CHECK(c.patches.size() == 3);  // round one corner, through three faces
      CHECK(c.closure_gap <= 1e-9 * l.part.size);
    } else {
      CHECK(c.start == RailEnd::BranchPoint);
      CHECK(c.end == RailEnd::BranchPoint);
      CHECK(c.source);
    }
  }
  // Corridors round each corner are 5 long: 5 tracks, so 4 loops per corner.
  CHECK(loops == 8 * 4);
}

TEST_CASE("the validator catches crossing rails, MA points off the axis and missing images",
          "[cutgraph][validator]") {
  const Laid l = lay(read_brep_json(cases_dir() + "/rect_10x4.json"), 0.5);
  REQUIRE(validate_cut_graph(l.part, l.axes, l.graph).empty());
  const auto mentions = [](const std::vector<std::string>& problems, const std::string& what) {
    return std::any_of(problems.begin(), problems.end(),
                       [&](const std::string& p) { return p.find(what) != std::string::npos; });
  };
  {  // an MA-CUT-VERT moved off its MA edge
    CutGraph g = l.graph;
    g.macuts[0].point.position = g.macuts[0].point.position + Vec2{0.3, 0.2};
    CHECK(mentions(validate_cut_graph(l.part, l.axes, g), "lies off its MA edge"));
  }
  {  // two rails of the long sides made to cross: swap the MA points of two rail segments
    CutGraph g = l.graph;
    std::size_t a = SIZE_MAX, b = SIZE_MAX;
    for (std::size_t i = 0; i < g.segments.size(); ++i) {
      const Vec2 c = g.cuts[g.segments[i].cut.index()].position;
      const MaCutVert& m = g.macuts[g.segments[i].ma.index()];
      if (m.branch || std::fabs(c.y - g.cuts[g.segments[0].cut.index()].position.y) > 1e-9)
        continue;
      if (a == SIZE_MAX)
        a = i;
      else if (std::fabs(c.x - g.cuts[g.segments[a].cut.index()].position.x) > 1.0) {
        b = i;
        break;
      }
    }
    REQUIRE(b != SIZE_MAX);
    std::swap(g.segments[a].ma, g.segments[b].ma);
    CHECK(mentions(validate_cut_graph(l.part, l.axes, g), "cross inside"));
  }
  {  // a rail point on a shared edge with no image on either patch
    const Laid cube = lay(read_brep_json(cases_dir() + "/closed_cube.json"), 1.0);
    CutGraph g = cube.graph;
    GCutVert orphan = g.gverts.front();
    orphan.source = false;
    g.gverts.push_back(orphan);
    CHECK(mentions(validate_cut_graph(cube.part, cube.axes, g), "has 0 images but its edge has 2"));
  }
}

TEST_CASE("a round plate: its axis is one point, and every rail ends at the centre", "[cutgraph]") {
  RawPart raw;
  raw.source = "disk";
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * M_PI * i / 3.0;
    raw.vertices.push_back({10.0 * std::cos(a), 10.0 * std::sin(a), 0.0});
    raw.arcs.push_back(
        {i, (i + 1) % 3, {10.0 * std::cos(a + M_PI / 3.0), 10.0 * std::sin(a + M_PI / 3.0), 0.0}});
  }
  raw.patches.push_back({std::string("disk"), {{0, 1, 2}}});
  const Laid l = lay(raw, 1.0);
  REQUIRE(l.axes[0].edges().empty());
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  const auto e = ends(l.graph);
  CHECK(e.count(RailEnd::Lost) == 0);
  CHECK(e.at(RailEnd::RoundCorner) == e.at(RailEnd::FreeEdge));
  CHECK(e.at(RailEnd::RoundCorner) >= 50);  // about 2 pi 10 / 1 tracks
}

TEST_CASE("a closed hexagonal prism closes its loops too", "[cutgraph]") {
  const Laid l = lay(hex_prism(), 0.8);
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  const auto e = ends(l.graph);
  CHECK(e.count(RailEnd::FreeEdge) == 0);
  CHECK(e.count(RailEnd::Lost) == 0);
  CHECK(e.count(RailEnd::Loop) > 0);
  for (const RailChain& c : l.graph.chains) {
    if (c.end == RailEnd::Loop) CHECK(c.closure_gap <= 1e-9 * l.part.size);
  }
}

TEST_CASE("open box: rails end on the free top edges", "[cutgraph]") {
  const Laid l = lay(read_brep_json(cases_dir() + "/open_box.json"), 1.5);
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  const auto e = ends(l.graph);
  CHECK(e.at(RailEnd::FreeEdge) > 0);
  CHECK(e.count(RailEnd::Lost) == 0);
  for (const RailChain& c : l.graph.chains) {
    if (c.end != RailEnd::FreeEdge) continue;
    const GCutVert& g = l.graph.gverts[c.through.back().index()];
    CHECK(std::fabs(g.position.z - 12.0) < 1e-9);  // the free edges are the top rim
  }
}

TEST_CASE("t-junction: a rail reaching the rib's foot continues into both other patches",
          "[cutgraph]") {
  const Laid l = lay(read_brep_json(cases_dir() + "/t_junction.json"), 1.0);
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  // Every rail point on the foot (x = 10, z = 0) has an image in all three patches.
  std::size_t on_foot = 0;
  for (std::size_t i = 0; i < l.graph.gverts.size(); ++i) {
    const GCutVert& g = l.graph.gverts[i];
    if (g.vertex || l.part.edges[g.edge.index()].patches.size() != 3) continue;
    ++on_foot;
    std::size_t images = 0;
    for (const CutVert& c : l.graph.cuts) images += c.g.index() == i ? 1u : 0u;
    CHECK(images == 3);
  }
  CHECK(on_foot > 0);
  CHECK(ends(l.graph).at(RailEnd::Junction) > 0);
}

TEST_CASE("L-shape: a rail runs from the branch point into the concave corner", "[cutgraph]") {
  const Laid l = lay(read_brep_json(cases_dir() + "/l_shape.json"), 1.0);
  CHECK(validate_cut_graph(l.part, l.axes, l.graph).empty());
  CHECK(ends(l.graph).at(RailEnd::ConcaveVertex) >= 1);
}

TEST_CASE("two close branch points: the narrow corridor between them is removed",
          "[cutgraph][narrow]") {
  RawPart raw;
  raw.vertices = {{0, 0, 0}, {4.2, 0, 0}, {4.2, 4, 0}, {0, 4, 0}};
  raw.patches.push_back({std::string("plate"), {{0, 1, 2, 3}}});
  const Part part = build_part(raw);
  const auto axes = compute_medial_axes(part);
  CutGraphOptions keep;
  keep.track_width = 1.0;
  keep.narrow_fraction = 0.0;
  keep.lay_tracks = false;
  const CutGraph before = build_cut_graph(part, axes, keep);
  CutGraphOptions remove = keep;
  remove.narrow_fraction = 0.5;
  const CutGraph after = build_cut_graph(part, axes, remove);
  CHECK(after.corridor_count == before.corridor_count - 1);
  // The rail through one branch point (top and bottom touching points) is gone: case 4.
  REQUIRE(after.deleted.size() == 2);
  for (const DeletedRail& d : after.deleted) CHECK(d.through_branch_point);
  CHECK(validate_cut_graph(part, axes, after).empty());
}

TEST_CASE("far-apart narrow corridors lose their rails in one round", "[cutgraph][narrow]") {
  // Four shells, each the plate of the test above (one narrow corridor between two close
  // branch points), and a fifth whose plate is turned: each round deletes for the narrowest
  // corridor of every region (its patches and their neighbours, untouched by a narrower one),
  // so all five go in one round, not five, and each plate loses what it loses alone.
  RawPart raw;
  for (int k = 0; k < 5; ++k) {
    const double x = 10.0 * k;
    const auto b = static_cast<std::int64_t>(raw.vertices.size());
    if (k < 4)
      raw.vertices.insert(raw.vertices.end(), {{x, 0, 0}, {x + 4.2, 0, 0}, {x + 4.2, 4, 0}, {x, 4, 0}});
    else
      raw.vertices.insert(raw.vertices.end(), {{x, 0, 0}, {x + 4, 0, 0}, {x + 4, 4.2, 0}, {x, 4.2, 0}});
    raw.patches.push_back({"plate" + std::to_string(k), {{b, b + 1, b + 2, b + 3}}});
  }
  const Part part = build_part(raw);
  const auto axes = compute_medial_axes(part);
  CutGraphOptions o;
  o.track_width = 1.0;
  o.lay_tracks = false;
  const CutGraph g = build_cut_graph(part, axes, o);
  CHECK(g.deleted.size() == 10);
  CHECK(g.narrow_rounds == 1);
  o.narrow_fraction = 0.0;
  CHECK(g.corridor_count == build_cut_graph(part, axes, o).corridor_count - 5);
  CHECK(validate_cut_graph(part, axes, g).empty());
}

namespace {

/// A torus of 24 x 12 quads (its rails run round it), an icosphere of 320 triangles (radii
/// jittered by `jitter`), and every test part.
std::vector<std::pair<std::string, RawPart>> shells_and_cases(double jitter) {
  std::vector<std::pair<std::string, RawPart>> parts = {{"torus 24 x 12", torus(24, 12, 30, 8)},
                                                        {"icosphere 320", icosphere(2, 50, jitter)}};
  for (const std::string& file : all_case_files()) parts.push_back({file, read_brep_json(file)});
  return parts;
}

/// A part with its axes, and options that lay its source rails at its own element size.
struct SourcesOnly {
  Part part;
  std::vector<MedialAxis> axes;
  CutGraphOptions options;
  explicit SourcesOnly(const RawPart& raw)
      : part(build_part(raw)), axes(compute_medial_axes(part)) {
    options.track_width = part.mesh.size.value_or(part.bbox.diagonal() / 40.0);
    options.lay_tracks = false;
  }
};

}  // namespace

TEST_CASE("narrow-corridor rounds delete what one deletion per round deletes, in far fewer "
          "rounds", "[cutgraph][narrow]") {
  // A torus of 24 x 12 quads: its rails run round it, so the patches round any narrow corridor
  // hold every other one, and one deletion per round took 48 rounds; far apart by corridors,
  // they go in two. An icosphere: far apart by patches. Since session 48 the torus's crowded
  // rail sets are left out before the rounds (docs/cutgraph.md, "Crowded rails") and it has
  // no narrow corridor left: the rounds are checked on every source rail as well.
  for (const bool crowded_out : {false, true}) {
    for (const auto& [name, raw] : shells_and_cases(0.0)) {
      CAPTURE(name, crowded_out);
      SourcesOnly s(raw);
      s.options.drop_crowded_rails = crowded_out;
      const CutGraph g = build_cut_graph(s.part, s.axes, s.options);
      s.options.narrow_one_per_round = true;
      const CutGraph one = build_cut_graph(s.part, s.axes, s.options);
      CHECK(one.narrow_rounds <= one.deleted.size());
      const auto at = [](const CutGraph& c) {
        std::vector<std::array<double, 3>> a;
        for (const DeletedRail& d : c.deleted) a.push_back({d.at.x, d.at.y, d.at.z});
        std::sort(a.begin(), a.end());
        return a;
      };
      CHECK(at(g) == at(one));
      CHECK(g.corridor_count == one.corridor_count);
      CHECK(g.narrow_kept == one.narrow_kept);
      CHECK(g.gverts.size() == one.gverts.size());
      CHECK(g.crowded_rails == one.crowded_rails);
      CHECK(g.narrow_rounds <= one.narrow_rounds);
      if (name == "torus 24 x 12" && !crowded_out) {
        CHECK(one.narrow_rounds >= 40);
        CHECK(g.narrow_rounds <= 3);
      }
      if (name == "torus 24 x 12" && crowded_out) CHECK(g.crowded_rails > 0);
    }
  }
}

TEST_CASE("corridors counted with the rounds' cache of mapped points are those found afresh",
          "[cutgraph][narrow]") {
  // build_cut_graph keeps where CUT-SEGs' points map across the axis from one search for
  // corridors to the next; corridor_pieces maps them all again.
  const auto fresh = [](const Part& part, const std::vector<MedialAxis>& axes, const CutGraph& g) {
    std::size_t n = 0;
    for (const CorridorPiece& c : corridor_pieces(part, axes, g)) n = std::max(n, c.corridor + 1);
    return n;
  };
  for (const auto& [name, raw] : shells_and_cases(0.15)) {
    CAPTURE(name);
    SourcesOnly s(raw);
    const CutGraph sources = build_cut_graph(s.part, s.axes, s.options);
    CHECK(sources.corridor_count == fresh(s.part, s.axes, sources));
    s.options.lay_tracks = true;
    const CutGraph tracks = build_cut_graph(s.part, s.axes, s.options);
    CHECK(tracks.track_count == fresh(s.part, s.axes, tracks));
    CHECK(tracks.track_count >= tracks.corridor_count);
  }
}

TEST_CASE("after removal, every corridor narrower than the minimum is a kept small feature",
          "[cutgraph][narrow][cases]") {
  for (const std::string& file : all_case_files()) {
    CAPTURE(file);
    const Part part = build_part(read_brep_json(file));
    const auto axes = compute_medial_axes(part);
    CutGraphOptions o;
    o.track_width = part.mesh.size.value_or(part.bbox.diagonal() / 40.0);
    o.lay_tracks = false;
    const CutGraph g = build_cut_graph(part, axes, o);
    std::map<std::size_t, double> width;
    for (const CorridorPiece& c : corridor_pieces(part, axes, g)) {
      width[c.corridor] = std::max(width[c.corridor], c.length);
    }
    std::size_t narrow = 0;
    for (const auto& kv : width) narrow += kv.second < o.narrow_fraction * o.track_width ? 1u : 0u;
    CHECK(narrow == g.narrow_kept);
    CHECK(validate_cut_graph(part, axes, g).empty());
  }
}

TEST_CASE("the validator passes on every part, and no rail is lost", "[cutgraph][cases]") {
  for (const std::string& file : all_case_files()) {
    CAPTURE(file);
    const RawPart raw = read_brep_json(file);
    const Part part = build_part(raw);
    const double width = part.mesh.size.value_or(part.bbox.diagonal() / 40.0);
    const Laid l = lay(raw, width);
    const auto problems = validate_cut_graph(l.part, l.axes, l.graph);
    INFO((problems.empty() ? std::string() : problems.front()));
    CHECK(problems.empty());
    CHECK(ends(l.graph).count(RailEnd::Lost) == 0);
  }
}

TEST_CASE("rotated and mirrored parts give the same rails", "[cutgraph][metamorphic]") {
  for (const std::string& name : all_case_files()) {
    CAPTURE(name);
    const RawPart raw = read_brep_json(name);
    const Part part = build_part(raw);
    const double w = part.mesh.size.value_or(part.bbox.diagonal() / 40.0);
    const Laid base = lay(raw, w);
    for (const Transform& t :
         {rotation({1, 2, 3}, 0.7), mirror_x(), compose(scaling(1e3), rotation({0, 1, 1}, 2.0))}) {
      const double k = norm(t.apply({1, 0, 0}) - t.apply({0, 0, 0}));
      const Laid moved = lay(transformed(raw, t), k * w);
      CHECK(moved.graph.gverts.size() == base.graph.gverts.size());
      CHECK(moved.graph.chains.size() == base.graph.chains.size());
      CHECK(ends(moved.graph) == ends(base.graph));
    }
  }
}
