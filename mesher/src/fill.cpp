#include "fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "laytracks/brep/error.hpp"

namespace laytracks::mesher_detail {

const char* to_string(FillKind kind) {
  switch (kind) {
    case FillKind::Grid:
      return "grid";
    case FillKind::Diamond:
      return "diamond";
    case FillKind::Quad:
      return "quad";
    case FillKind::Ring:
      return "ring";
    case FillKind::Split:
      return "split";
  }
  return "?";
}

double min_scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 p[4] = {a, b, c, d};
  double worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    const Vec2 e1 = p[(i + 1) % 4] - p[i];
    const Vec2 e0 = p[(i + 3) % 4] - p[i];
    const double l = norm(e1) * norm(e0);
    const double j = l > 0.0 ? cross(e1, e0) / l : -1.0;
    worst = std::min(worst, j);
  }
  return worst;
}

namespace {

using Quad = std::array<std::uint32_t, 4>;

/// A face being meshed: its cycle, interior nodes appended, quads.
struct Builder {
  const FaceInput& face;
  FaceMesh out;
  explicit Builder(const FaceInput& f, FillKind kind) : face(f) { out.kind = kind; }

  std::uint32_t n() const { return static_cast<std::uint32_t>(face.cycle.size()); }
  /// Cycle node `k` steps after `first` (wrapping).
  std::uint32_t at(std::uint32_t first, std::int64_t k) const {
    const std::int64_t m = n();
    return static_cast<std::uint32_t>(((first + k) % m + m) % m);
  }
  Vec2 pos(std::uint32_t i) const { return i < n() ? face.cycle[i] : out.interior[i - n()]; }
  std::uint32_t add(Vec2 p) {
    out.interior.push_back(p);
    return n() + static_cast<std::uint32_t>(out.interior.size() - 1);
  }
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    out.quads.push_back({a, b, c, d});
  }
  FaceMesh finish() {
    out.min_jacobian = std::numeric_limits<double>::infinity();
    for (const Quad& q : out.quads) {
      out.min_jacobian =
          std::min(out.min_jacobian, min_scaled_jacobian(pos(q[0]), pos(q[1]), pos(q[2]), pos(q[3])));
    }
    return std::move(out);
  }
};

/// Improves a template's interior nodes in place (boundary nodes fixed).
void relax(FaceMesh& m, const FaceInput& face, int iterations) {
  if (m.interior.empty()) return;
  std::vector<Vec2> pos(face.cycle);
  pos.insert(pos.end(), m.interior.begin(), m.interior.end());
  std::vector<bool> fixed(pos.size(), false);
  std::fill(fixed.begin(), fixed.begin() + static_cast<std::ptrdiff_t>(face.cycle.size()), true);
  smooth_nodes(pos, fixed, m.quads, iterations);
  std::copy(pos.begin() + static_cast<std::ptrdiff_t>(face.cycle.size()), pos.end(),
            m.interior.begin());
  m.min_jacobian = std::numeric_limits<double>::infinity();
  for (const Quad& q : m.quads) {
    m.min_jacobian =
        std::min(m.min_jacobian, min_scaled_jacobian(pos[q[0]], pos[q[1]], pos[q[2]], pos[q[3]]));
  }
}

/// The four sides of a strip (boundary, rail, boundary, rail), starting at a boundary side.
std::optional<std::array<const FaceSide*, 4>> strip_sides(const FaceInput& face) {
  if (face.sides.size() != 4) return std::nullopt;
  for (std::size_t s = 0; s < 2; ++s) {
    std::array<const FaceSide*, 4> r{};
    for (std::size_t k = 0; k < 4; ++k) r[k] = &face.sides[(s + k) % 4];
    if (r[0]->kind == FaceSide::Kind::Boundary && r[1]->kind == FaceSide::Kind::Rail &&
        r[2]->kind == FaceSide::Kind::Boundary && r[3]->kind == FaceSide::Kind::Rail)
      return r;
  }
  return std::nullopt;
}

/// Grid: boundary pieces of b edges each, rails of m edges each; transfinite interpolation
/// between the four sides, rows of quads from one boundary piece to the other.
std::optional<FaceMesh> fill_grid(const FaceInput& face) {
  const auto sides = strip_sides(face);
  if (!sides) return std::nullopt;
  const FaceSide& b1 = *(*sides)[0];
  const FaceSide& r1 = *(*sides)[1];
  const FaceSide& b2 = *(*sides)[2];
  const FaceSide& r2 = *(*sides)[3];
  if (b1.edges != b2.edges || r1.edges != r2.edges) return std::nullopt;
  Builder m(face, FillKind::Grid);
  const std::uint32_t b = b1.edges;
  const std::uint32_t h = r1.edges;
  // Grid node (i, j), i along b1 (0..b), j along r1 (0..h).
  std::vector<std::uint32_t> id((b + 1) * (h + 1));
  auto g = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t& { return id[j * (b + 1) + i]; };
  for (std::uint32_t i = 0; i <= b; ++i) {
    g(i, 0) = m.at(b1.first, i);
    g(i, h) = m.at(b2.first, b - i);
  }
  for (std::uint32_t j = 0; j <= h; ++j) {
    g(b, j) = m.at(r1.first, j);
    g(0, j) = m.at(r2.first, h - j);
  }
  // Parameters by arc length along each side, blended (so uneven spacing carries inwards).
  auto arc = [&](auto node_of, std::uint32_t count) {
    std::vector<double> t(count + 1, 0.0);
    for (std::uint32_t k = 1; k <= count; ++k)
      t[k] = t[k - 1] + distance(m.pos(node_of(k - 1)), m.pos(node_of(k)));
    for (double& x : t) x = t[count] > 0.0 ? x / t[count] : 0.0;
    return t;
  };
  const auto u0 = arc([&](std::uint32_t i) { return g(i, 0); }, b);
  const auto u1 = arc([&](std::uint32_t i) { return g(i, h); }, b);
  const auto v0 = arc([&](std::uint32_t j) { return g(0, j); }, h);
  const auto v1 = arc([&](std::uint32_t j) { return g(b, j); }, h);
  const Vec2 c00 = m.pos(g(0, 0)), c10 = m.pos(g(b, 0)), c01 = m.pos(g(0, h)), c11 = m.pos(g(b, h));
  for (std::uint32_t j = 1; j < h; ++j) {
    for (std::uint32_t i = 1; i < b; ++i) {
      // Intersection of the blended parameter lines (the usual two-step approximation).
      const double u = (u0[i] * (1.0 - v0[j]) + u1[i] * v0[j]);
      const double v = (v0[j] * (1.0 - u) + v1[j] * u);
      const Vec2 p = (1.0 - v) * m.pos(g(i, 0)) + v * m.pos(g(i, h)) + (1.0 - u) * m.pos(g(0, j)) +
                     u * m.pos(g(b, j)) -
                     ((1.0 - u) * (1.0 - v) * c00 + u * (1.0 - v) * c10 + (1.0 - u) * v * c01 +
                      u * v * c11);
      g(i, j) = m.add(p);
    }
  }
  for (std::uint32_t j = 0; j < h; ++j)
    for (std::uint32_t i = 0; i < b; ++i) m.quad(g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
  FaceMesh r = m.finish();
  if (!r.interior.empty() && r.min_jacobian < kAcceptJacobian) relax(r, face, 20);
  return r;
}

/// Diamond: a strip with one-edge boundary pieces whose rails differ by two edges, the longer
/// one bending at an MA point. Rows of quads from both boundary pieces meet at that MA point,
/// where one quad spans the axis (the paper's two triangles merged across the MA).
std::optional<FaceMesh> fill_diamond(const FaceInput& face) {
  const auto sides = strip_sides(face);
  if (!sides) return std::nullopt;
  for (int flip = 0; flip < 2; ++flip) {
    // Rotate so that the long rail is r1: the order is b1, r1, b2, r2 either way.
    const FaceSide& b1 = *(*sides)[flip ? 2 : 0];
    const FaceSide& r1 = *(*sides)[flip ? 3 : 1];
    const FaceSide& b2 = *(*sides)[flip ? 0 : 2];
    const FaceSide& r2 = *(*sides)[flip ? 1 : 3];
    if (b1.edges != 1 || b2.edges != 1 || r1.edges != r2.edges + 2) continue;
    Builder m(face, FillKind::Diamond);
    const std::uint32_t n1 = r1.edges, n2 = r2.edges;
    for (std::uint32_t joint : r1.joints) {
      if (joint < 1 || joint + 1 > n1) continue;
      auto a = [&](std::uint32_t k) { return m.at(r1.first, k); };       // long rail, up
      auto l = [&](std::uint32_t k) { return m.at(r2.first, n2 - k); };  // short rail, up
      const std::uint32_t jj = joint;
      for (std::uint32_t k = 0; k + 1 < jj; ++k) m.quad(l(k), a(k), a(k + 1), l(k + 1));
      m.quad(l(jj - 1), a(jj - 1), a(jj), a(jj + 1));
      for (std::uint32_t k = 0; jj + 1 + k < n1; ++k)
        m.quad(l(jj - 1 + k), a(jj + 1 + k), a(jj + 2 + k), l(jj + k));
      return m.finish();
    }
  }
  return std::nullopt;
}

/// Four nodes: the face itself is the quad.
FaceMesh fill_quad(const FaceInput& face) {
  Builder m(face, FillKind::Quad);
  m.quad(0, 1, 2, 3);
  return m.finish();
}

/// Four nodes, one corner flat or reflex: an inner quad and four quads around it, so that
/// every corner of the face gets an edge into it.
FaceMesh fill_ring(const FaceInput& face) {
  Builder m(face, FillKind::Ring);
  Vec2 c{0.0, 0.0};
  for (const Vec2& p : face.cycle) c = c + 0.25 * p;
  std::uint32_t inner[4];
  for (std::uint32_t i = 0; i < 4; ++i) inner[i] = m.add(lerp(c, face.cycle[i], 0.5));
  for (std::uint32_t i = 0; i < 4; ++i) m.quad(i, (i + 1) % 4, inner[(i + 1) % 4], inner[i]);
  m.quad(inner[0], inner[1], inner[2], inner[3]);
  FaceMesh r = m.finish();
  relax(r, face, 10);
  return r;
}

/// Twice the smallest angle's sine-like measure of triangle abc: min over corners of
/// cross / (|e1| |e2|), negative when the triangle turns clockwise.
double triangle_shape(Vec2 a, Vec2 b, Vec2 c) {
  const Vec2 p[3] = {a, b, c};
  double worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const Vec2 e1 = p[(i + 1) % 3] - p[i];
    const Vec2 e0 = p[(i + 2) % 3] - p[i];
    const double l = norm(e1) * norm(e0);
    worst = std::min(worst, l > 0.0 ? cross(e1, e0) / l : -1.0);
  }
  return worst;
}

bool strictly_inside(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  return cross(b - a, p - a) > 0.0 && cross(c - b, p - b) > 0.0 && cross(a - c, p - c) > 0.0;
}

/// Ear clipping of a simple counter-clockwise polygon, best-shaped ear first. Indices into
/// `poly`. Empty when it finds no ear (a polygon that is not simple).
std::vector<std::array<std::uint32_t, 3>> triangulate(const std::vector<Vec2>& poly) {
  std::vector<std::uint32_t> left(poly.size());
  for (std::uint32_t i = 0; i < left.size(); ++i) left[i] = i;
  std::vector<std::array<std::uint32_t, 3>> tris;
  while (left.size() > 3) {
    const std::size_t m = left.size();
    double best = 0.0;
    std::size_t pick = m;
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
      const double shape = triangle_shape(poly[a], poly[b], poly[c]);
      if (shape <= best) continue;
      bool empty = true;
      for (std::size_t k = 0; k < m && empty; ++k) {
        const std::uint32_t q = left[k];
        if (q == a || q == b || q == c) continue;
        if (strictly_inside(poly[q], poly[a], poly[b], poly[c])) empty = false;
        // A vertex on the diagonal ac blocks it too.
        const Vec2 d = poly[c] - poly[a];
        const double along = dot(poly[q] - poly[a], d);
        if (empty && std::abs(cross(d, poly[q] - poly[a])) <= 1e-12 * dot(d, d) && along > 0.0 &&
            along < dot(d, d))
          empty = false;
      }
      if (!empty) continue;
      best = shape;
      pick = i;
    }
    if (pick == m) return {};
    tris.push_back({left[(pick + m - 1) % m], left[pick], left[(pick + 1) % m]});
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(pick));
  }
  if (triangle_shape(poly[left[0]], poly[left[1]], poly[left[2]]) <= 0.0) return {};
  tris.push_back({left[0], left[1], left[2]});
  return tris;
}

/// Split: the even (or odd) cycle nodes form a coarse polygon whose edges each have one face
/// node in their middle; the coarse polygon is triangulated and every triangle split into three
/// quads through its centre and its edge midpoints. Every face node then has an edge into the
/// face, so flat nodes on rails never become 180-degree corners.
std::optional<FaceMesh> fill_split(const FaceInput& face, std::uint32_t offset) {
  const std::uint32_t n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 6 || n % 2 != 0) return std::nullopt;
  std::vector<Vec2> coarse;
  for (std::uint32_t k = 0; k < n / 2; ++k) coarse.push_back(face.cycle[(offset + 2 * k) % n]);
  const auto tris = triangulate(coarse);
  if (tris.empty()) return std::nullopt;
  Builder m(face, FillKind::Split);
  const std::uint32_t half = n / 2;
  auto node = [&](std::uint32_t k) { return (offset + 2 * k) % n; };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mids;
  auto mid = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t {
    if ((i + 1) % half == j) return (offset + 2 * i + 1) % n;  // a coarse boundary edge
    if ((j + 1) % half == i) return (offset + 2 * j + 1) % n;
    const auto key = std::minmax(i, j);
    const auto it = mids.find(key);
    if (it != mids.end()) return it->second;
    const std::uint32_t id = m.add(lerp(coarse[i], coarse[j], 0.5));
    mids.emplace(key, id);
    return id;
  };
  for (const auto& t : tris) {
    const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    const Vec2 g = (1.0 / 6.0) * (coarse[t[0]] + coarse[t[1]] + coarse[t[2]] + m.pos(ab) +
                                  m.pos(bc) + m.pos(ca));
    const std::uint32_t c = m.add(g);
    m.quad(node(t[0]), ab, c, ca);
    m.quad(node(t[1]), bc, c, ab);
    m.quad(node(t[2]), ca, c, bc);
  }
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

}  // namespace

FaceMesh fill_face(const FaceInput& face, const std::string& where) {
  const std::size_t n = face.cycle.size();
  if (n < 4 || n % 2 != 0) {
    throw InternalError("mesher: " + where + " has " + std::to_string(n) +
                        " boundary nodes; a face needs an even number, at least 4");
  }
  std::optional<FaceMesh> best;
  auto consider = [&](std::optional<FaceMesh> m) {
    if (m && (!best || m->min_jacobian > best->min_jacobian)) best = std::move(m);
    return best && best->min_jacobian >= kAcceptJacobian;
  };
  if (consider(fill_grid(face))) return *best;
  if (consider(fill_diamond(face))) return *best;
  if (n == 4) {
    if (consider(fill_quad(face))) return *best;
    consider(fill_ring(face));
  } else {
    if (consider(fill_split(face, 0))) return *best;
    consider(fill_split(face, 1));
  }
  if (best && best->min_jacobian > 0.0) return *best;
  std::ostringstream s;
  s << "mesher: no template gives valid quads in " << where << " (" << n
    << " boundary nodes, " << face.sides.size() << " sides";
  if (best) s << ", best corner scaled Jacobian " << best->min_jacobian;
  s << ")";
  if (std::getenv("LAYTRACKS_DEBUG_FACE")) {
    s << "\nsides:";
    for (const FaceSide& side : face.sides)
      s << " " << (side.kind == FaceSide::Kind::Rail ? "R" : "B") << side.edges << "@" << side.first;
    s << "\ncycle:";
    for (const Vec2& p : face.cycle) s << " (" << p.x << "," << p.y << ")";
  }
  throw InternalError(s.str());
}

void smooth_nodes(std::vector<Vec2>& pos,
                  const std::vector<bool>& fixed,
                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                  int iterations) {
  const std::size_t n = pos.size();
  std::vector<std::vector<std::uint32_t>> nbr(n), around(n);
  for (std::uint32_t q = 0; q < quads.size(); ++q) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t a = quads[q][k], b = quads[q][(k + 1) % 4];
      nbr[a].push_back(b);
      nbr[b].push_back(a);
      around[a].push_back(q);
    }
  }
  for (auto& v : nbr) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  auto jac = [&](std::uint32_t q) {
    const auto& x = quads[q];
    return min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]);
  };
  for (int it = 0; it < iterations; ++it) {
    bool moved = false;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (fixed[v] || nbr[v].empty()) continue;
      Vec2 avg{0.0, 0.0};
      for (std::uint32_t w : nbr[v]) avg = avg + pos[w];
      avg = (1.0 / static_cast<double>(nbr[v].size())) * avg;
      double before = std::numeric_limits<double>::infinity();
      for (std::uint32_t q : around[v]) before = std::min(before, jac(q));
      const Vec2 old = pos[v];
      pos[v] = avg;
      double after = std::numeric_limits<double>::infinity();
      for (std::uint32_t q : around[v]) after = std::min(after, jac(q));
      // Accept when the worst quad around v does not get worse (or stays above the floor).
      if (after >= std::min(before, kSmoothFloor) && (after >= before || after >= kSmoothFloor)) {
        moved = moved || old != avg;
      } else {
        pos[v] = old;
      }
    }
    if (!moved) break;
  }
}

}  // namespace laytracks::mesher_detail
