// Adaptive mode (Algorithm III) on single patches and shells: valid meshes, sizes that follow
// the radius function, bounded grading, the clamps, and the same mesh in every pose.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "laytracks/brep/build.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/medial/part_medial.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "test_support.hpp"

using namespace laytracks;
using namespace laytracks::test;

namespace {

MeshPartOptions adaptive(double dtheta_deg = kDefaultDthetaDeg) {
  MeshPartOptions o;
  o.adaptive = true;
  o.dtheta_deg = dtheta_deg;
  return o;
}

/// The radius function at each quad: the radius of the maximal disk touching the boundary at
/// the boundary point nearest the quad's centroid (in its patch).
std::vector<double> element_radii(const Part& part, const QuadMesh& mesh) {
  const std::vector<MedialAxis> axes = compute_medial_axes(part);
  std::vector<double> radii;
  for (const MeshElement& e : mesh.elements) {
    const Patch& patch = part.patches[e.patch.index()];
    Vec3 c;
    for (std::uint32_t v : e.nodes) c = c + 0.25 * mesh.nodes[v];
    const Vec2 x = patch.frame.to_2d(c);
    BoundaryPoint best;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::uint32_t l = 0; l < patch.polygon.loops.size(); ++l) {
      const auto& loop = patch.polygon.loops[l];
      for (std::uint32_t i = 0; i < loop.size(); ++i) {
        const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
        const double t = std::clamp(dot(x - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
        const double d = distance(x, lerp(a, b, t));
        if (d < best_d) {
          best_d = d;
          best.site = {BoundarySite::Kind::Segment, l, i};
          best.s = t;
          best.position = lerp(a, b, t);
        }
      }
    }
    const auto m = axes[e.patch.index()].project(best);
    radii.push_back(m ? m->radius : 0.0);
  }
  return radii;
}

double element_size(const QuadMesh& mesh, const MeshElement& e, Vec3 n) {
  const auto& x = mesh.nodes;
  return std::sqrt(0.5 * std::abs(dot(n, cross(x[e.nodes[2]] - x[e.nodes[0]],
                                                x[e.nodes[3]] - x[e.nodes[1]]))));
}

/// Mean element size in the smallest-radius decile over that in the largest-radius decile.
double decile_size_ratio(const Part& part, const QuadMesh& mesh) {
  const std::vector<double> radii = element_radii(part, mesh);
  std::vector<std::size_t> order(mesh.elements.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return radii[a] < radii[b] || (radii[a] == radii[b] && a < b);
  });
  const std::size_t decile = std::max<std::size_t>(1, order.size() / 10);
  double small = 0.0, large = 0.0;
  for (std::size_t k = 0; k < decile; ++k) {
    const MeshElement& a = mesh.elements[order[k]];
    const MeshElement& b = mesh.elements[order[order.size() - 1 - k]];
    small += element_size(mesh, a, part.patches[a.patch.index()].frame.n);
    large += element_size(mesh, b, part.patches[b.patch.index()].frame.n);
  }
  return small / large;
}

}  // namespace

TEST_CASE("every part meshes valid in adaptive mode", "[adaptive]") {
  for (const std::string& path : all_case_files()) {
    INFO(path);
    const Part part = load_part(path);
    try {
      const MeshPartResult r = mesh_part(part, adaptive());
      CHECK(r.adaptive);
      CHECK(r.check.valid());
      CHECK(r.check.triangles == 0);
      CHECK(r.quality.invalid_elements == 0);
      CHECK(r.quality.measures[6].worst > 0.0);
    } catch (const Error& e) {
      FAIL("adaptive mode refused: " << e.what());
    }
  }
}

TEST_CASE("star_5: the quads near the tips are much smaller than at the centre", "[adaptive]") {
  const Part part = load_part(cases_dir() + "/star_5.json");
  const MeshPartResult a = mesh_part(part, adaptive(12.0));
  MeshPartOptions u;
  u.adaptive = false;
  const MeshPartResult b = mesh_part(part, u);
  const double ratio_adaptive = decile_size_ratio(part, a.mesh);
  const double ratio_uniform = decile_size_ratio(part, b.mesh);
  INFO("adaptive " << ratio_adaptive << ", uniform " << ratio_uniform);
  CHECK(ratio_adaptive < 0.3);
  CHECK(ratio_uniform > 0.5);
  CHECK(a.quality.worst_neighbour_ratio < 2.0);
}

TEST_CASE("plate_with_hole, l_shape and shells grade with the radius, within a bounded ratio",
          "[adaptive]") {
  for (const char* name : {"plate_with_hole", "l_shape", "t_junction", "open_box"}) {
    INFO(name);
    const Part part = load_part(cases_dir() + "/" + name + ".json");
    const MeshPartResult r = mesh_part(part, adaptive());
    REQUIRE(r.check.valid());
    const double ratio = decile_size_ratio(part, r.mesh);
    INFO("decile size ratio " << ratio << ", worst neighbour ratio "
                              << r.quality.worst_neighbour_ratio);
    CHECK(ratio < 0.5);
    CHECK(r.quality.worst_neighbour_ratio < 3.0);
    CHECK(r.quality.max_size > 4.0 * r.quality.min_size);
  }
}

TEST_CASE("a smaller dtheta gives a finer mesh", "[adaptive]") {
  const Part part = load_part(cases_dir() + "/plate_with_hole.json");
  const std::size_t coarse = mesh_part(part, adaptive(24.0)).mesh.elements.size();
  const std::size_t mid = mesh_part(part, adaptive(12.0)).mesh.elements.size();
  const std::size_t fine = mesh_part(part, adaptive(6.0)).mesh.elements.size();
  INFO(coarse << " " << mid << " " << fine);
  CHECK(coarse < mid);
  CHECK(mid < fine);
  CHECK(fine > 2 * coarse);
}

TEST_CASE("the size clamps (--min-size, --max-size) bound the track widths", "[adaptive]") {
  const Part part = load_part(cases_dir() + "/star_5.json");
  const MeshPartResult free = mesh_part(part, adaptive(12.0));
  // The tracks are no wider than the cap: no boundary edge (used by one quad) is longer than
  // a piece left whole (kSplitPiece = 2 widths).
  const auto longest_boundary_edge = [](const QuadMesh& mesh) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const MeshElement& e : mesh.elements)
      for (std::size_t k = 0; k < 4; ++k) ++uses[std::minmax(e.nodes[k], e.nodes[(k + 1) % 4])];
    double longest = 0.0;
    for (const auto& [edge, n] : uses) {
      if (n == 1)
        longest = std::max(longest, distance(mesh.nodes[edge.first], mesh.nodes[edge.second]));
    }
    return longest;
  };
  const double cap = 0.4 * longest_boundary_edge(free.mesh);
  MeshPartOptions capped = adaptive(12.0);
  capped.max_size = cap;
  const MeshPartResult c = mesh_part(part, capped);
  CHECK(c.check.valid());
  CHECK(c.mesh.elements.size() > free.mesh.elements.size());
  CHECK(longest_boundary_edge(c.mesh) <= 2.0 * cap);
  MeshPartOptions floored = adaptive(12.0);
  floored.min_size = 4.0 * free.size;  // four times MIN_END_WIDTH
  const MeshPartResult f = mesh_part(part, floored);
  CHECK(f.check.valid());
  CHECK(f.size == Approx(4.0 * free.size));
  CHECK(f.mesh.elements.size() < free.mesh.elements.size());
}

TEST_CASE("adaptive meshes are the same in every pose", "[adaptive][pose]") {
  for (const std::string& path : all_case_files()) {
    INFO(path);
    const RawPart raw = read_brep_json(path);
    const MeshPartResult base = mesh_part(build_part(raw), adaptive());
    const std::vector<Transform> poses = {
        compose(translation({3.0, -7.0, 11.0}), rotation({1, 2, 3}, 0.7)), mirror_x(),
        scaling(1e-3), compose(scaling(1e3), rotation({0, 1, 1}, 2.0))};
    for (std::size_t k = 0; k < poses.size(); ++k) {
      INFO("pose " << k << " of rotated+translated, mirrored, x1e-3, x1e3+rotated");
      const MeshPartResult r = mesh_part(build_part(transformed(raw, poses[k])), adaptive());
      CHECK(r.check.valid());
      CHECK(r.mesh.elements.size() == base.mesh.elements.size());
      CHECK(r.mesh.nodes.size() == base.mesh.nodes.size());
    }
  }
}
