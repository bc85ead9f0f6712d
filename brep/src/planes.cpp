// Rules 5-6 of build_part(): best-fit planes, planarity, degenerate patches, patch frames.
#include <algorithm>
#include <array>
#include <cmath>

#include "build_state.hpp"
#include "describe.hpp"

namespace laytracks::detail {
namespace {

/// Eigen-decomposition of a symmetric 3x3 matrix: values ascending, unit vectors to match.
struct Eigen3 {
  std::array<double, 3> values;
  std::array<Vec3, 3> vectors;
};

/// Cyclic Jacobi rotations on a symmetric 3x3 matrix `a` (destroyed) until it is diagonal.
Eigen3 symmetric_eigen(std::array<std::array<double, 3>, 3> a) {
  std::array<std::array<double, 3>, 3> v = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 64; ++sweep) {
    const double off = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
    const double diag = std::fabs(a[0][0]) + std::fabs(a[1][1]) + std::fabs(a[2][2]);
    if (off == 0.0 || off <= 1e-30 * diag) break;
    for (std::size_t p = 0; p < 2; ++p) {
      for (std::size_t q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // The rotation that zeroes a[p][q] (Golub & Van Loan, Algorithm 8.4.1).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        for (std::size_t k = 0; k < 3; ++k) {  // a <- a J
          const double akp = a[k][p];
          const double akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (std::size_t k = 0; k < 3; ++k) {  // a <- J^T a
          const double apk = a[p][k];
          const double aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (std::size_t k = 0; k < 3; ++k) {  // v <- v J
          const double vkp = v[k][p];
          const double vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  std::array<std::size_t, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return a[i][i] < a[j][j]; });
  Eigen3 e;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t k = order[i];
    e.values[i] = a[k][k];
    e.vectors[i] = normalized(Vec3{v[0][k], v[1][k], v[2][k]});
  }
  return e;
}

/// The centroid of the points, summed as offsets from the first (precision far from 0).
Vec3 centroid(const std::vector<Vec3>& points) {
  Vec3 sum;
  for (const Vec3& q : points) sum = sum + (q - points[0]);
  return points[0] + (1.0 / static_cast<double>(points.size())) * sum;
}

/// Covariance of the points about c.
std::array<std::array<double, 3>, 3> covariance(const std::vector<Vec3>& points, Vec3 c) {
  std::array<std::array<double, 3>, 3> m{};
  for (const Vec3& q : points) {
    const double d[3] = {q.x - c.x, q.y - c.y, q.z - c.z};
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 3; ++j) m[i][j] += d[i] * d[j];
    }
  }
  return m;
}

/// The patch's points: every vertex of its chains (loop vertices and arc points).
std::vector<VertexId> patch_vertices(const BuildState& s, std::size_t p) {
  std::vector<VertexId> ids;
  for (const Chain& c : s.chains[p]) ids.insert(ids.end(), c.vertices.begin(), c.vertices.end());
  return ids;
}

/// The patch's bbox diagonal, over its points and the via points of its arcs.
double patch_diagonal(const BuildState& s, std::size_t p, const std::vector<Vec3>& points) {
  Box3 box;
  for (const Vec3& q : points) box.add(q);
  for (std::size_t a : s.patch_arcs[p]) box.add(s.raw.arcs[a].via);
  return box.diagonal();
}

/// Refuses a point or via point farther than tol from the plane (c, n), naming the worst.
void check_planarity(const BuildState& s,
                     std::size_t p,
                     const std::vector<VertexId>& ids,
                     Vec3 c,
                     Vec3 n,
                     double tol) {
  std::size_t worst = 0;
  double worst_distance = -1.0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const double d = std::fabs(dot(s.part.vertices[ids[k].index()].position - c, n));
    if (d > worst_distance) worst_distance = d, worst = k;
  }
  double worst_via_distance = -1.0;
  std::size_t worst_via = 0;
  for (std::size_t a : s.patch_arcs[p]) {
    const double d = std::fabs(dot(s.raw.arcs[a].via - c, n));
    if (d > worst_via_distance) worst_via_distance = d, worst_via = a;
  }
  const std::string tolerance = " (tolerance " + len(s, tol) + ")";
  if (worst_via_distance > tol && worst_via_distance >= worst_distance) {
    fail(arc_name(s, worst_via) + ": its via point " + point(s.raw.arcs[worst_via].via) + " is " +
         len(s, worst_via_distance) + " off the plane of " + patch_name(s, p) + tolerance);
  }
  if (worst_distance > tol) {
    const VertexId v = ids[worst];
    if (v.index() >= s.file_vertex_count()) {
      const std::size_t a = s.arc_point_of[v.index() - s.file_vertex_count()].first;
      const double d = std::fabs(dot(s.raw.arcs[a].via - c, n));
      if (d > tol) {
        fail(arc_name(s, a) + ": its via point " + point(s.raw.arcs[a].via) + " is " + len(s, d) +
             " off the plane of " + patch_name(s, p) + tolerance);
      }
    }
    fail(patch_name(s, p) + " is not planar: " + vertex_name(s, v) + " is " +
         len(s, worst_distance) + " off its plane" + tolerance);
  }
}

/// When the patch's own corners (the file's vertices) are planar and the via point of one of its
/// arcs is not, names that arc: the arc, not the whole patch, is what the user must fix.
void blame_off_plane_arc(const BuildState& s,
                         std::size_t p,
                         const std::vector<VertexId>& ids,
                         double tol) {
  std::vector<Vec3> corners;
  for (VertexId v : ids) {
    if (v.index() < s.file_vertex_count()) corners.push_back(s.part.vertices[v.index()].position);
  }
  if (corners.size() < 3) return;
  const Vec3 c = centroid(corners);
  const Eigen3 e = symmetric_eigen(covariance(corners, c));
  if (std::sqrt(std::max(0.0, e.values[1] / static_cast<double>(corners.size()))) <= tol) return;
  const Vec3 n = e.vectors[0];
  for (const Vec3& q : corners) {
    if (std::fabs(dot(q - c, n)) > tol) return;  // the corners themselves are not planar
  }
  for (std::size_t a : s.patch_arcs[p]) {
    const double d = std::fabs(dot(s.raw.arcs[a].via - c, n));
    if (d > tol) {
      fail(arc_name(s, a) + ": its via point " + point(s.raw.arcs[a].via) + " is " + len(s, d) +
           " off the plane of " + patch_name(s, p) + " (tolerance " + len(s, tol) + ")");
    }
  }
}

/// Newell's normal of a closed chain (twice its vector area), about c.
Vec3 newell_normal(const BuildState& s, const Chain& chain, Vec3 c) {
  Vec3 sum;
  const std::size_t m = chain.vertices.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3 a = s.part.vertices[chain.vertices[i].index()].position - c;
    const Vec3 b = s.part.vertices[chain.vertices[(i + 1) % m].index()].position - c;
    sum = sum + cross(a, b);
  }
  return sum;
}

/// u: the first outer-loop segment direction with a usable projection on the plane normal n.
Vec3 first_direction(const BuildState& s, const Chain& outer, Vec3 n) {
  const std::size_t m = outer.vertices.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3 d = s.part.vertices[outer.vertices[(i + 1) % m].index()].position -
                   s.part.vertices[outer.vertices[i].index()].position;
    const Vec3 in_plane = d - dot(d, n) * n;
    if (norm(in_plane) > 1e-3 * norm(d)) return normalized(in_plane);
  }
  return normalized(std::fabs(n.x) < 0.5 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
}

/// Fits the plane of patch p, refuses it if degenerate or not planar, and sets its frame.
void fit_patch(BuildState& s, std::size_t p) {
  const std::vector<VertexId> ids = patch_vertices(s, p);
  std::vector<Vec3> points;
  points.reserve(ids.size());
  for (VertexId v : ids) points.push_back(s.part.vertices[v.index()].position);
  const Vec3 c = centroid(points);
  const Eigen3 e = symmetric_eigen(covariance(points, c));
  const double diag = patch_diagonal(s, p, points);
  const double tol = Tolerances::kPlanarity * diag;
  const double count = static_cast<double>(points.size());
  if (std::sqrt(std::max(0.0, e.values[1] / count)) <= tol) {
    fail(patch_name(s, p) + " is degenerate: its points all lie on one line");
  }
  Vec3 n = e.vectors[0];
  blame_off_plane_arc(s, p, ids, tol);
  check_planarity(s, p, ids, c, n, tol);
  const double twice_area = dot(newell_normal(s, s.chains[p][0], c), n);
  const bool zero_area = std::fabs(twice_area) <= 2.0 * tol * diag;
  if (twice_area < 0.0) n = -n;
  Frame& f = s.part.patches[p].frame;
  f.origin = c;
  f.n = n;
  f.u = first_direction(s, s.chains[p][0], n);
  f.v = cross(n, f.u);
  if (zero_area) {
    // A bowtie's two lobes cancel: say where the loop crosses itself, if it does.
    const std::string crossing = loop_conflict(s, p);
    if (!crossing.empty()) fail(crossing);
    fail(patch_name(s, p) + " is degenerate: its outer loop encloses zero area");
  }
}

}  // namespace

void fit_planes(BuildState& s) {
  s.loops2d.assign(s.part.patches.size(), {});
  for (std::size_t p = 0; p < s.part.patches.size(); ++p) {
    fit_patch(s, p);
    const Frame& f = s.part.patches[p].frame;
    for (const Chain& c : s.chains[p]) {
      std::vector<Vec2> loop;
      loop.reserve(c.vertices.size());
      for (VertexId v : c.vertices) loop.push_back(f.to_2d(s.part.vertices[v.index()].position));
      s.loops2d[p].push_back(std::move(loop));
    }
  }
}

}  // namespace laytracks::detail
