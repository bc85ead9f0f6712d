#include "fill.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>

#include "cdt.hpp"
#include "laytracks/brep/error.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/quality.hpp"
#include "match.hpp"
#include "memo.hpp"
#include "regrid.hpp"

namespace laytracks::mesher_detail {

static_assert(static_cast<std::size_t>(FillKind::Kites) + 1 == kTemplateNames.size(),
              "a name for every face template");

const char* to_string(FillKind kind) { return kTemplateNames[static_cast<std::size_t>(kind)]; }

LocalFrame::LocalFrame(const std::vector<Vec2>& pos, const std::vector<std::uint32_t>& ids)
    : origin_(pos[ids[0]]) {
  double length = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    length += norm(pos[ids[(i + 1) % ids.size()]] - pos[ids[i]]);
  scale_ = length / static_cast<double>(ids.size());
  const Vec2 d = pos[ids[1]] - origin_;
  const double l = norm(d);
  ux_ = l > 0.0 ? Vec2{d.x / l, d.y / l} : Vec2{1.0, 0.0};
  if (!(scale_ > 0.0)) scale_ = 1.0;
}

LocalFrame::LocalFrame(const std::vector<Vec2>& cycle)
    : LocalFrame(cycle, [&] {
        std::vector<std::uint32_t> ids(cycle.size());
        for (std::uint32_t k = 0; k < ids.size(); ++k) ids[k] = k;
        return ids;
      }()) {}

Vec2 LocalFrame::to_local(Vec2 p) const {
  const Vec2 d = p - origin_;
  const Vec2 q{(d.x * ux_.x + d.y * ux_.y) / scale_, (d.y * ux_.x - d.x * ux_.y) / scale_};
  // + 0.0: -0 (a point a hair below an axis in one pose) is 0, as in every other pose
  // (atan2 and the order of ties tell -0 from 0).
  return {std::round(q.x / kLocalGrid) * kLocalGrid + 0.0,
          std::round(q.y / kLocalGrid) * kLocalGrid + 0.0};
}

Vec2 LocalFrame::to_patch(Vec2 q) const {
  return {origin_.x + scale_ * (q.x * ux_.x - q.y * ux_.y),
          origin_.y + scale_ * (q.x * ux_.y + q.y * ux_.x)};
}

double min_scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  // corner_jacobian at each corner, its edges' squared lengths computed once (an edge and its
  // reverse square alike, to the bit): the same values.
  const Vec2 e[4] = {b - a, c - b, d - c, a - d};  // e[i]: from corner i to corner i + 1
  const double l[4] = {dot(e[0], e[0]), dot(e[1], e[1]), dot(e[2], e[2]), dot(e[3], e[3])};
  double worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 3) % 4;  // the edge into corner i
    worst = std::min(worst, corner_of_edges(e[i], -1.0 * e[j], l[i] * l[j]));
  }
  return worst;
}

double shortest_norm(const std::vector<Vec2>& vs) {
  double least2 = std::numeric_limits<double>::infinity();
  for (const Vec2& e : vs) least2 = std::min(least2, dot(e, e));
  const bool plain = least2 > 1e-200 && least2 < 1e200;
  const double near2 = least2 * (1.0 + 1e-12);
  double least = std::numeric_limits<double>::infinity();
  for (const Vec2& e : vs)
    if (!plain || dot(e, e) <= near2) least = std::min(least, norm(e));
  return least;
}

namespace {

using Quad = std::array<std::uint32_t, 4>;
constexpr std::uint32_t kNoId = 0xffffffffu;

/// A quad with an edge shorter than this x the shortest edge of its face's boundary is scored
/// as if its scaled Jacobian were smaller in that ratio: the scaled Jacobian does not see
/// size, and the relaxation could shrink a well-shaped quad to a speck round a node where many
/// quads meet (cgal_wheel_16_spokes, adaptive: quads of 1e-5 beside quads of 0.3).
constexpr double kTinyEdge = 0.1;

/// The score of a template's quads: their smallest corner scaled Jacobian, each quad's lowered
/// in proportion when one of its edges is below kTinyEdge x the face's shortest boundary edge.
template <class Pos>
double face_score(const std::vector<Quad>& quads, Pos pos, const FaceInput& face) {
  double shortest = std::numeric_limits<double>::infinity();
  const std::size_t n = face.cycle.size();
  for (std::size_t k = 0; k < n; ++k)
    shortest = std::min(shortest, distance(face.cycle[k], face.cycle[(k + 1) % n]));
  const double tiny = kTinyEdge * shortest;
  double worst = std::numeric_limits<double>::infinity();
  for (const Quad& q : quads) {
    double sj = min_scaled_jacobian(pos(q[0]), pos(q[1]), pos(q[2]), pos(q[3]));
    double edge = std::numeric_limits<double>::infinity();
    // Squared lengths first: this runs for every quad of every template tried.
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec2 d = pos(q[(k + 1) % 4]) - pos(q[k]);
      edge = std::min(edge, dot(d, d));
    }
    if (edge < tiny * tiny && sj > 0.0) sj *= std::sqrt(edge) / tiny;
    worst = std::min(worst, sj);
  }
  return worst;
}

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
  /// A quad given as a cycle in either direction: stored counter-clockwise.
  void quad_ccw(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    const double twice = cross(pos(b) - pos(a), pos(c) - pos(a)) + cross(pos(c) - pos(a), pos(d) - pos(a));
    if (twice >= 0.0) quad(a, b, c, d);
    else quad(a, d, c, b);
  }
  /// Takes in the quads of a sub-face whose cycle node k is this face's node ids[k]: its
  /// interior nodes are added, its quads mapped.
  void embed(const FaceMesh& sub, const std::vector<std::uint32_t>& ids) {
    std::vector<std::uint32_t> map(ids);
    for (const Vec2& p : sub.interior) map.push_back(add(p));
    for (const auto& q : sub.quads) quad(map[q[0]], map[q[1]], map[q[2]], map[q[3]]);
  }
  FaceMesh finish() {
    out.min_jacobian = face_score(out.quads, [&](std::uint32_t i) { return pos(i); }, face);
    return std::move(out);
  }
};

/// relax() does nothing while fill_cavity runs: the cavity's caller relaxes the quads it
/// keeps with the quads round them (and the templates' own sweeps were most of its time).
thread_local bool relax_off = false;
/// The relaxation sweeps of each kind a repaired lattice's cavities get (refill_face), as the
/// re-fill's cavities get at most kRefillSweeps.
constexpr int kFaceRefillSweeps = 4;

/// Improves a template's interior nodes in place (boundary nodes fixed).
void relax(FaceMesh& m, const FaceInput& face, int iterations) {
  if (m.interior.empty() || relax_off) return;
  std::vector<Vec2> pos(face.cycle);
  pos.insert(pos.end(), m.interior.begin(), m.interior.end());
  std::vector<bool> fixed(pos.size(), false);
  std::fill(fixed.begin(), fixed.begin() + static_cast<std::ptrdiff_t>(face.cycle.size()), true);
  smooth_nodes(pos, fixed, m.quads, iterations);
  untangle_nodes(pos, fixed, m.quads, iterations);
  std::copy(pos.begin() + static_cast<std::ptrdiff_t>(face.cycle.size()), pos.end(),
            m.interior.begin());
  m.min_jacobian = face_score(m.quads, [&](std::uint32_t i) { return pos[i]; }, face);
}

/// A face seen as a strip: cap1 (boundary), rail1, cap2 (boundary, possibly a single node),
/// rail2, each a list of cycle indices in counter-clockwise order, consecutive lists sharing
/// their end nodes. Joints are indices into rail1 / rail2 of MA points inside them.
struct Strip {
  std::vector<std::uint32_t> cap1, rail1, cap2, rail2;
  std::vector<std::uint32_t> joints1, joints2;
  /// Edge counts: cap1, cap2, rail1, rail2.
  struct Edges {
    std::uint32_t a, c, n1, n2;
  };
  Edges edges() const {
    const auto e = [](const std::vector<std::uint32_t>& run) {
      return static_cast<std::uint32_t>(run.size() - 1);
    };
    return {e(cap1), e(cap2), e(rail1), e(rail2)};
  }
};

std::vector<std::uint32_t> run_of(const FaceInput& face, std::uint32_t first, std::uint32_t edges) {
  std::vector<std::uint32_t> r;
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  for (std::uint32_t k = 0; k <= edges; ++k) r.push_back((first + k) % n);
  return r;
}

/// The strips a face can be read as: four sides boundary, rail, boundary, rail (a boundary
/// side may have no edge: two rails meeting at a boundary node, a concave corner's fan); or a
/// boundary side and one rail chain through one MA point where both halves meet (a wedge:
/// rails of a rounded corner or a branch point), cap2 then being that point.
std::vector<Strip> strips_of(const FaceInput& face) {
  std::vector<Strip> out;
  const auto& sd = face.sides;
  using K = FaceSide::Kind;
  if (sd.size() == 4) {
    for (std::size_t s = 0; s < 2; ++s) {
      const FaceSide& a = sd[s];
      const FaceSide& b = sd[s + 1];
      const FaceSide& c = sd[(s + 2) % 4];
      const FaceSide& d = sd[(s + 3) % 4];
      if (a.kind != K::Boundary || b.kind != K::Rail || c.kind != K::Boundary || d.kind != K::Rail)
        continue;
      Strip st{run_of(face, a.first, a.edges), run_of(face, b.first, b.edges),
               run_of(face, c.first, c.edges), run_of(face, d.first, d.edges), b.joints, d.joints};
      out.push_back(st);
      // The same strip read from the other cap.
      Strip sw{st.cap2, st.rail2, st.cap1, st.rail1, d.joints, b.joints};
      out.push_back(sw);
    }
  } else if (sd.size() == 2) {
    for (std::size_t s = 0; s < 2; ++s) {
      const FaceSide& a = sd[s];
      const FaceSide& b = sd[1 - s];
      if (a.kind != K::Boundary || b.kind != K::Rail || b.joints.empty()) continue;
      // The apex: the joint that splits the rail chain most evenly.
      std::uint32_t apex = b.joints.front();
      for (std::uint32_t j : b.joints)
        if (std::abs(2.0 * j - b.edges) < std::abs(2.0 * apex - b.edges)) apex = j;
      Strip st;
      st.cap1 = run_of(face, a.first, a.edges);
      st.rail1 = run_of(face, b.first, apex);
      st.cap2 = {st.rail1.back()};
      st.rail2 = run_of(face, st.rail1.back(), b.edges - apex);
      for (std::uint32_t j : b.joints) {
        if (j < apex) st.joints1.push_back(j);
        if (j > apex) st.joints2.push_back(j - apex);
      }
      out.push_back(st);
    }
  }
  // Any other face with an apex (two rails meeting at a boundary node, a zero-edge side):
  // a wedge whose cap1 is all the rest of the face.
  if (sd.size() != 4 && sd.size() >= 3) {
    const auto n = static_cast<std::uint32_t>(face.cycle.size());
    for (std::size_t s = 0; s < sd.size(); ++s) {
      const FaceSide& apex = sd[s];
      const FaceSide& next = sd[(s + 1) % sd.size()];
      const FaceSide& prev = sd[(s + sd.size() - 1) % sd.size()];
      if (apex.kind != K::Boundary || apex.edges != 0 || next.kind != K::Rail ||
          prev.kind != K::Rail || next.edges + prev.edges >= n)
        continue;
      Strip st;
      st.rail1 = run_of(face, prev.first, prev.edges);  // ends at the apex
      st.cap2 = {apex.first};
      st.rail2 = run_of(face, next.first, next.edges);  // starts there
      st.cap1 = run_of(face, st.rail2.back(), n - next.edges - prev.edges);
      st.joints1 = prev.joints;
      st.joints2 = next.joints;
      out.push_back(st);
    }
  }
  return out;
}

/// Grid: caps of b edges each, rails of m edges each; transfinite interpolation between the
/// four sides, rows of quads from one cap to the other. With a one-node cap2 (a wedge) and an
/// even b, the last row folds into b / 2 quads round that node.
/// The arc-length fractions (0 to 1) of the nodes node_of(0 .. count) along their chain.
template <class NodeOf>
std::vector<double> arc_fractions(const Builder& m, NodeOf node_of, std::uint32_t count) {
  std::vector<double> t(count + 1, 0.0);
  for (std::uint32_t k = 1; k <= count; ++k)
    t[k] = t[k - 1] + distance(m.pos(node_of(k - 1)), m.pos(node_of(k)));
  for (double& x : t) x = t[count] > 0.0 ? x / t[count] : 0.0;
  return t;
}

/// A grid whose worst corner, before relaxing, is below this is folded over itself and is not
/// relaxed: over the 20 parts at 1x and 2x and the 217 generated parts, none of the 56 grid
/// relaxations that started below -0.7 came back to kAcceptJacobian (the best reached 0.09;
/// one from -0.48 did), and they took 2.3 s of the 2.4 s of all 496 (faces of 154 to 286
/// nodes round a ring of holes or a wavy outline: holes3__wavy60_hole40 1.6 s).
constexpr double kFoldedGrid = -0.7;

std::optional<FaceMesh> fill_grid(const FaceInput& face, const Strip& st) {
  const auto b = static_cast<std::uint32_t>(st.cap1.size() - 1);
  const auto h = static_cast<std::uint32_t>(st.rail1.size() - 1);
  const bool wedge = st.cap2.size() == 1;
  if (b == 0 || h != st.rail2.size() - 1) return std::nullopt;
  if (wedge ? (b % 2 != 0 || h < 2) : st.cap2.size() != st.cap1.size()) return std::nullopt;
  Builder m(face, FillKind::Grid);
  // Grid node (i, j), i along cap1 (0..b), j along rail1 (0..h).
  std::vector<std::uint32_t> id((b + 1) * (h + 1), kNoId);
  auto g = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t& { return id[j * (b + 1) + i]; };
  for (std::uint32_t i = 0; i <= b; ++i) {
    g(i, 0) = st.cap1[i];
    if (!wedge) g(i, h) = st.cap2[b - i];
  }
  for (std::uint32_t j = 0; j <= h; ++j) {
    g(b, j) = st.rail1[j];
    g(0, j) = st.rail2[h - j];
  }
  auto arc = [&](auto node_of, std::uint32_t count) { return arc_fractions(m, node_of, count); };
  const Vec2 apex = m.pos(st.cap2.front());
  auto top = [&](std::uint32_t i) { return wedge ? apex : m.pos(g(i, h)); };
  const auto u0 = arc([&](std::uint32_t i) { return g(i, 0); }, b);
  std::vector<double> u1 = u0;
  if (!wedge) u1 = arc([&](std::uint32_t i) { return g(i, h); }, b);
  const auto v0 = arc([&](std::uint32_t j) { return g(0, j); }, h);
  const auto v1 = arc([&](std::uint32_t j) { return g(b, j); }, h);
  const Vec2 c00 = m.pos(g(0, 0)), c10 = m.pos(g(b, 0)), c01 = top(0), c11 = top(b);
  for (std::uint32_t j = 1; j < h; ++j) {
    for (std::uint32_t i = 1; i < b; ++i) {
      const double u = u0[i] * (1.0 - v0[j]) + u1[i] * v0[j];
      const double v = v0[j] * (1.0 - u) + v1[j] * u;
      const Vec2 p = (1.0 - v) * m.pos(g(i, 0)) + v * top(i) + (1.0 - u) * m.pos(g(0, j)) +
                     u * m.pos(g(b, j)) -
                     ((1.0 - u) * (1.0 - v) * c00 + u * (1.0 - v) * c10 + (1.0 - u) * v * c01 +
                      u * v * c11);
      g(i, j) = m.add(p);
    }
  }
  const std::uint32_t rows = wedge ? h - 1 : h;
  for (std::uint32_t j = 0; j < rows; ++j)
    for (std::uint32_t i = 0; i < b; ++i) m.quad(g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
  if (wedge) {
    for (std::uint32_t i = 0; i < b; i += 2)
      m.quad(g(i, h - 1), g(i + 1, h - 1), g(i + 2, h - 1), st.cap2.front());
  }
  FaceMesh r = m.finish();
  if (!r.interior.empty() && r.min_jacobian < kAcceptJacobian && r.min_jacobian >= kFoldedGrid)
    relax(r, face, 30);
  return r;
}

/// Quads of a four-sided region given by its sides' node ids (counter-clockwise, consecutive
/// sides sharing their end nodes, opposite sides of equal counts): transfinite interpolation
/// between the sides, as fill_grid does.
void grid_into(Builder& m, const std::vector<std::uint32_t>& s0, const std::vector<std::uint32_t>& s1,
               const std::vector<std::uint32_t>& s2, const std::vector<std::uint32_t>& s3) {
  const auto b = static_cast<std::uint32_t>(s0.size() - 1);
  const auto h = static_cast<std::uint32_t>(s1.size() - 1);
  std::vector<std::uint32_t> id((b + 1) * (h + 1), kNoId);
  auto g = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t& { return id[j * (b + 1) + i]; };
  for (std::uint32_t i = 0; i <= b; ++i) {
    g(i, 0) = s0[i];
    g(i, h) = s2[b - i];
  }
  for (std::uint32_t j = 0; j <= h; ++j) {
    g(b, j) = s1[j];
    g(0, j) = s3[h - j];
  }
  auto arc = [&](auto node_of, std::uint32_t count) { return arc_fractions(m, node_of, count); };
  const auto u0 = arc([&](std::uint32_t i) { return g(i, 0); }, b);
  const auto u1 = arc([&](std::uint32_t i) { return g(i, h); }, b);
  const auto v0 = arc([&](std::uint32_t j) { return g(0, j); }, h);
  const auto v1 = arc([&](std::uint32_t j) { return g(b, j); }, h);
  const Vec2 c00 = m.pos(g(0, 0)), c10 = m.pos(g(b, 0)), c01 = m.pos(g(0, h)), c11 = m.pos(g(b, h));
  for (std::uint32_t j = 1; j < h; ++j) {
    for (std::uint32_t i = 1; i < b; ++i) {
      const double u = u0[i] * (1.0 - v0[j]) + u1[i] * v0[j];
      const double v = v0[j] * (1.0 - u) + v1[j] * u;
      const Vec2 p = (1.0 - v) * m.pos(g(i, 0)) + v * m.pos(g(i, h)) + (1.0 - u) * m.pos(g(0, j)) +
                     u * m.pos(g(b, j)) -
                     ((1.0 - u) * (1.0 - v) * c00 + u * (1.0 - v) * c10 + (1.0 - u) * v * c01 +
                      u * v * c11);
      g(i, j) = m.add(p);
    }
  }
  for (std::uint32_t j = 0; j < h; ++j)
    for (std::uint32_t i = 0; i < b; ++i) m.quad(g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
}

/// Three grids: a four-sided face whose two longer sides meet at one corner, each longer by
/// the same d edges than the side opposite it (a grid needs equal opposite sides). One inner
/// node X of valence three joins the corner opposite the longer sides' (d edges), a node of
/// each longer side (so many edges as the shorter side beside it), and the three regions
/// between are grids. The one irregular node is the whole price of the mismatch.
constexpr double kThreeFloor = 0.5;
/// Strips narrower than this (in edges) keep the strip templates: three grids in a corridor
/// one edge wide are slivers (the tray's one- and two-edge corridors at the floor's corners
/// went to aspect 5-8).
constexpr std::uint32_t kThreeShortest = 2;

std::optional<FaceMesh> fill_three(const FaceInput& face, const Strip& st) {
  if (st.cap2.size() < 2 || st.cap1.size() < 2) return std::nullopt;
  const std::array<const std::vector<std::uint32_t>*, 4> side{&st.cap1, &st.rail1, &st.cap2, &st.rail2};
  auto edges = [&](std::size_t k) { return static_cast<std::uint32_t>(side[k % 4]->size() - 1); };
  for (std::size_t rot = 0; rot < 4; ++rot) {
    const std::uint32_t es = edges(rot), ee = edges(rot + 1), en = edges(rot + 2), ew = edges(rot + 3);
    if (es <= en || ee <= ew || es - en != ee - ew || std::min(en, ew) < kThreeShortest) continue;
    const std::uint32_t d = es - en;
    const std::vector<std::uint32_t>& S = *side[rot];
    const std::vector<std::uint32_t>& E = *side[(rot + 1) % 4];
    const std::vector<std::uint32_t>& N = *side[(rot + 2) % 4];
    const std::vector<std::uint32_t>& W = *side[(rot + 3) % 4];
    Builder m(face, FillKind::Three);
    const std::uint32_t p0 = S.front(), p2 = E.back(), p3 = N.back();
    const std::uint32_t m1 = S[d], m2 = E[ew];
    const Vec2 x = m.pos(p3) + 0.5 * ((m.pos(m1) - m.pos(p0)) + (m.pos(m2) - m.pos(p2)));
    const std::uint32_t xi = m.add(x);
    // A chain of `count` edges from node a to node b, its inner nodes on the segment.
    auto chain = [&](std::uint32_t a, std::uint32_t b, std::uint32_t count) {
      std::vector<std::uint32_t> c{a};
      for (std::uint32_t k = 1; k < count; ++k)
        c.push_back(m.add(lerp(m.pos(a), m.pos(b), static_cast<double>(k) / count)));
      c.push_back(b);
      return c;
    };
    const std::vector<std::uint32_t> to_p3 = chain(xi, p3, d), to_m1 = chain(xi, m1, ew),
                                     to_m2 = chain(xi, m2, en);
    auto reversed = [](std::vector<std::uint32_t> v) {
      std::reverse(v.begin(), v.end());
      return v;
    };
    auto run = [](const std::vector<std::uint32_t>& v, std::uint32_t from, std::uint32_t to) {
      return std::vector<std::uint32_t>(v.begin() + from, v.begin() + to + 1);
    };
    grid_into(m, run(S, 0, d), reversed(to_m1), to_p3, W);
    grid_into(m, run(S, d, es), run(E, 0, ew), reversed(to_m2), to_m1);
    grid_into(m, to_m2, run(E, ew, ee), N, reversed(to_p3));
    FaceMesh r = m.finish();
    relax(r, face, 30);
    // A worse corner means the face is not this shape: the later templates get their turn.
    if (r.min_jacobian < kThreeFloor) return std::nullopt;
    return r;
  }
  return std::nullopt;
}

/// Diamond: caps of one edge, rails differing by 2d edges, the longer bending at an MA point.
/// Rows from both caps end on one node of the short rail (the apex); between it and the bend,
/// d - 1 nodes on the segment apex-bend carry 2(d - 1) quads, and one quad spans the axis at
/// the bend (the paper's two triangles merged across the MA).
std::optional<FaceMesh> fill_diamond(const FaceInput& face, const Strip& st) {
  if (st.cap1.size() != 2 || st.cap2.size() != 2) return std::nullopt;
  const auto n1 = static_cast<std::uint32_t>(st.rail1.size() - 1);
  const auto n2 = static_cast<std::uint32_t>(st.rail2.size() - 1);
  if (n1 <= n2 || (n1 - n2) % 2 != 0) return std::nullopt;
  const std::uint32_t d = (n1 - n2) / 2;
  std::optional<FaceMesh> best;
  for (std::uint32_t jj : st.joints1) {
    if (jj < d || n1 - jj < d) continue;
    Builder m(face, FillKind::Diamond);
    auto R = [&](std::uint32_t k) { return st.rail1[k]; };
    auto L = [&](std::uint32_t k) { return st.rail2[n2 - k]; };  // the short rail, upwards
    const std::uint32_t k1 = jj - d;
    const std::uint32_t k2 = n1 - jj - d;
    for (std::uint32_t k = 0; k < k1; ++k) m.quad(L(k), R(k), R(k + 1), L(k + 1));
    for (std::uint32_t k = 0; k < k2; ++k)
      m.quad(L(n2 - k - 1), R(n1 - k - 1), R(n1 - k), L(n2 - k));
    std::vector<std::uint32_t> y{L(k1)};
    for (std::uint32_t k = 1; k < d; ++k)
      y.push_back(m.add(lerp(m.pos(L(k1)), m.pos(R(jj)), static_cast<double>(k) / d)));
    for (std::uint32_t k = 0; k + 1 < d; ++k) {
      m.quad_ccw(y[k], R(k1 + k), R(k1 + k + 1), y[k + 1]);
      m.quad_ccw(y[k], R(n1 - k2 - k), R(n1 - k2 - k - 1), y[k + 1]);
    }
    m.quad_ccw(y[d - 1], R(jj - 1), R(jj), R(jj + 1));
    FaceMesh r = m.finish();
    if (!r.interior.empty() && r.min_jacobian < kAcceptJacobian) relax(r, face, 30);
    if (!best || r.min_jacobian > best->min_jacobian) best = std::move(r);
  }
  return best;
}

/// Rows and a remainder: from a one-edge cap, K rows of quads join node k of one rail to node k
/// of the other; what is left near the other cap (unequal rails, a fan's corner) is a small
/// polygon meshed by the other templates. Tries the K that gives the best quads.
std::optional<FaceMesh> fill_rows(const FaceInput& face, const Strip& st, int depth);

/// Four nodes: the face itself is the quad.
FaceMesh fill_quad(const FaceInput& face) {
  Builder m(face, FillKind::Quad);
  m.quad(0, 1, 2, 3);
  return m.finish();
}

/// Four nodes, one corner flat or reflex: an inner quad and four quads around it, so that
/// every corner of the face gets an edge into it.
/// Quad abcd (counter-clockwise) as a ring: an inner quad halfway to the centre, four around.
void ring_into(Builder& m, const std::array<std::uint32_t, 4>& v) {
  Vec2 c{0.0, 0.0};
  for (std::uint32_t id : v) c = c + 0.25 * m.pos(id);
  std::array<std::uint32_t, 4> inner{};
  for (std::size_t i = 0; i < 4; ++i) inner[i] = m.add(lerp(c, m.pos(v[i]), 0.5));
  for (std::size_t i = 0; i < 4; ++i) m.quad(v[i], v[(i + 1) % 4], inner[(i + 1) % 4], inner[i]);
  m.quad(inner[0], inner[1], inner[2], inner[3]);
}

FaceMesh fill_ring(const FaceInput& face) {
  Builder m(face, FillKind::Ring);
  ring_into(m, {0, 1, 2, 3});
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
    worst = std::min(worst, corner_of_edges(e1, e0, dot(e1, e1) * dot(e0, e0)));
  }
  return worst;
}


/// Three points whose angle at the first (the sine between the two directions) is below this
/// are collinear, and a triangle whose triangle_shape is not above it is flat: far above
/// rounding (nodes laid on one straight rail or boundary side are collinear but for their last
/// bits, which differ between poses of a part), far below any shape a template could use.
constexpr double kCollinearSine = 1e-9;

/// Which side of the line ab the point c lies on: 1 left, -1 right, 0 on it (within
/// kCollinearSine).
int side_of(Vec2 a, Vec2 b, Vec2 c) {
  const Vec2 u = b - a, v = c - a;
  const double d = cross(u, v);
  // |d| against kCollinearSine |u| |v|, squared: this runs O(m^3) times in triangulate.
  if (d * d <= kCollinearSine * kCollinearSine * dot(u, u) * dot(v, v)) return 0;
  return d > 0.0 ? 1 : -1;
}

/// True when the open segments pq and rt cross or touch (a shared end point does not count).
/// Collinear segments meet only when they overlap: exactly collinear nodes (a diagonal along
/// a straight rail, in a pose where its nodes' coordinates are exact) must not be told apart
/// from nearly collinear ones by the signs of rounding errors (a face of a generated bracket
/// lost its best diagonal in one pose, and its pairs template went from 49 quads to 112).
/// segments_meet given the four sides it reads: d1, d2 = side_of(p, q, r), side_of(p, q, t);
/// d3, d4 = side_of(r, t, p), side_of(r, t, q) (triangulate has them from its tables).
bool segments_meet(Vec2 p, Vec2 q, Vec2 r, Vec2 t, int d1, int d2, int d3, int d4) {
  if (p == r || p == t || q == r || q == t) return false;
  if ((d1 == 0 && d2 == 0) || (d3 == 0 && d4 == 0)) {
    // Collinear: the parameters of the shorter segment's ends along the longer one overlap
    // [0, 1] (touching counts).
    const bool pq_longer = dot(q - p, q - p) >= dot(t - r, t - r);
    const Vec2 o = pq_longer ? p : r, d = pq_longer ? q - p : t - r;
    const Vec2 a = pq_longer ? r : p, b = pq_longer ? t : q;
    const double l2 = dot(d, d);
    const double sa = dot(a - o, d) / l2, sb = dot(b - o, d) / l2;
    return std::max(sa, sb) >= -kCollinearSine && std::min(sa, sb) <= 1.0 + kCollinearSine;
  }
  return d1 * d2 <= 0 && d3 * d4 <= 0;
}

}  // namespace

bool segments_meet(Vec2 p, Vec2 q, Vec2 r, Vec2 t) {
  if (p == r || p == t || q == r || q == t) return false;
  return segments_meet(p, q, r, t, side_of(p, q, r), side_of(p, q, t), side_of(r, t, p),
                       side_of(r, t, q));
}

bool inside_polygon(Vec2 x, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y > x.y) != (poly[j].y > x.y) &&
        x.x < poly[j].x + (x.y - poly[j].y) * (poly[i].x - poly[j].x) / (poly[i].y - poly[j].y))
      in = !in;
  }
  return in;
}

namespace {

/// The triangulation of a simple counter-clockwise polygon that maximises the smallest
/// `score(a, b, c)` of its triangles (dynamic programming over diagonals, O(m^3)). Indices
/// into `poly`; empty when the polygon has no triangulation with positive triangles.
/// A split must beat the best so far by more than this to replace it: scores equal but for
/// rounding (mirror-image triangles, a worst triangle shared by both) keep the first split in
/// every pose of a part.
constexpr double kTriangulationTie = 1e-9;
template <class Score>
std::vector<std::array<std::uint32_t, 3>> triangulate(const std::vector<Vec2>& poly, Score score) {
  const auto m = static_cast<std::uint32_t>(poly.size());
  if (m < 3) return {};
  const double kNone = -std::numeric_limits<double>::infinity();
  // ok(i, j): i < j, the segment is a polygon edge or a diagonal inside the polygon.
  std::vector<char> ok(m * m, 0);
  // The sides every test below reads, each computed once: edge_side[k * m + v] is
  // side_of(poly[k], poly[k + 1], poly[v]); `at` the sides of the nodes from a diagonal, as
  // far as its test has gone.
  std::vector<signed char> edge_side(m * m);
  for (std::uint32_t k = 0; k < m; ++k)
    for (std::uint32_t v = 0; v < m; ++v)
      edge_side[k * m + v] = static_cast<signed char>(side_of(poly[k], poly[(k + 1) % m], poly[v]));
  std::vector<signed char> at(m);
  for (std::uint32_t i = 0; i < m; ++i) {
    for (std::uint32_t j = i + 1; j < m; ++j) {
      if (j == i + 1 || (i == 0 && j == m - 1)) {
        ok[i * m + j] = 1;
        continue;
      }
      bool good = inside_polygon(lerp(poly[i], poly[j], 0.5), poly);
      if (good) at[0] = static_cast<signed char>(side_of(poly[i], poly[j], poly[0]));
      for (std::uint32_t k = 0; k < m && good; ++k) {
        const std::uint32_t l = k + 1 == m ? 0 : k + 1;
        if (l != 0) at[l] = static_cast<signed char>(side_of(poly[i], poly[j], poly[l]));
        const int ei = edge_side[k * m + i], ej = edge_side[k * m + j];
        // Both ends of edge kl strictly on one side of the diagonal, and the diagonal not along
        // the edge's line: segments_meet is false without its tests.
        const bool apart = at[k] * at[l] > 0 && !(ei == 0 && ej == 0);
        if (!apart && segments_meet(poly[i], poly[j], poly[k], poly[l], at[k], at[l], ei, ej))
          good = false;
        // A vertex lying on the diagonal blocks it.
        if (at[k] == 0 && k != i && k != j) {
          const Vec2 d = poly[j] - poly[i];
          const double along = dot(poly[k] - poly[i], d);
          if (along > 0.0 && along < dot(d, d)) good = false;
        }
      }
      ok[i * m + j] = good ? 1 : 0;
    }
  }
  std::vector<double> best(m * m, kNone);
  std::vector<std::uint32_t> split(m * m, 0);
  for (std::uint32_t i = 0; i + 1 < m; ++i) best[i * m + i + 1] = std::numeric_limits<double>::infinity();
  for (std::uint32_t len = 2; len < m; ++len) {
    for (std::uint32_t i = 0; i + len < m; ++i) {
      const std::uint32_t j = i + len;
      if (!ok[i * m + j]) continue;
      for (std::uint32_t k = i + 1; k < j; ++k) {
        const double left = best[i * m + k], right = best[k * m + j];
        if (left == kNone || right == kNone) continue;
        // v below is at most min(left, right): when that cannot beat the best so far, the
        // triangle's shape and score need not be computed (the same choices, in less time).
        if (std::min(left, right) <= best[i * m + j] + kTriangulationTie) continue;
        if (triangle_shape(poly[i], poly[k], poly[j]) <= kCollinearSine) continue;  // flat
        const double v = std::min({left, right, score(i, k, j)});
        if (v > best[i * m + j] + kTriangulationTie) {
          best[i * m + j] = v;
          split[i * m + j] = k;
        }
      }
    }
  }
  if (best[m - 1] == kNone) return {};
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0u, m - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j == i + 1) continue;
    const std::uint32_t k = split[i * m + j];
    tris.push_back({i, k, j});
    todo.push_back({i, k});
    todo.push_back({k, j});
  }
  return tris;
}

/// Two coarse triangles sharing a diagonal become one coarse quad when its four quads (through
/// its edge midpoints and centre) are at least as good as the six kites of the two triangles
/// (better by kMergeMargin), best merged quad first, each triangle merged at most once. A
/// triangle split into three has taper 0.5 at best; a coarse quad split into four keeps the
/// coarse quad's shape (the subdivision Gmsh applies after Blossom). Merged triangles are
/// marked in `tris` with kNoId; the coarse quads come back counter-clockwise.
constexpr double kMergeMargin = 1e-6;

template <class MidAt, class Score>
std::vector<std::array<std::uint32_t, 4>> merge_coarse_pairs(
    std::vector<std::array<std::uint32_t, 3>>& tris, const std::vector<Vec2>& coarse, MidAt mid_at,
    Score score) {
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  std::map<Edge, std::vector<std::size_t>> by_edge;
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      by_edge[std::minmax(tris[t][k], tris[t][(k + 1) % 3])].push_back(t);
  struct Candidate {
    double worst;  // the coarse quad's four quads' worst corner, in kMergeMargin steps
    std::size_t t1, t2;
    std::array<std::uint32_t, 4> quad;
  };
  std::vector<Candidate> candidates;
  for (const auto& [edge, ts] : by_edge) {
    if (ts.size() != 2) continue;
    // The quad: t1's corners from the one off the diagonal, then t2's far corner between the
    // diagonal's ends (both triangles run counter-clockwise).
    const auto& a = tris[ts[0]];
    const auto& b = tris[ts[1]];
    std::size_t ka = 0, kb = 0;
    while (a[ka] == edge.first || a[ka] == edge.second) ++ka;
    while (b[kb] == edge.first || b[kb] == edge.second) ++kb;
    const std::array<std::uint32_t, 4> q{a[ka], a[(ka + 1) % 3], b[kb], a[(ka + 2) % 3]};
    Vec2 g{0.0, 0.0};
    std::array<Vec2, 4> e;
    for (std::size_t k = 0; k < 4; ++k) {
      e[k] = mid_at(q[k], q[(k + 1) % 4]);
      g = g + 0.125 * (coarse[q[k]] + e[k]);
    }
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < 4; ++k)
      worst = std::min(worst, min_scaled_jacobian(coarse[q[k]], e[k], g, e[(k + 3) % 4]));
    const double kites = std::min(score(a[0], a[1], a[2]), score(b[0], b[1], b[2]));
    if (worst > kites + kMergeMargin)
      candidates.push_back({std::round(worst / kMergeMargin), ts[0], ts[1], q});
  }
  // Best first; equal ones (symmetric faces) in the order of the diagonals, so every pose of
  // a part merges the same pairs.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.worst > y.worst; });
  std::vector<std::array<std::uint32_t, 4>> out;
  std::vector<bool> used(tris.size(), false);
  for (const Candidate& c : candidates) {
    if (used[c.t1] || used[c.t2]) continue;
    used[c.t1] = used[c.t2] = true;
    out.push_back(c.quad);
  }
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (used[t]) tris[t] = {kNoId, kNoId, kNoId};
  return out;
}

/// Split's coarse mesh: the coarse polygon (face nodes offset, offset + 2, ...), then any
/// coarse nodes inside it (the lattice template's).
struct CoarseMesh {
  const FaceInput& face;
  std::uint32_t offset, half;
  std::vector<Vec2> coarse;
  CoarseMesh(const FaceInput& f, std::uint32_t off)
      : face(f), offset(off), half(static_cast<std::uint32_t>(f.cycle.size() / 2)) {
    for (std::uint32_t k = 0; k < half; ++k) coarse.push_back(face.cycle[(offset + 2 * k) % face.cycle.size()]);
  }
  /// Where the middle node of coarse edge ij is: the face node between them on the boundary,
  /// else the midpoint of the diagonal.
  Vec2 mid_at(std::uint32_t i, std::uint32_t j) const {
    const std::size_t n = face.cycle.size();
    if (i < half && j < half) {
      if ((i + 1) % half == j) return face.cycle[(offset + 2 * i + 1) % n];
      if ((j + 1) % half == i) return face.cycle[(offset + 2 * j + 1) % n];
    }
    return lerp(coarse[i], coarse[j], 0.5);
  }
  /// An ear scores the worst of the three quads it will be split into.
  double score(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const Vec2 ab = mid_at(a, b), bc = mid_at(b, c), ca = mid_at(c, a);
    const Vec2 g = (1.0 / 6.0) * (coarse[a] + coarse[b] + coarse[c] + ab + bc + ca);
    return std::min({min_scaled_jacobian(coarse[a], ab, g, ca),
                     min_scaled_jacobian(coarse[b], bc, g, ab),
                     min_scaled_jacobian(coarse[c], ca, g, bc)});
  }
};

/// The quads of a split coarse mesh: each coarse quad of `merged` into four through its edge
/// midpoints and centre, each triangle of `tris` left unmerged into three through its edge
/// midpoints and centre. Coarse node k is face node id[k]; those below `half` are the
/// coarse polygon (face nodes offset, offset + 2, ...), whose edges' middle nodes are the face
/// nodes between them; any other coarse edge gets a new node at its middle.
void split_into(Builder& m, const std::vector<std::uint32_t>& id, std::uint32_t half, std::uint32_t offset,
                const std::vector<std::array<std::uint32_t, 3>>& tris,
                const std::vector<std::array<std::uint32_t, 4>>& merged) {
  const std::uint32_t n = m.n();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mids;
  auto mid = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t {
    if (i < half && j < half) {
      if ((i + 1) % half == j) return (offset + 2 * i + 1) % n;  // a coarse boundary edge
      if ((j + 1) % half == i) return (offset + 2 * j + 1) % n;
    }
    const auto key = std::minmax(i, j);
    const auto it = mids.find(key);
    if (it != mids.end()) return it->second;
    const std::uint32_t made = m.add(lerp(m.pos(id[i]), m.pos(id[j]), 0.5));
    mids.emplace(key, made);
    return made;
  };
  for (const auto& c : merged) {
    // A coarse quad: four quads through its edge midpoints and its centre.
    std::array<std::uint32_t, 4> e{};
    Vec2 g{0.0, 0.0};
    for (std::size_t k = 0; k < 4; ++k) {
      e[k] = mid(c[k], c[(k + 1) % 4]);
      g = g + 0.125 * (m.pos(id[c[k]]) + m.pos(e[k]));
    }
    const std::uint32_t centre = m.add(g);
    for (std::size_t k = 0; k < 4; ++k) m.quad(id[c[k]], e[k], centre, e[(k + 3) % 4]);
  }
  for (const auto& t : tris) {
    if (t[0] == kNoId) continue;  // merged into a coarse quad
    const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    const Vec2 g = (1.0 / 6.0) * (m.pos(id[t[0]]) + m.pos(id[t[1]]) + m.pos(id[t[2]]) + m.pos(ab) +
                                  m.pos(bc) + m.pos(ca));
    const std::uint32_t c = m.add(g);
    m.quad(id[t[0]], ab, c, ca);
    m.quad(id[t[1]], bc, c, ab);
    m.quad(id[t[2]], ca, c, bc);
  }
}

/// Split: the even (or odd) cycle nodes form a coarse polygon whose edges each have one face
/// node in their middle; the coarse polygon is triangulated and every triangle split into three
/// quads through its centre and its edge midpoints. Every face node then has an edge into the
/// face, so flat nodes on rails never become 180-degree corners.
std::optional<FaceMesh> fill_split(const FaceInput& face, std::uint32_t offset) {
  const std::uint32_t n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 6 || n % 2 != 0) return std::nullopt;
  const CoarseMesh cm(face, offset);
  const std::vector<Vec2>& coarse = cm.coarse;
  const std::uint32_t half = cm.half;
  auto mid_at = [&](std::uint32_t i, std::uint32_t j) { return cm.mid_at(i, j); };
  auto score = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { return cm.score(a, b, c); };
  auto tris = triangulate(coarse, score);
  if (tris.empty()) return std::nullopt;
  const std::vector<std::array<std::uint32_t, 4>> merged = merge_coarse_pairs(tris, coarse, mid_at, score);
  Builder m(face, FillKind::Split);
  std::vector<std::uint32_t> id(half);
  for (std::uint32_t k = 0; k < half; ++k) id[k] = (offset + 2 * k) % n;
  split_into(m, id, half, offset, tris, merged);
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

/// Lawson flips for the split's score: a diagonal shared by two coarse triangles is swapped
/// for the quadrilateral's other one when that is convex and raises the worse of the two
/// triangles' scores (the worst corner of the quads each is split into) by more than
/// kFlipMargin. The Delaunay triangulation knows nothing of the face nodes between coarse
/// nodes: where the boundary bends at one, the triangle on that coarse edge needs its third
/// corner elsewhere. Up to kLatticeFlipPasses passes over the diagonals, in the order of
/// their end nodes (the same in every pose), each triangle changed at most once a pass.
constexpr double kFlipMargin = 1e-6;
constexpr int kLatticeFlipPasses = 8;

template <class Score>
void improve_by_flips(std::vector<std::array<std::uint32_t, 3>>& tris, const std::vector<Vec2>& coarse,
                      Score score) {
  for (int pass = 0; pass < kLatticeFlipPasses; ++pass) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> by_edge;
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) by_edge[std::minmax(tris[t][k], tris[t][(k + 1) % 3])].push_back(t);
    std::vector<bool> touched(tris.size(), false);
    bool flipped = false;
    for (const auto& [edge, ts] : by_edge) {
      if (ts.size() != 2 || touched[ts[0]] || touched[ts[1]]) continue;
      // t1 runs i -> j -> k, t2 j -> i -> l: the quadrilateral is i, l, j, k.
      std::array<std::uint32_t, 3> t1 = tris[ts[0]], t2 = tris[ts[1]];
      while (!(t1[0] == edge.first || t1[0] == edge.second) || !(t1[1] == edge.first || t1[1] == edge.second))
        std::rotate(t1.begin(), t1.begin() + 1, t1.end());
      const std::uint32_t i = t1[0], j = t1[1], k = t1[2];
      std::uint32_t l = t2[0];
      for (std::uint32_t x : t2)
        if (x != i && x != j) l = x;
      const Vec2 I = coarse[i], J = coarse[j], Kp = coarse[k], L = coarse[l];
      // Convex: the new diagonal k-l crosses i-j, by more than kCollinearSine at both ends (a
      // flat corner there, three nodes of one straight rail, was convex in one pose of a part
      // and not in another, and the flip made a sliver triangle of them in one pose only).
      if (!(side_of(L, J, Kp) > 0 && side_of(Kp, I, L) > 0)) continue;
      const double now = std::min(score(i, j, k), score(j, i, l));
      const double then = std::min(score(l, j, k), score(k, i, l));
      if (then > now + kFlipMargin) {
        tris[ts[0]] = {l, j, k};
        tris[ts[1]] = {k, i, l};
        touched[ts[0]] = touched[ts[1]] = true;
        flipped = true;
      }
    }
    if (!flipped) break;
  }
}

/// Lattice split (`fill_lattice`): split with points inside. The split template's coarse
/// triangles span the whole face, so in a face many elements wide its quads are as long as
/// the face. Here the coarse polygon (every other face node, offset by `offset`) gets inner
/// coarse nodes on a square lattice of the coarse polygon's mean edge, turned to the face's
/// dominant edge direction (the angle whose fourfold multiple is the length-weighted mean of
/// the edges' fourfold angles, so a face with straight sides lines up with them), centred on
/// the polygon's box; a lattice point is kept when it is inside the polygon and at least
/// kLatticeClear lattice steps from its edges. The constrained Delaunay triangulation of the
/// polygon and those points (CGAL, cdt.cpp) gives coarse triangles about the lattice step
/// wide; pairs become coarse quads as in split (a lattice square's two halves make a square),
/// and each coarse quad is split into four quads, each triangle left into three. It all runs
/// in the face's LocalFrame, so every pose of a part builds the same lattice and the same
/// triangulation, ties of four points on a circle included. Faces with no lattice point
/// inside are split's.
constexpr double kLatticeClear = 0.75;
/// At most this many lattice cells in the polygon's box (a face some 400 x 400 elements).
constexpr double kLatticeMaxPoints = 40000.0;

std::optional<FaceMesh> fill_lattice(const FaceInput& face, std::uint32_t offset) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 8 || n % 2 != 0) return std::nullopt;
  const std::uint32_t half = n / 2;
  const LocalFrame frame(face.cycle);
  std::vector<Vec2> local;  // coarse nodes in the frame: the polygon, then the lattice points
  for (std::uint32_t k = 0; k < half; ++k) local.push_back(frame.to_local(face.cycle[(offset + 2 * k) % n]));
  double length = 0.0, c4 = 0.0, s4 = 0.0;
  for (std::uint32_t k = 0; k < half; ++k) {
    const Vec2 d = local[(k + 1) % half] - local[k];
    const double l = norm(d), a = 4.0 * std::atan2(d.y, d.x);
    length += l;
    c4 += l * std::cos(a);
    s4 += l * std::sin(a);
  }
  const double step = length / half;
  if (!(step > 0.0)) return std::nullopt;
  const double turn = std::atan2(s4, c4) / 4.0;
  const Vec2 u{std::cos(turn), std::sin(turn)}, v{-std::sin(turn), std::cos(turn)};
  double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
  for (std::uint32_t k = 0; k < half; ++k) {
    u0 = std::min(u0, dot(local[k], u));
    u1 = std::max(u1, dot(local[k], u));
    v0 = std::min(v0, dot(local[k], v));
    v1 = std::max(v1, dot(local[k], v));
  }
  const auto cells_u = static_cast<std::int64_t>(std::floor((u1 - u0) / step));
  const auto cells_v = static_cast<std::int64_t>(std::floor((v1 - v0) / step));
  if (cells_u < 2 || cells_v < 2) return std::nullopt;
  // A box of more cells is left to the other templates: the distance test below is points x
  // edges.
  if (static_cast<double>(cells_u) * static_cast<double>(cells_v) > kLatticeMaxPoints) return std::nullopt;
  const double su = u0 + 0.5 * ((u1 - u0) - static_cast<double>(cells_u) * step);
  const double sv = v0 + 0.5 * ((v1 - v0) - static_cast<double>(cells_v) * step);
  const double clear2 = (kLatticeClear * step) * (kLatticeClear * step);
  const std::vector<Vec2> polygon(local.begin(), local.end());
  for (std::int64_t j = 1; j < cells_v; ++j) {
    for (std::int64_t i = 1; i < cells_u; ++i) {
      const double a = su + static_cast<double>(i) * step, b = sv + static_cast<double>(j) * step;
      const Vec2 p{a * u.x + b * v.x, a * u.y + b * v.y};
      if (!inside_polygon(p, polygon)) continue;
      bool clear = true;
      for (std::uint32_t k = 0; k < half && clear; ++k) {
        const Vec2 e0 = polygon[k], d = polygon[(k + 1) % half] - e0;
        const double dd = dot(d, d);
        const double t = dd > 0.0 ? std::clamp(dot(p - e0, d) / dd, 0.0, 1.0) : 0.0;
        const Vec2 q = p - (e0 + t * d);
        clear = dot(q, q) >= clear2;
      }
      if (clear) local.push_back(p);
    }
  }
  if (local.size() == half) return std::nullopt;
  auto tris = constrained_triangulation(local, half);
  if (tris.empty()) return std::nullopt;
  CoarseMesh cm(face, offset);  // in the patch frame; the polygon's nodes exactly the face's
  for (std::size_t k = half; k < local.size(); ++k) cm.coarse.push_back(frame.to_patch(local[k]));
  const std::vector<Vec2>& coarse = cm.coarse;
  auto mid_at = [&](std::uint32_t i, std::uint32_t j) { return cm.mid_at(i, j); };
  auto score = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { return cm.score(a, b, c); };
  improve_by_flips(tris, coarse, score);
  const std::vector<std::array<std::uint32_t, 4>> merged = merge_coarse_pairs(tris, coarse, mid_at, score);
  Builder m(face, FillKind::Lattice);
  std::vector<std::uint32_t> id(coarse.size());
  for (std::uint32_t k = 0; k < half; ++k) id[k] = (offset + 2 * k) % n;
  for (std::size_t k = half; k < coarse.size(); ++k) id[k] = m.add(coarse[k]);
  split_into(m, id, half, offset, tris, merged);
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

/// Fan split: like split, but the coarse polygon is triangulated as a fan round one interior
/// point (the mean of the face's nodes, then moved by the untangler), so that every coarse
/// node, flat or reflex, gets two quads. For star-shaped faces that split cannot do (an L
/// whose flat nodes would all need a diagonal).
std::optional<FaceMesh> fill_fan_split(const FaceInput& face, std::uint32_t offset) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 6 || n % 2 != 0) return std::nullopt;
  const std::uint32_t half = n / 2;
  Builder m(face, FillKind::Split);
  Vec2 c{0.0, 0.0};
  for (const Vec2& p : face.cycle) c = c + (1.0 / n) * p;
  const std::uint32_t centre = m.add(c);
  std::vector<std::uint32_t> spoke(half);  // midpoint of centre - coarse node k
  for (std::uint32_t k = 0; k < half; ++k)
    spoke[k] = m.add(lerp(c, face.cycle[(offset + 2 * k) % n], 0.5));
  for (std::uint32_t k = 0; k < half; ++k) {
    const std::uint32_t a = (offset + 2 * k) % n, mid = (a + 1) % n, b = (a + 2) % n;
    const std::uint32_t kb = (k + 1) % half;
    const Vec2 g = (1.0 / 6.0) * (c + face.cycle[a] + face.cycle[b] + face.cycle[mid] +
                                  m.pos(spoke[k]) + m.pos(spoke[kb]));
    const std::uint32_t t = m.add(g);
    m.quad(a, mid, t, spoke[k]);
    m.quad(b, spoke[kb], t, mid);
    m.quad(centre, spoke[k], t, spoke[kb]);
  }
  FaceMesh r = m.finish();
  relax(r, face, 60);
  return r;
}

}  // namespace

double interior_angle(const std::vector<Vec2>& poly, std::size_t i) {
  const std::size_t n = poly.size();
  const Vec2 out = poly[(i + 1) % n] - poly[i], back = poly[(i + n - 1) % n] - poly[i];
  double a = std::atan2(cross(out, back), dot(out, back));
  if (a <= 0.0) a += 2.0 * kPi;
  return a;
}

bool is_round(const std::vector<Vec2>& poly) {
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const double a = interior_angle(poly, k);
    if (a < kRoundMin || a > kRoundMax) return false;
  }
  return true;
}

double ccw_angle(Vec2 from, Vec2 to) {
  double a = std::atan2(cross(from, to), dot(from, to));
  if (a < 0.0) a += 2.0 * kPi;
  return a;
}

/// A corner turns by more than 30.5 degrees. Off round values (150 degrees until session
/// 34): a regular 12-gon's corners, an arc's 30-degree chords, are 150 degrees exactly, below
/// or above it by the pose's rounding, and a fuzzed rounded rectangle far smaller than its
/// element (fuzz seed 34034, extreme_006) read a reflex cut's piece as four sides when turned
/// and as none as given: 136 quads against 213.
constexpr double kCornerAngle = 149.5 * kPi / 180.0;
/// A polygon with a node more reflex than this has no corner reading. Off round values for
/// the same reason (200 degrees until session 46): the chords of an arc turning by 20 degrees
/// meet at 200 degrees exactly, above or below it by the pose's rounding, and a cut piece of
/// fuzz seed 93093's arcs_021 (a bulged outline) was a grid of 0.86 as given and none turned:
/// 340 quads against 347.
constexpr double kCornerReflexMax = 200.5 * kPi / 180.0;

/// The corners of a polygon (interior angle below kCornerAngle), in order; none when a node
/// is reflex beyond kCornerReflexMax. How corner_strip and fill_sided read a face.
std::optional<std::vector<std::uint32_t>> polygon_corners(const std::vector<Vec2>& poly) {
  std::vector<std::uint32_t> corners;
  for (std::uint32_t k = 0; k < poly.size(); ++k) {
    const double a = interior_angle(poly, k);
    if (a > kCornerReflexMax) return std::nullopt;
    if (a < kCornerAngle) corners.push_back(k);
  }
  return corners;
}

namespace {

/// A polygon read by its corners: when exactly four nodes are corners (polygon_corners), its
/// four sides as a strip (cap1 from the first corner, then rail1, cap2, rail2), `rotate`
/// sides later.
std::optional<Strip> corner_strip(const std::vector<Vec2>& poly, std::size_t rotate) {
  const auto n = static_cast<std::uint32_t>(poly.size());
  const std::optional<std::vector<std::uint32_t>> found = polygon_corners(poly);
  if (!found || found->size() != 4) return std::nullopt;
  const std::vector<std::uint32_t>& corners = *found;
  std::array<std::vector<std::uint32_t>, 4> side;
  for (std::size_t c = 0; c < 4; ++c) {
    const std::uint32_t from = corners[(c + rotate) % 4], to = corners[(c + rotate + 1) % 4];
    for (std::uint32_t k = from;; k = (k + 1) % n) {
      side[c].push_back(k);
      if (k == to) break;
    }
  }
  Strip st;
  st.cap1 = side[0];
  st.rail1 = side[1];
  st.cap2 = side[2];
  st.rail2 = side[3];
  return st;
}

/// The grids of a face read by its corners (corner_strip), in both readings that apply.
std::vector<FaceMesh> corner_grids(const FaceInput& face) {
  std::vector<FaceMesh> out;
  for (std::size_t rotate = 0; rotate < 2; ++rotate) {
    const std::optional<Strip> st = corner_strip(face.cycle, rotate);
    if (!st) break;
    if (std::optional<FaceMesh> g = fill_grid(face, *st)) out.push_back(std::move(*g));
  }
  return out;
}

/// One chord of the cut template: from node i to node j of the polygon through `inner` new
/// nodes, and its score (higher is better).
struct Chord {
  std::uint32_t i = 0, j = 0;
  std::vector<Vec2> inner;
  double score = -std::numeric_limits<double>::infinity();
};

/// Worst corner of a four-node polygon as an angle in degrees (asin of the scaled Jacobian);
/// -inf when a corner is flat or turns the wrong way.
double quad_angle_score(const std::vector<Vec2>& q) {
  const double j = min_scaled_jacobian(q[0], q[1], q[2], q[3]);
  if (j <= kMinValidJacobian) return -std::numeric_limits<double>::infinity();
  return std::asin(std::min(j, 1.0)) * (180.0 / kPi);
}

/// The best chord of a polygon (counter-clockwise, even node count >= 6) for the cut template;
/// score -inf when none fits. Rules (docs/mesher.md, "Cut"): a chord joins two nodes that are
/// not neighbours, inside the polygon; it gets the inner nodes that make both halves' node
/// counts even and smaller than the polygon's, spaced as close to `h` (the polygon's mean edge)
/// as parity allows. Its nodes lie on the straight segment. With `kites` (fill_cut), also a
/// chord with one inner node that cuts one corner off as a quad (its other half as large as
/// the polygon): that node is pushed off the segment, away from the corner, so the quad has no
/// flat corner. Score: the smallest angle it makes at its ends
/// (capped at 90 degrees), or of a quad it cuts off (asin of its scaled Jacobian); lowered by
/// 30 per unit of |ln(spacing / h)| and when it passes closer than 0.6 spacing to another node.
std::vector<Chord> best_chords(const std::vector<Vec2>& poly, std::size_t keep, bool kites) {
  const auto n = static_cast<std::uint32_t>(poly.size());
  double h = 0.0;
  for (std::uint32_t k = 0; k < n; ++k) h += distance(poly[k], poly[(k + 1) % n]);
  h /= n;
  std::vector<double> angle(n);
  for (std::uint32_t k = 0; k < n; ++k) angle[k] = interior_angle(poly, k);
  constexpr double kDeg = 180.0 / kPi;
  auto crosses_boundary = [&](Vec2 p, Vec2 q, std::uint32_t i, std::uint32_t j) {
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t k1 = (k + 1) % n;
      if (k == i || k == j || k1 == i || k1 == j) continue;
      if (mesher_detail::segments_meet(p, q, poly[k], poly[k1])) return true;
    }
    return false;
  };
  std::vector<Chord> best;  // the `keep` best so far, best first
  auto bar = [&] {
    return best.size() < keep ? -std::numeric_limits<double>::infinity() : best.back().score;
  };
  std::vector<Vec2> half_a, half_b, inner, offsets;
  // No chord scores above its cap less its spacing's penalty: the angles' part is at most 90
  // and at most half the interior angle at either end (min(a, angle - a) <= angle / 2, which
  // is exact), and the rounded operations are monotone. A count whose bound is not above the
  // bar needs no angles, crossings or clearance.
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t gap = 2; gap + 2 <= n; ++gap) {
      const std::uint32_t j = (i + gap) % n;
      if (j < i) continue;  // each chord once
      const double cap = std::min({0.5 * angle[i], 0.5 * angle[j], 0.5 * kPi}) * kDeg;
      // No penalty is negative: a cap at or below the bar bounds every count (settled is
      // monotone and the bar a settled value), and most chords end here.
      if (cap <= bar()) continue;
      const Vec2 d = poly[j] - poly[i];
      const double len = norm(d);
      if (len <= 0.0) continue;
      const auto ideal = static_cast<std::int64_t>(std::floor(len / h + 0.5)) - 1;
      for (std::int64_t count = std::max<std::int64_t>(0, ideal - 1); count <= ideal + 1; ++count) {
        const auto in = static_cast<std::uint32_t>(count);
        if ((gap + in + 1) % 2 != 0) continue;
        const bool kite = in == 1 && (gap == 2 || n - gap == 2);
        // A kite leaves a polygon of as many nodes (one node traded for a new one): only when
        // `kites` (the needle-tip attempt's last resort), bounded by cut_down's budget.
        if ((gap + 1 + in >= n || n - gap + 1 + in >= n) && !(kites && kite)) continue;
        const double spacing = len / static_cast<double>(in + 1);
        const double penalty = 30.0 * std::abs(std::log(spacing / h));
        if (settled(cap - penalty) <= bar()) continue;
        // The inner nodes (made below, once the chord's angles pass): node k at k / (in + 1).
        const auto inner_node = [&](std::uint32_t k) {
          return lerp(poly[i], poly[j], static_cast<double>(k) / (in + 1));
        };
        Vec2 kite_node{};
        if (kite) {  // push the node away from the corner it cuts off
          const Vec2 corner = poly[gap == 2 ? (i + 1) % n : (j + 1) % n];
          kite_node = inner_node(1) + 0.5 * (inner_node(1) - corner);
          // The kites' last resort: in a needle far thinner than the chord is long, half the
          // way out leaves the polygon; the first of smaller pushes that stays inside.
          if (kites)
            for (const double push : {0.5, 0.2, 0.05, 0.01}) {
              kite_node = inner_node(1) + push * (inner_node(1) - corner);
              if (inside_polygon(kite_node, poly)) break;
            }
        }
        const Vec2 first = kite ? kite_node : in ? inner_node(1) : poly[j];
        const Vec2 last = kite ? kite_node : in ? inner_node(in) : poly[i];
        const double ai = ccw_angle(poly[(i + 1) % n] - poly[i], first - poly[i]);
        const double aj = ccw_angle(poly[(j + 1) % n] - poly[j], last - poly[j]);
        // A chord along a side (collinear nodes: an angle of 0 or 2 pi but for rounding) is none.
        if (ai <= kCollinearSine || ai >= angle[i] - kCollinearSine || aj <= kCollinearSine ||
            aj >= angle[j] - kCollinearSine)
          continue;
        double score = std::min({ai, angle[i] - ai, aj, angle[j] - aj, 0.5 * kPi}) * kDeg;
        if (settled(score) <= bar()) continue;
        score -= penalty;
        if (settled(score) <= bar()) continue;
        inner.clear();
        if (kite) inner.push_back(kite_node);
        else
          for (std::uint32_t k = 1; k <= in; ++k) inner.push_back(inner_node(k));
        if (kite ? crosses_boundary(poly[i], inner[0], i, j) ||
                       crosses_boundary(inner[0], poly[j], i, j) || !inside_polygon(inner[0], poly)
                 : crosses_boundary(poly[i], poly[j], i, j))
          continue;
        if (!kite) {  // a kite's score does not read its clearance
          offsets.clear();
          for (std::uint32_t k = 0; k < n; ++k) {
            if (k == i || k == j) continue;
            const double t = std::clamp(dot(poly[k] - poly[i], d) / (len * len), 0.0, 1.0);
            offsets.push_back(poly[k] - (poly[i] + t * d));
          }
          const double clearance = shortest_norm(offsets);
          score = std::min(score, 90.0 * clearance / (0.6 * spacing));
        }
        // Halves that are quads already (gap + 1 + in and n - gap + 1 + in nodes): their worst
        // corner counts.
        if (gap + 1 + in == 4) {
          half_a.clear();
          for (std::uint32_t k = i; k != j; k = (k + 1) % n) half_a.push_back(poly[k]);
          half_a.push_back(poly[j]);
          half_a.insert(half_a.end(), inner.rbegin(), inner.rend());
          score = std::min(score, quad_angle_score(half_a));
        }
        if (n - gap + 1 + in == 4) {
          half_b.clear();
          for (std::uint32_t k = j; k != i; k = (k + 1) % n) half_b.push_back(poly[k]);
          half_b.push_back(poly[i]);
          half_b.insert(half_b.end(), inner.begin(), inner.end());
          score = std::min(score, quad_angle_score(half_b));
        }
        if (score == -std::numeric_limits<double>::infinity()) continue;
        // Settled: two chords of a symmetric polygon score alike but for rounding, and the
        // first of them in enumeration order wins in every pose.
        score = settled(score);
        if (score <= bar()) continue;
        if (best.size() == keep) best.pop_back();
        const auto at = std::find_if(best.begin(), best.end(),
                                     [&](const Chord& c) { return c.score < score; });
        best.insert(at, Chord{i, j, inner, score});
      }
    }
  }
  return best;
}

/// Splits the polygon `ids` (node ids of m, counter-clockwise) by chords, again and again,
/// down to quads: the best chord first, the next ones when a half cannot be split (depth-first,
/// at most kCutChoices per polygon and `budget` polygons in all). False when it finds no way.
constexpr std::size_t kCutChoices = 4;

/// best_chords of the pieces one fill_cut meets, by their nodes' positions (the bytes): the
/// search backtracks and meets many a piece again (40% of the searches on
/// cgal_wiggly_03_cgal), and best_chords reads nothing but the positions.
using ChordCache = std::unordered_map<std::string, std::vector<Chord>>;

bool cut_down(
    Builder& m, const std::vector<std::uint32_t>& ids, int& budget, ChordCache& cache, bool kites) {
  const auto n = static_cast<std::uint32_t>(ids.size());
  if (n == 4) {
    m.quad(ids[0], ids[1], ids[2], ids[3]);
    return true;
  }
  if (n < 6 || --budget < 0) return false;
  std::vector<Vec2> poly;
  for (std::uint32_t id : ids) poly.push_back(m.pos(id));
  // A piece with four corners and matching sides is a structured grid: done.
  FaceInput piece;
  piece.cycle = poly;
  for (const FaceMesh& g : corner_grids(piece)) {
    if (g.min_jacobian < kAcceptJacobian) continue;
    m.embed(g, ids);
    return true;
  }
  std::string key(reinterpret_cast<const char*>(poly.data()), poly.size() * sizeof(Vec2));
  auto found = cache.find(key);
  if (found == cache.end())
    found = cache.emplace(std::move(key), best_chords(poly, kCutChoices, kites)).first;
  // A reference to the element stays valid while the recursion below adds others.
  const std::vector<Chord>& chords = found->second;
  for (const Chord& c : chords) {
    const std::size_t interior = m.out.interior.size(), quads = m.out.quads.size();
    std::vector<std::uint32_t> chord;  // from i to j, ends excluded
    for (const Vec2& p : c.inner) chord.push_back(m.add(p));
    std::vector<std::uint32_t> a, b;
    for (std::uint32_t k = c.i; k != c.j; k = (k + 1) % n) a.push_back(ids[k]);
    a.push_back(ids[c.j]);
    a.insert(a.end(), chord.rbegin(), chord.rend());
    for (std::uint32_t k = c.j; k != c.i; k = (k + 1) % n) b.push_back(ids[k]);
    b.push_back(ids[c.i]);
    b.insert(b.end(), chord.begin(), chord.end());
    if (cut_down(m, a, budget, cache, kites) && cut_down(m, b, budget, cache, kites)) return true;
    m.out.interior.resize(interior);
    m.out.quads.resize(quads);
    if (budget < 0) return false;
  }
  return false;
}

/// Two paired triangles whose quad has a corner below this with an inner node at it or at one
/// of its two edges' ends become rings of five (quads_from_marks); above it the relaxation
/// mends the corner, as the node moves (with kSmoothFloor there, as between face nodes, the
/// match template's toothed test face got 0.21 and 810 quads against 0.41 and 693).
constexpr double kInnerRingBelow = 0.01;

/// Quads from a triangulation of a face (nodes: the builder's) and a set of its inner edges
/// that gives every triangle one or three (`is_marked`): a triangle with three becomes three
/// quads round its centre (and its edges' midpoints); two triangles sharing their one mark become
/// one quad, or, when their union has a flat or reflex corner, each a ring of five round its
/// corners and the edge's midpoint; a triangle with one mark whose neighbour has three becomes
/// such a ring.
template <class Marked>
void quads_from_marks(Builder& m,
                      const std::vector<std::array<std::uint32_t, 3>>& tris,
                      Marked is_marked) {
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  std::map<Edge, std::vector<std::size_t>> sharing;  // marked diagonal -> its two triangles
  std::vector<int> degree(tris.size(), 0);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto [i, k, j] = tris[t];
    for (const Edge& e : {Edge{i, k}, Edge{k, j}, Edge{i, j}}) {
      if (is_marked(e.first, e.second)) {
        sharing[{std::min(e.first, e.second), std::max(e.first, e.second)}].push_back(t);
        ++degree[t];
      }
    }
  }
  std::map<Edge, std::uint32_t> mids;
  auto mid = [&](std::uint32_t a, std::uint32_t b) {
    const Edge e{std::min(a, b), std::max(a, b)};
    const auto it = mids.find(e);
    if (it != mids.end()) return it->second;
    const std::uint32_t id = m.add(lerp(m.pos(a), m.pos(b), 0.5));
    mids.emplace(e, id);
    return id;
  };
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto [i, k, j] = tris[t];
    if (degree[t] == 3) {
      const std::uint32_t ik = mid(i, k), kj = mid(k, j), ij = mid(i, j);
      const Vec2 g =
          (1.0 / 6.0) * (m.pos(i) + m.pos(k) + m.pos(j) + m.pos(ik) + m.pos(kj) + m.pos(ij));
      const std::uint32_t c = m.add(g);
      m.quad(i, ik, c, ij);
      m.quad(k, kj, c, ik);
      m.quad(j, ij, c, kj);
      continue;
    }
    // One marked edge x -> y, counter-clockwise in the triangle i k j; z the third corner.
    const std::array<std::uint32_t, 3> v{i, k, j};
    std::size_t s = 0;
    while (!is_marked(v[s], v[(s + 1) % 3])) ++s;
    const std::uint32_t x = v[s], y = v[(s + 1) % 3], z = v[(s + 2) % 3];
    const auto& pair = sharing[{std::min(x, y), std::max(x, y)}];
    const std::size_t other = pair[0] == t ? pair[1] : pair[0];
    if (degree[other] == 1) {
      if (other < t) continue;  // emitted with the other one
      std::uint32_t w = 0;
      for (std::uint32_t u : tris[other])
        if (u != x && u != y) w = u;
      // A flat or reflex corner between face nodes only (a node on a straight side, or a
      // reflex node) cannot be relaxed away, nor one about to fold: each triangle a ring of
      // five round its corners and the shared midpoint. A poor corner that an inner node
      // bounds (the match template's) is left to the relaxation.
      const std::array<std::uint32_t, 4> q{y, z, x, w};
      bool ring = false;
      for (std::size_t c = 0; c < 4; ++c) {
        const double corner =
            corner_jacobian(m.pos(q[c]), m.pos(q[(c + 1) % 4]), m.pos(q[(c + 3) % 4]));
        const bool fixed = q[c] < m.n() && q[(c + 1) % 4] < m.n() && q[(c + 3) % 4] < m.n();
        ring = ring || corner < (fixed ? kSmoothFloor : kInnerRingBelow);
      }
      if (ring) {
        const std::uint32_t c = mid(x, y);
        ring_into(m, {y, z, x, c});
        ring_into(m, {x, w, y, c});
      } else {
        m.quad(y, z, x, w);
      }
    } else {
      ring_into(m, {y, z, x, mid(x, y)});
    }
  }
}

/// Triangle pairs: the face triangulated (all its nodes, the worst triangle as good as it can
/// be), then each triangle given an odd number of its diagonals' midpoints (the one set of
/// diagonals that makes every triangle's degree in the dual tree odd; it exists because the
/// tree has n - 2 nodes, an even number). A triangle with three midpoints becomes three quads
/// round its centre; two triangles that share their one marked diagonal become one quad (the
/// midpoint dropped; when that quad would have a flat or reflex corner, each triangle becomes a
/// ring of five round its corners and the midpoint); a triangle with
/// one midpoint whose neighbour has three becomes a ring of five round its four nodes (the
/// midpoint a flat corner, which the ring's two quads there split). It needs nothing of the
/// face but a triangulation: the template of last resort. The quads: quads_from_marks.
std::optional<FaceMesh> fill_pairs(const FaceInput& face) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 4 || n % 2 != 0) return std::nullopt;
  const auto& poly = face.cycle;
  const auto tris = triangulate(poly, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return triangle_shape(poly[a], poly[b], poly[c]);
  });
  if (tris.empty()) return std::nullopt;
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  auto diagonal = [&](std::uint32_t a, std::uint32_t b) {
    return b - a > 1 && !(a == 0 && b == n - 1);
  };
  // Children come after their parent in `tris`; each non-root triangle's parent edge is (i, j).
  std::map<Edge, bool> marked;
  for (auto t = tris.rbegin(); t != tris.rend(); ++t) {
    const auto [i, k, j] = *t;
    int odd = 0;
    if (diagonal(i, k)) odd += marked[{i, k}] ? 1 : 0;
    if (diagonal(k, j)) odd += marked[{k, j}] ? 1 : 0;
    if (diagonal(i, j)) {
      marked[{i, j}] = odd % 2 == 0;
    } else if (odd % 2 == 0) {
      return std::nullopt;  // cannot happen: the root's parity follows from n being even
    }
  }
  auto is_marked = [&](std::uint32_t a, std::uint32_t b) {
    const Edge e{std::min(a, b), std::max(a, b)};
    return diagonal(e.first, e.second) && marked[e];
  };
  Builder m(face, FillKind::Pairs);
  quads_from_marks(m, tris, is_marked);
  FaceMesh r = m.finish();
  relax(r, face, 60);
  return r;
}

/// The match template (fill_match) competes with the other unstructured ones (match_ok) only
/// with at most kMatchMoreQuads times the quads of the pick so far, and in a face of fewer than
/// kMatchMinNodes nodes only with a worst corner of kMatchSmallFloor or more: in small faces
/// the quads the later stages make of the other templates' are often better than the match's
/// (cgal_Detmier 0.706 -> 0.396 with the acceptable 0.3, rounded_plate's fillets 0.765 ->
/// 0.675 without a floor; docs/mesher.md, "Matched triangles").
constexpr double kMatchMoreQuads = 1.25;
constexpr std::size_t kMatchMinNodes = 24;
constexpr double kMatchSmallFloor = 0.5;

/// Match: the face triangulated with inner points graded from its edges, the triangles paired
/// into quads (matched_triangles, quads_from_marks), in the face's LocalFrame so that every
/// pose pairs alike.
std::optional<FaceMesh> fill_match(const FaceInput& face) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 4 || n % 2 != 0) return std::nullopt;
  const LocalFrame frame(face.cycle);
  std::vector<Vec2> local(n);
  for (std::uint32_t k = 0; k < n; ++k) local[k] = frame.to_local(face.cycle[k]);
  const std::optional<MarkedTriangles> mt = matched_triangles(local);
  if (!mt) return std::nullopt;
  Builder m(face, FillKind::Match);
  for (const Vec2& p : mt->inner) m.add(frame.to_patch(p));
  const auto is_marked = [&](std::uint32_t a, std::uint32_t b) {
    return std::binary_search(mt->marks.begin(), mt->marks.end(),
                              std::make_pair(std::min(a, b), std::max(a, b)));
  };
  quads_from_marks(m, mt->triangles, is_marked);
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

/// Faces of more nodes than this get no cut template: its chord search is O(n^3) per
/// piece and it may search 4n pieces before it gives up, O(n^4) in all. Over 227,000 faces
/// (the 20 parts at 1x, 2x and 3x finer, the 217 generated parts and 107 random outlines;
/// the 20 and the 217 also in adaptive mode) cut won no face above 130 nodes; the 49 faces of
/// 140-754 nodes went to split or pairs. With this limit cgal_wiggly_03_cgal at 3x finer
/// (faces of up to 426 nodes) takes 1.50 s instead of 1.70 s, for the same mesh. 96 since
/// session 15 (the lattice template takes large faces): the 20 parts at 3x finer 6.39 ->
/// 5.90 s in all; of the 20 parts at 1x-3x and adaptive and the 217 generated parts at two
/// sizes and adaptive, 3 meshes changed, none in its worst corner or by 0.1 point of taper.
constexpr std::size_t kMaxCutNodes = 96;

/// Cut: recursive decomposition by chords (best_chord) down to quads, then the interior nodes
/// relaxed. The template of last resort: it needs nothing of the face but a simple polygon.
/// With `kites` (FillKind::Kites, fill_face's very last resort in the needle-tip attempt) a
/// chord may also cut one corner off as a quad through one new node, leaving a polygon of as
/// many nodes: a needle whose one side is one edge and whose other side has nodes in a line
/// (flat corners) has no quads on its own nodes, nor pieces smaller than itself.
std::optional<FaceMesh> fill_cut(const FaceInput& face, bool kites = false) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 6 || n % 2 != 0 || n > kMaxCutNodes) return std::nullopt;
  Builder m(face, kites ? FillKind::Kites : FillKind::Cut);
  std::vector<std::uint32_t> ids(n);
  for (std::uint32_t k = 0; k < n; ++k) ids[k] = k;
  int budget = 4 * static_cast<int>(n);
  ChordCache cache;
  if (!cut_down(m, ids, budget, cache, kites)) return std::nullopt;
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

std::optional<FaceMesh> fill_any(const FaceInput& face, int depth);

std::optional<FaceMesh> fill_rows(const FaceInput& face, const Strip& st, int depth) {
  if (st.cap1.size() != 2 || depth > 1) return std::nullopt;
  const auto n1 = static_cast<std::uint32_t>(st.rail1.size() - 1);
  const auto n2 = static_cast<std::uint32_t>(st.rail2.size() - 1);
  const std::uint32_t lo = std::min(n1, n2);
  if (lo < 2 || n1 == n2) return std::nullopt;
  auto R = [&](std::uint32_t k) { return st.rail1[k]; };
  auto L = [&](std::uint32_t k) { return st.rail2[n2 - k]; };
  std::optional<FaceMesh> best;
  for (std::uint32_t rows = lo - 1; rows + 3 >= lo && rows >= 1; --rows) {
    // The remainder, counter-clockwise: the chord L(rows) -> R(rows), rail1 up, cap2, rail2 down.
    FaceInput rest;
    std::vector<std::uint32_t> ids;
    auto push = [&](std::uint32_t id) {
      ids.push_back(id);
      rest.cycle.push_back(face.cycle[id]);
    };
    for (std::uint32_t k = rows; k < n1; ++k) push(R(k));
    for (std::size_t k = 0; k + 1 < st.cap2.size(); ++k) push(st.cap2[k]);
    for (std::uint32_t k = n2; k > rows; --k) push(L(k));
    if (rest.cycle.size() < 4 || rest.cycle.size() % 2 != 0) continue;
    FaceSide all;
    all.kind = FaceSide::Kind::Boundary;
    all.edges = static_cast<std::uint32_t>(rest.cycle.size());
    rest.sides.push_back(all);
    const std::optional<FaceMesh> sub = fill_any(rest, depth + 1);
    if (!sub) continue;
    Builder m(face, FillKind::Rows);
    for (std::uint32_t k = 0; k < rows; ++k) m.quad(L(k), R(k), R(k + 1), L(k + 1));
    m.embed(*sub, ids);
    FaceMesh r = m.finish();
    if (!r.interior.empty() && r.min_jacobian < kAcceptJacobian) relax(r, face, 30);
    if (!best || r.min_jacobian > best->min_jacobian) best = std::move(r);
  }
  return best;
}

/// The rest of a strip once rows are laid from its caps: the last rung from cap1 (`end1`,
/// counter-clockwise from rail2 to rail1), rail1[s1, e1), the last rung from cap2 (`end2`),
/// rail2[s2, e2), read as boundary, rail, boundary, rail; filled by any template and embedded
/// in m. False when no template fills it.
bool fill_remainder(Builder& m, const Strip& st, const std::vector<std::uint32_t>& end1,
                    std::uint32_t s1, std::uint32_t e1, const std::vector<std::uint32_t>& end2,
                    std::uint32_t s2, std::uint32_t e2, int depth) {
  FaceInput rest;
  std::vector<std::uint32_t> ids;
  auto side = [&](FaceSide::Kind kind, std::uint32_t edges, const std::vector<std::uint32_t>& joints,
                  std::uint32_t shift) {
    FaceSide sd;
    sd.kind = kind;
    sd.first = static_cast<std::uint32_t>(ids.size());
    sd.edges = edges;
    for (std::uint32_t j : joints)
      if (j > shift && j < shift + edges) sd.joints.push_back(j - shift);
    rest.sides.push_back(sd);
  };
  auto push = [&](std::uint32_t id) {
    ids.push_back(id);
    rest.cycle.push_back(m.pos(id));
  };
  side(FaceSide::Kind::Boundary, static_cast<std::uint32_t>(end1.size() - 1), {}, 0);
  for (std::size_t i = 0; i + 1 < end1.size(); ++i) push(end1[i]);
  side(FaceSide::Kind::Rail, e1 - s1, st.joints1, s1);
  for (std::uint32_t k = s1; k < e1; ++k) push(st.rail1[k]);
  side(FaceSide::Kind::Boundary, static_cast<std::uint32_t>(end2.size() - 1), {}, 0);
  for (std::size_t i = 0; i + 1 < end2.size(); ++i) push(end2[i]);
  side(FaceSide::Kind::Rail, e2 - s2, st.joints2, s2);
  for (std::uint32_t k = s2; k < e2; ++k) push(st.rail2[k]);
  if (rest.cycle.size() < 4 || rest.cycle.size() % 2 != 0) return false;
  const std::optional<FaceMesh> sub = fill_any(rest, depth + 1);
  if (!sub) return false;
  m.embed(*sub, ids);
  return true;
}

/// Strip: a long face between two rails whose caps or rails do not match (so no grid): rows
/// of cap1's width laid from cap1 and rows of cap2's width from cap2 along the rails, straight
/// rungs across, until a short remainder in the middle (its rails about as long as the strip
/// is wide, or as the mismatch) takes the change of width by any other template. Keeps long
/// strips out of the O(n^3) templates and puts the irregular quads in one place.
std::optional<FaceMesh> fill_strip(const FaceInput& face, const Strip& st, int depth) {
  if (depth > 1 || st.cap1.size() < 2 || st.cap2.size() < 2) return std::nullopt;
  const Strip::Edges e = st.edges();  // not a structured binding: lambdas capture n1, n2
  const std::uint32_t a = e.a, c = e.c, n1 = e.n1, n2 = e.n2;
  const std::uint32_t lo = std::min(n1, n2);
  const std::uint32_t mismatch = (a > c ? a - c : c - a) + (n1 > n2 ? n1 - n2 : n2 - n1);
  const std::uint32_t keep = std::max({a, c, mismatch, 2u});
  if (lo <= keep) return std::nullopt;
  const std::uint32_t r1 = (lo - keep) / 2, r2 = lo - keep - r1;
  Builder m(face, FillKind::Strip);
  // Rung k from cap1 joins L(k) = rail2[n2 - k] to R(k) = rail1[k] with a edges spaced like
  // cap1; rung k from cap2 joins rail1[n1 - k] to rail2[k] with c edges spaced like cap2.
  auto params = [&](const std::vector<std::uint32_t>& cap) {
    std::vector<double> t(cap.size(), 0.0);
    for (std::size_t k = 1; k < cap.size(); ++k)
      t[k] = t[k - 1] + distance(m.pos(cap[k - 1]), m.pos(cap[k]));
    for (double& x : t) x = t.back() > 0.0 ? x / t.back() : 0.0;
    return t;
  };
  auto lay_rows = [&](const std::vector<std::uint32_t>& cap, std::uint32_t rows,
                      auto from, auto to) {
    const std::vector<double> t = params(cap);
    std::vector<std::uint32_t> prev = cap, rung(cap.size());
    for (std::uint32_t k = 1; k <= rows; ++k) {
      rung.front() = from(k);
      rung.back() = to(k);
      for (std::size_t i = 1; i + 1 < cap.size(); ++i)
        rung[i] = m.add(lerp(m.pos(rung.front()), m.pos(rung.back()), t[i]));
      for (std::size_t i = 0; i + 1 < cap.size(); ++i) m.quad(prev[i], prev[i + 1], rung[i + 1], rung[i]);
      prev = rung;
    }
    return prev;
  };
  const std::vector<std::uint32_t> end1 = lay_rows(
      st.cap1, r1, [&](std::uint32_t k) { return st.rail2[n2 - k]; },
      [&](std::uint32_t k) { return st.rail1[k]; });
  const std::vector<std::uint32_t> end2 = lay_rows(
      st.cap2, r2, [&](std::uint32_t k) { return st.rail1[n1 - k]; },
      [&](std::uint32_t k) { return st.rail2[k]; });
  // The remainder: end1, rail1 from r1 to n1 - r2, end2, rail2 from r2 to n2 - r1.
  if (!fill_remainder(m, st, end1, r1, n1 - r2, end2, r2, n2 - r1, depth)) return std::nullopt;
  FaceMesh r = m.finish();
  if (r.min_jacobian < kAcceptJacobian) relax(r, face, 30);
  return r;
}

/// Taper: a strip whose caps differ by at least kTaperCaps edges (a corridor narrowing to a
/// point, or much wider at one end). fill_strip would take the whole change of width, and of
/// the rails' lengths, in one remainder. Here rows are laid from the wide cap along the
/// rails, spreading both changes evenly over the rows: a row is plain (one rail edge on each
/// side, the rung as wide as the one before), a narrowing (the rung two edges narrower: a
/// three-to-one transition of four quads and two inner nodes in the middle of the row) or a
/// shear (two edges of the longer rail, the rung one edge narrower: three quads round an
/// inner node beside the extra rail node take the row's first or last two edges). Shears take
/// min(rail difference, cap difference), narrowings the rest of the cap difference; a short
/// remainder at the narrow cap takes what is left of the rails' difference by any other
/// template.
constexpr std::uint32_t kTaperCaps = 4;

std::optional<FaceMesh> fill_taper(const FaceInput& face, const Strip& st, int depth) {
  if (depth > 1 || st.cap1.size() < 2 || st.cap2.size() < 2) return std::nullopt;
  const Strip::Edges e = st.edges();  // not a structured binding: lambdas capture n1, n2
  const std::uint32_t a = e.a, c = e.c, n1 = e.n1, n2 = e.n2;
  const bool from_cap1 = a >= c;
  const std::uint32_t wide = std::max(a, c), narrow = std::min(a, c);
  if (wide < narrow + kTaperCaps) return std::nullopt;
  // Rung k joins from(kf) to to(kt), kf and kt counted along their rails from the wide cap,
  // as fill_strip's rungs from that cap. `from` runs along rail2 from cap1, rail1 from cap2.
  const std::uint32_t nf = from_cap1 ? n2 : n1, nt = from_cap1 ? n1 : n2;
  const auto from = [&](std::uint32_t k) {
    return from_cap1 ? st.rail2[n2 - k] : st.rail1[n1 - k];
  };
  const auto to = [&](std::uint32_t k) { return from_cap1 ? st.rail1[k] : st.rail2[k]; };
  const std::uint32_t diff = nf > nt ? nf - nt : nt - nf;
  const std::uint32_t shears = std::min(diff, wide - narrow);
  if ((wide - narrow - shears) % 2 != 0) return std::nullopt;  // cannot happen: even cycle
  const std::uint32_t narrowings = (wide - narrow - shears) / 2;
  const std::uint32_t events = shears + narrowings;
  const std::uint32_t keep = std::max({narrow, diff - shears, 2u});
  const std::uint32_t lo = std::min(nf, nt);
  if (lo <= keep || lo - keep < 2 * events) return std::nullopt;
  const std::uint32_t rows = lo - keep;
  Builder m(face, FillKind::Taper);
  std::vector<std::uint32_t> prev = from_cap1 ? st.cap1 : st.cap2, rung;
  // Quads between prev's edges i in [i0, i1) and the rung's edges `shift` places before them.
  const auto row = [&](std::uint32_t i0, std::uint32_t i1, std::uint32_t shift) {
    for (std::uint32_t i = i0; i < i1; ++i)
      m.quad(prev[i], prev[i + 1], rung[i + 1 - shift], rung[i - shift]);
  };
  std::uint32_t kf = 0, kt = 0, done = 0, sheared = 0;
  for (std::uint32_t k = 1; k <= rows; ++k) {
    const auto pw = static_cast<std::uint32_t>(prev.size() - 1);
    // Event i in row floor((i + 1/2) rows / events) + 1; shears spread among them alike.
    const bool event = done < events && 2 * (k - 1) * events >= (2 * done + 1) * rows;
    const bool shear = event && (done + 1) * shears / events > sheared;
    const bool shear_from = shear && nf > nt;
    const bool shear_to = shear && !shear_from;
    const std::uint32_t cw = !event ? pw : shear ? pw - 1 : pw - 2;
    const std::uint32_t xf = kf + 1, xt = kt + 1;  // the extra rail node of a shear
    kf += shear_from ? 2 : 1;
    kt += shear_to ? 2 : 1;
    rung.assign(cw + 1, 0);
    rung.front() = from(kf);
    rung.back() = to(kt);
    for (std::uint32_t i = 1; i < cw; ++i)
      rung[i] = m.add(lerp(m.pos(rung.front()), m.pos(rung.back()), static_cast<double>(i) / cw));
    if (!event) {
      row(0, pw, 0);
    } else if (shear_from) {
      // The extra rail node x is no flat corner: an inner node y beside it takes two quads.
      const std::uint32_t x = from(xf);
      const std::uint32_t y =
          m.add(lerp(m.pos(x), lerp(m.pos(prev[1]), m.pos(rung[1]), 0.5), 0.5));
      m.quad(prev[0], prev[1], y, x);
      m.quad(x, y, rung[1], rung[0]);
      m.quad(prev[1], prev[2], rung[1], y);
      row(2, pw, 1);
    } else if (shear_to) {
      const std::uint32_t x = to(xt);
      const std::uint32_t y =
          m.add(lerp(m.pos(x), lerp(m.pos(prev[pw - 1]), m.pos(rung[pw - 2]), 0.5), 0.5));
      row(0, pw - 2, 0);
      m.quad(prev[pw - 2], prev[pw - 1], y, rung[pw - 2]);
      m.quad(prev[pw - 1], prev[pw], x, y);
      m.quad(y, x, rung[pw - 1], rung[pw - 2]);
    } else {
      const std::uint32_t j = (pw - 3) / 2;
      row(0, j, 0);
      const std::uint32_t p0 = prev[j], p1 = prev[j + 1], p2 = prev[j + 2], p3 = prev[j + 3];
      const std::uint32_t q0 = rung[j], q1 = rung[j + 1];
      const std::uint32_t m1 = m.add(0.5 * (m.pos(p1) + lerp(m.pos(q0), m.pos(q1), 1.0 / 3.0)));
      const std::uint32_t m2 = m.add(0.5 * (m.pos(p2) + lerp(m.pos(q0), m.pos(q1), 2.0 / 3.0)));
      m.quad(p0, p1, m1, q0);
      m.quad(p1, p2, m2, m1);
      m.quad(p2, p3, q1, m2);
      m.quad(m1, m2, q1, q0);
      row(j + 3, pw, 2);
    }
    if (event) ++done;
    if (shear) ++sheared;
    prev = rung;
  }
  if (done != events || kf > nf - 2 || kt > nt - 2) return std::nullopt;
  // The remainder, as fill_strip's: the last rung and the narrow cap, and the rest of the
  // rails. rail1 runs from cap1 to cap2: from cap1 it is `to` (kt edges used at its start),
  // from cap2 it is `from` (kf used at its end); rail2 likewise.
  const std::uint32_t s1 = from_cap1 ? kt : 0, e1 = from_cap1 ? n1 : n1 - kf;
  const std::uint32_t s2 = from_cap1 ? 0 : kt, e2 = from_cap1 ? n2 - kf : n2;
  if (!fill_remainder(m, st, from_cap1 ? prev : st.cap1, s1, e1, from_cap1 ? st.cap2 : prev, s2,
                      e2, depth))
    return std::nullopt;
  FaceMesh r = m.finish();
  if (r.min_jacobian < kAcceptJacobian) relax(r, face, 30);
  return r;
}

/// Faces with more nodes than kLargeFace try the split, cut and pairs templates (O(n^3)) only
/// when the structured templates gave nothing with a worst corner of kLargeFaceFloor or more,
/// and faces of more than kHugeFace nodes only below kHugeFaceFloor (0.2 for every size cost
/// 4x in the quads stage of the million-quad tray; 0.05 still catches a 0.007 grid).
constexpr std::size_t kLargeFace = 48;
constexpr double kLargeFaceFloor = 0.2;
constexpr std::size_t kHugeFace = 128;
constexpr double kHugeFaceFloor = 0.05;

/// x in whole steps of `step`, counting a value within kStepSlack of a step (in steps) as
/// that step. Grid-cell outlines give worst corners and lengths exactly on a step in one pose
/// (a 3-4-5 quad's 0.6, a square's 1) and a rounding below it in another: plain floor put
/// them a step apart, and rect_043 of the session-30 fuzzing took another template and 378
/// quads instead of 385 scaled by 1e3.
constexpr double kStepSlack = 1e-6;
double whole_steps(double x, double step) { return std::floor(x / step + kStepSlack); }

/// Templates' worst corners are compared in steps of this; any valid one beats every invalid.
constexpr double kChoiceStep = 0.05;
double quantised(double jacobian) {
  const double step = whole_steps(jacobian, kChoiceStep);
  return jacobian > kMinValidJacobian ? step : step - 1e6;
}

/// O-grid: a round face (every interior angle between kRoundMin and kRoundMax) as a rectangle
/// of a x b quads in its middle and rings of quads round it: the boundary is read as four
/// quarters of a, b, a, b edges (n = 2(a + b)), each joined by `layers` rows to one side of
/// the rectangle, whose corners are the quarters' ends drawn towards the centroid by
/// kOgridInner. A disk's rails all meet at its centre; without them (drop_disk_rails) its
/// one face gets this instead of a fan of wedges with slivers at the centre. The quarters
/// start at each of a few nodes; the best by worst corner wins (the first on ties).
constexpr double kOgridInner = 0.85;
constexpr std::uint32_t kOgridStarts = 4;

/// Arms: a face whose sides alternate boundary, rail, boundary, rail... with three or more of
/// each (narrow corridors meeting at a junction, their rails long, each ended by a short
/// boundary piece, its cap). From each cap, rows of quads are laid along its two rails, straight
/// rungs of the cap's count across, while a rung stays within kArmWiden of the cap's length and
/// the rows from both ends of a rail leave kArmKeep of it between them; the junction left in
/// the middle takes any other template. Such a face with no structured reading fell to the
/// split template, whose coarse triangles spanned it (tray_ribs at h = 0.1357: a T of three
/// 2-wide arms 20 long, quads 100 element sizes long, worst 0.001).
constexpr double kArmWiden = 1.25;
constexpr std::uint32_t kArmKeep = 2;
constexpr std::uint32_t kArmRows = 4;
constexpr std::size_t kArmFace = 192;

std::optional<FaceMesh> fill_arms(const FaceInput& face, int depth) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  const std::size_t ns = face.sides.size();
  // Long faces only (more than kArmFace nodes): smaller ones are as well served by the
  // unstructured templates (cgal_hole's worst element 0.730 against 0.635 with arms for every
  // face, cgal_wiggly_03_cgal's skew >= 30 10.5% against 11.9% with arms above 48 nodes).
  if (depth > 0 || n <= kArmFace || ns < 6 || ns % 2 != 0) return std::nullopt;
  // Rotate so that the sides read cap, rail, cap, rail...
  std::size_t off = face.sides[0].kind == FaceSide::Kind::Boundary ? 0 : 1;
  for (std::size_t k = 0; k < ns; ++k) {
    const FaceSide& sd = face.sides[(k + off) % ns];
    const bool cap = k % 2 == 0;
    if ((sd.kind == FaceSide::Kind::Boundary) != cap || sd.edges == 0) return std::nullopt;
  }
  const std::size_t arms = ns / 2;
  std::vector<std::uint32_t> s(arms), e(arms), len(arms);  // cap start, cap edges, next rail
  for (std::size_t i = 0; i < arms; ++i) {
    s[i] = face.sides[(off + 2 * i) % ns].first;
    e[i] = face.sides[(off + 2 * i) % ns].edges;
    len[i] = face.sides[(off + 2 * i + 1) % ns].edges;  // the rail after cap i
  }
  auto at = [&](std::int64_t k) { return static_cast<std::uint32_t>(((k % n) + n) % n); };
  // Rows per arm: rung r joins node s - r (on the rail before the cap) to node s + e + r.
  std::vector<std::uint32_t> rows(arms, 0);
  for (std::size_t i = 0; i < arms; ++i) {
    const double cap = distance(face.cycle[s[i]], face.cycle[at(s[i] + e[i])]);
    const std::uint32_t before = len[(i + arms - 1) % arms], after = len[i];
    std::uint32_t r = 0;
    auto width = [&](std::uint32_t k) {
      return distance(face.cycle[at(std::int64_t{s[i]} - k)], face.cycle[at(s[i] + e[i] + k)]);
    };
    while (r + 1 + kArmKeep <= std::min(before, after) && width(r + 1) <= kArmWiden * cap) ++r;
    rows[i] = r;
  }
  // The rows from both ends of a rail leave kArmKeep edges of it between them.
  for (std::size_t i = 0; i < arms; ++i) {
    const std::size_t j = (i + 1) % arms;  // rail i runs from cap i to cap j
    while (rows[i] + rows[j] + kArmKeep > len[i]) {
      if (rows[i] >= rows[j] && rows[i] > 0) --rows[i];
      else if (rows[j] > 0) --rows[j];
      else return std::nullopt;
    }
  }
  // Arms at least kArmRows rows long: corridors, not a ragged face that happens to alternate.
  if (*std::min_element(rows.begin(), rows.end()) < kArmRows) return std::nullopt;
  Builder m(face, FillKind::Arms);
  // Rung r of arm i: node ids from the rail before the cap to the rail after it, spaced like
  // the cap.
  auto rung = [&](std::size_t i, std::uint32_t r) {
    std::vector<std::uint32_t> ids;
    if (r == 0) {
      for (std::uint32_t k = 0; k <= e[i]; ++k) ids.push_back(at(s[i] + k));
      return ids;
    }
    std::vector<double> t(e[i] + 1, 0.0);
    for (std::uint32_t k = 1; k <= e[i]; ++k)
      t[k] = t[k - 1] + distance(face.cycle[at(s[i] + k - 1)], face.cycle[at(s[i] + k)]);
    const std::uint32_t a = at(std::int64_t{s[i]} - r), b = at(s[i] + e[i] + r);
    ids.push_back(a);
    for (std::uint32_t k = 1; k < e[i]; ++k) {
      const double u = t.back() > 0.0 ? t[k] / t.back() : 0.0;
      ids.push_back(m.add(lerp(face.cycle[a], face.cycle[b], u)));
    }
    ids.push_back(b);
    return ids;
  };
  std::vector<std::vector<std::uint32_t>> last(arms);
  for (std::size_t i = 0; i < arms; ++i) {
    std::vector<std::uint32_t> lo = rung(i, 0);
    for (std::uint32_t r = 1; r <= rows[i]; ++r) {
      std::vector<std::uint32_t> hi = rung(i, r);
      for (std::uint32_t k = 0; k < e[i]; ++k) m.quad(lo[k], lo[k + 1], hi[k + 1], hi[k]);
      lo = std::move(hi);
    }
    last[i] = std::move(lo);
  }
  // The junction: each arm's last rung, then the rail left between it and the next arm's.
  FaceInput rest;
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < arms; ++i) {
    const std::size_t j = (i + 1) % arms;
    for (std::size_t k = 0; k + 1 < last[i].size(); ++k) ids.push_back(last[i][k]);
    const std::int64_t from = std::int64_t{s[i]} + e[i] + rows[i];
    const std::int64_t to = std::int64_t{s[i]} + e[i] + len[i] - rows[j];
    for (std::int64_t k = from; k < to; ++k) ids.push_back(at(k));
  }
  for (std::uint32_t id : ids) rest.cycle.push_back(m.pos(id));
  if (rest.cycle.size() < 4 || rest.cycle.size() % 2 != 0) return std::nullopt;
  FaceSide all;
  all.kind = FaceSide::Kind::Boundary;
  all.edges = static_cast<std::uint32_t>(rest.cycle.size());
  rest.sides.push_back(all);
  const std::optional<FaceMesh> sub = fill_any(rest, depth + 1);
  if (!sub) return std::nullopt;
  m.embed(*sub, ids);
  FaceMesh r = m.finish();
  if (!r.interior.empty() && r.min_jacobian < kAcceptJacobian) relax(r, face, 30);
  return r;
}

std::optional<FaceMesh> fill_ogrid(const FaceInput& face) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (n < 12 || n % 2 != 0) return std::nullopt;
  const std::vector<Vec2>& p = face.cycle;
  if (!is_round(p)) return std::nullopt;
  // The centroid of the polygon's area, and its mean edge.
  double twice = 0.0, s = 0.0;
  Vec2 c{0.0, 0.0};
  for (std::uint32_t k = 0; k < n; ++k) {
    const Vec2 x = p[k], y = p[(k + 1) % n];
    const double w = cross(x, y);
    twice += w;
    c = c + (w / 3.0) * (x + y);
    s += distance(x, y) / n;
  }
  if (!(twice > 0.0)) return std::nullopt;
  c = (1.0 / twice) * c;
  const std::uint32_t a = n / 4, b = n / 2 - a;
  std::optional<FaceMesh> best;
  const std::uint32_t tries = std::min<std::uint32_t>(kOgridStarts, a);
  for (std::uint32_t t = 0; t < tries; ++t) {
    const std::uint32_t start = t * a / tries;
    auto at = [&](std::uint32_t i) { return (start + i) % n; };  // boundary node i of the reading
    const std::array<std::uint32_t, 5> quarter{0, a, a + b, 2 * a + b, n};
    std::array<Vec2, 4> corner;
    for (std::size_t k = 0; k < 4; ++k) corner[k] = lerp(c, p[at(quarter[k])], kOgridInner);
    // The inner polygon: each quarter's nodes at the same fractions of its length along the
    // rectangle's side.
    std::vector<Vec2> inner(n);
    for (std::size_t k = 0; k < 4; ++k) {
      double total = 0.0;
      for (std::uint32_t i = quarter[k]; i < quarter[k + 1]; ++i) total += distance(p[at(i)], p[at(i + 1)]);
      double run = 0.0;
      for (std::uint32_t i = quarter[k]; i < quarter[k + 1]; ++i) {
        inner[i] = lerp(corner[k], corner[(k + 1) % 4], total > 0.0 ? run / total : 0.0);
        run += distance(p[at(i)], p[at(i + 1)]);
      }
    }
    double gap = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) gap += distance(p[at(i)], inner[i]) / n;
    const auto layers = static_cast<std::uint32_t>(std::max(1.0, std::round(gap / s)));
    Builder m(face, FillKind::Ogrid);
    // Ring l (0 the boundary, `layers` the rectangle's boundary), node i.
    std::vector<std::uint32_t> ring(static_cast<std::size_t>(layers + 1) * n);
    auto r = [&](std::uint32_t l, std::uint32_t i) -> std::uint32_t& { return ring[l * n + i % n]; };
    for (std::uint32_t i = 0; i < n; ++i) r(0, i) = at(i);
    // The rectangle's grid (u along quarter 0, v along quarter 1): its boundary nodes are the
    // last ring.
    std::vector<std::uint32_t> grid(static_cast<std::size_t>(a + 1) * (b + 1), kNoId);
    auto g = [&](std::uint32_t u, std::uint32_t v) -> std::uint32_t& { return grid[v * (a + 1) + u]; };
    for (std::uint32_t i = 0; i < n; ++i) {
      for (std::uint32_t l = 1; l < layers; ++l)
        r(l, i) = m.add(lerp(p[at(i)], inner[i], static_cast<double>(l) / layers));
      r(layers, i) = m.add(inner[i]);
    }
    for (std::uint32_t u = 0; u < a; ++u) g(u, 0) = r(layers, u);
    for (std::uint32_t v = 0; v < b; ++v) g(a, v) = r(layers, a + v);
    for (std::uint32_t u = 0; u < a; ++u) g(a - u, b) = r(layers, a + b + u);
    for (std::uint32_t v = 0; v < b; ++v) g(0, b - v) = r(layers, 2 * a + b + v);
    for (std::uint32_t v = 1; v < b; ++v)
      for (std::uint32_t u = 1; u < a; ++u) {
        const double x = static_cast<double>(u) / a, y = static_cast<double>(v) / b;
        const Vec2 q = (1.0 - y) * m.pos(g(u, 0)) + y * m.pos(g(u, b)) + (1.0 - x) * m.pos(g(0, v)) +
                       x * m.pos(g(a, v)) -
                       ((1.0 - x) * (1.0 - y) * corner[0] + x * (1.0 - y) * corner[1] +
                        x * y * corner[2] + (1.0 - x) * y * corner[3]);
        g(u, v) = m.add(q);
      }
    for (std::uint32_t l = 0; l < layers; ++l)
      for (std::uint32_t i = 0; i < n; ++i) m.quad(r(l, i), r(l, i + 1), r(l + 1, i + 1), r(l + 1, i));
    for (std::uint32_t v = 0; v < b; ++v)
      for (std::uint32_t u = 0; u < a; ++u) m.quad(g(u, v), g(u + 1, v), g(u + 1, v + 1), g(u, v + 1));
    FaceMesh out = m.finish();
    relax(out, face, 30);
    if (!best || quantised(out.min_jacobian) > quantised(best->min_jacobian)) best = std::move(out);
  }
  return best;
}

}  // namespace

double quad_taper(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3) {
  const Vec2 p[4] = {p0, p1, p2, p3};
  double a[4], sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    a[i] = cross(p[(i + 1) % 4] - p[i], p[(i + 3) % 4] - p[i]);
    sum += a[i];
  }
  if (!(sum > 0.0)) return 0.0;
  return std::min({a[0], a[1], a[2], a[3]}) / (0.25 * sum);
}

TaperJacobian quad_taper_jacobian(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3) {
  // e[i] runs from corner i to i + 1; corner i's product is cross(e[i], -e[i - 1]), which is
  // quad_taper's cross(p[i + 1] - p[i], p[i - 1] - p[i]) and min_scaled_jacobian's numerator.
  const Vec2 e[4] = {p1 - p0, p2 - p1, p3 - p2, p0 - p3};
  const double l[4] = {dot(e[0], e[0]), dot(e[1], e[1]), dot(e[2], e[2]), dot(e[3], e[3])};
  double a[4], sum = 0.0, worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 3) % 4;  // the edge into corner i
    const Vec2 back = -1.0 * e[j];
    a[i] = cross(e[i], back);
    sum += a[i];
    const double l2 = l[i] * l[j];
    worst = std::min(worst, l2 > 0.0 ? a[i] / std::sqrt(l2) : -1.0);
  }
  const double taper = sum > 0.0 ? std::min({a[0], a[1], a[2], a[3]}) / (0.25 * sum) : 0.0;
  return {taper, worst};
}

namespace {

/// The mean over a face's quads of min(scaled Jacobian, taper) (quality.md): 1 for squares,
/// 0.5 for the kites of a triangle split into three. Chooses between unstructured templates
/// whose worst corners are all acceptable, so that fewer and squarer quads win.
double mean_shape(const FaceMesh& m, const FaceInput& face) {
  if (m.quads.empty()) return 0.0;
  const std::size_t n = face.cycle.size();
  auto pos = [&](std::uint32_t i) { return i < n ? face.cycle[i] : m.interior[i - n]; };
  double sum = 0.0;
  for (const auto& q : m.quads) {
    const Vec2 a = pos(q[0]), b = pos(q[1]), c = pos(q[2]), d = pos(q[3]);
    const TaperJacobian tj = quad_taper_jacobian(a, b, c, d);
    sum += std::min(tj.taper, tj.jacobian);
  }
  return sum / static_cast<double>(m.quads.size());
}

/// mean_shape compared in whole steps of this (a later template must be better by one).
constexpr double kShapeStep = 0.01;

/// Reflex cut: a face with a reflex corner (an L, a T, the corner region between tracks of
/// different widths) is cut in two by a straight chord from that corner to another node of
/// the face, and each piece is filled by any template (a piece with four corners is read as a
/// strip whose first cap holds the chord). Chords leave every corner they cut near a right
/// angle or flat (kReflexCutSlack), so that the pieces are grids where their counts match.
/// The chord gets the inner nodes that make both pieces' node counts even, spaced as close as
/// parity allows to the mean edge at its two ends. At most kReflexCuts chords are tried (one
/// in a face over kReflexLargeFace nodes), best first; the quads with the best quantised worst
/// corner win, then the best mean_shape.
constexpr double kReflexCutMin = 201.0 * kPi / 180.0;
constexpr double kReflexCutSlack = 24.5 * kPi / 180.0;
constexpr std::size_t kReflexCuts = 3;
/// In a face of more than kReflexLargeFace nodes only the best chord is tried: each other one
/// filled two pieces of some 90 nodes with every template (cgal_wiggly_03_cgal's 124-node
/// face: 55 ms on one thread, 40 of them in the second and third chords, which did not win;
/// quads stage 0.095 -> 0.080 s, the same mesh). Of the 277 set meshes one more changed than
/// with kReflexSkipAbove alone (manyv__random_star250: 1876 -> 1999 quads, taper <= 0.8 62.2%
/// -> 63.2%, the same worst corner).
constexpr std::size_t kReflexLargeFace = 120;
constexpr double kReflexSlackStep = 1.0 * kPi / 180.0;
constexpr double kReflexLengthStep = 0.1;
/// Only faces up to this size, and pieces are cut again only once (depth).
constexpr std::size_t kReflexCutNodes = 160;
constexpr int kReflexCutDepth = 1;
/// Halving cuts, where no plain cut fits: a corner of kReflexHalveMin to kReflexHalveMax at a
/// node off the boundary (FaceInput::free_nodes) halved within kReflexHalveSlack, the far end
/// within it of 45, 90, 135 or 180 degrees; at most kReflexHalves tried, until one gives
/// quads of kReflexHalveBelow or more.
constexpr double kReflexHalveMin = 250.0 * kPi / 180.0;
constexpr double kReflexHalveMax = 300.0 * kPi / 180.0;
constexpr double kReflexHalveSlack = 12.0 * kPi / 180.0;
constexpr std::size_t kReflexHalves = 2;
constexpr double kReflexHalveBelow = 0.5;

/// How far an angle of a piece's corner is from 90 degrees or flat (a reflex part counts
/// from flat).
double corner_slack(double a) {
  return std::min(std::abs(a - 0.5 * kPi), std::abs(a - kPi));
}

/// The sides of a piece: four sides boundary, rail, boundary, rail from its corners (interior
/// angles below kCornerAngle, none reflex), the side holding edge `mark` first; otherwise one
/// boundary side of every edge.
std::vector<FaceSide> piece_sides(const std::vector<Vec2>& poly, std::uint32_t mark) {
  const auto n = static_cast<std::uint32_t>(poly.size());
  std::vector<std::uint32_t> corners;
  bool reflex = false;
  for (std::uint32_t k = 0; k < n; ++k) {
    const double a = interior_angle(poly, k);
    if (a >= kReflexCutMin) reflex = true;
    if (a < kCornerAngle) corners.push_back(k);
  }
  std::vector<FaceSide> sides;
  if (reflex || corners.size() != 4) {
    FaceSide all;
    all.kind = FaceSide::Kind::Boundary;
    all.edges = n;
    sides.push_back(all);
    return sides;
  }
  // The side holding edge mark (from node mark to mark + 1).
  std::size_t first = 3;
  for (std::size_t c = 0; c < 4; ++c) {
    const std::uint32_t from = corners[c], edges = (corners[(c + 1) % 4] + n - from) % n;
    if ((mark + n - from) % n < edges) first = c;
  }
  for (std::size_t c = 0; c < 4; ++c) {
    const std::uint32_t from = corners[(first + c) % 4], to = corners[(first + c + 1) % 4];
    FaceSide s;
    s.kind = c % 2 == 0 ? FaceSide::Kind::Boundary : FaceSide::Kind::Rail;
    s.first = from;
    s.edges = (to + n - from) % n;
    sides.push_back(s);
  }
  return sides;
}

/// How far an angle is from a multiple of 45 degrees between 45 and 180: the far end of a
/// halving cut may leave 45 or 135 degrees (a grid's worst corner there is sin 45 = 0.71).
double loose_slack(double a) {
  double best = kPi;
  for (int k = 1; k <= 4; ++k) best = std::min(best, std::abs(a - 0.25 * kPi * k));
  return best;
}

bool has_reflex(const std::vector<Vec2>& poly) {
  for (std::size_t k = 0; k < poly.size(); ++k)
    if (interior_angle(poly, k) >= kReflexCutMin) return true;
  return false;
}

std::optional<FaceMesh> fill_reflex(const FaceInput& face, int depth) {
  const auto n = static_cast<std::uint32_t>(face.cycle.size());
  if (depth > kReflexCutDepth || n < 8 || n > kReflexCutNodes) return std::nullopt;
  const std::vector<Vec2>& p = face.cycle;
  std::vector<double> angle(n);
  for (std::uint32_t k = 0; k < n; ++k) angle[k] = interior_angle(p, k);
  auto edge = [&](std::uint32_t k) { return distance(p[k], p[(k + 1) % n]); };
  struct Cut {
    double slack;
    double length;
    std::uint32_t r, t;
    bool halves;  ///< bisects a corner of kReflexHalveMin or more (and its other end)
  };
  std::vector<Cut> cuts;
  for (std::uint32_t r = 0; r < n; ++r) {
    if (angle[r] < kReflexCutMin) continue;
    const Vec2 out_r = p[(r + 1) % n] - p[r];
    for (std::uint32_t gap = 2; gap + 2 <= n; ++gap) {
      const std::uint32_t t = (r + gap) % n;
      const Vec2 c = p[t] - p[r];
      if (!(norm(c) > 0.0)) continue;
      // The chord's angles in the two pieces at r (piece A runs r .. t along the cycle).
      const double ra = ccw_angle(out_r, c), rb = angle[r] - ra;
      if (ra <= 0.0 || rb <= 0.0) continue;
      const double ta = ccw_angle(-1.0 * c, p[(t + n - 1) % n] - p[t]);
      const double tb = angle[t] - ta;
      if (ta <= 0.0 || tb <= 0.0) continue;
      // Halving cuts (docs/mesher.md, "Reflex cut"): a corner of 250-300 degrees off the
      // boundary (round a large fillet's centre: the arc's fan spans its 90 degrees, the face
      // the rest) halved, the far end left near 45, 90, 135 or 180 degrees.
      const bool free_r = r < face.free_nodes.size() && face.free_nodes[r];
      const double half_r = free_r && angle[r] >= kReflexHalveMin && angle[r] <= kReflexHalveMax
                                ? std::abs(ra - 0.5 * angle[r])
                                : kPi;
      const double plain = std::max({corner_slack(ra), corner_slack(rb), corner_slack(ta), corner_slack(tb)});
      const double halved = std::max({half_r, loose_slack(ta), loose_slack(tb)});
      const bool halves = plain > kReflexCutSlack;
      const double slack = halves ? halved : plain;
      if (slack > (halves ? kReflexHalveSlack : kReflexCutSlack)) continue;
      bool crosses = false;
      for (std::uint32_t k = 0; k < n && !crosses; ++k) {
        const std::uint32_t k1 = (k + 1) % n;
        if (k == r || k == t || k1 == r || k1 == t) continue;
        crosses = mesher_detail::segments_meet(p[r], p[t], p[k], p[k1]);
      }
      if (crosses || !inside_polygon(0.5 * (p[r] + p[t]), p)) continue;
      cuts.push_back({slack, norm(c), r, t, halves});
    }
  }
  // Halving cuts only where no plain one fits.
  if (std::any_of(cuts.begin(), cuts.end(), [](const Cut& c) { return !c.halves; }))
    cuts.erase(std::remove_if(cuts.begin(), cuts.end(), [](const Cut& c) { return c.halves; }),
               cuts.end());
  if (cuts.empty()) return std::nullopt;
  // Best first: least slack, then shortest, each in whole steps (kReflexSlackStep, and
  // kReflexLengthStep of the face's mean edge) so that chords equal but for rounding (mirror
  // images) keep their order, by node index, in every pose of a part.
  double mean_edge = 0.0;
  for (std::uint32_t k = 0; k < n; ++k) mean_edge += edge(k) / n;
  auto rank = [&](const Cut& c) {
    return std::make_tuple(std::round(c.slack / kReflexSlackStep),
                           whole_steps(c.length, kReflexLengthStep * mean_edge), c.r, c.t);
  };
  std::sort(cuts.begin(), cuts.end(), [&](const Cut& a, const Cut& b) { return rank(a) < rank(b); });
  // A chord and its reverse (both ends reflex) are one cut.
  std::optional<FaceMesh> best;
  double best_shape = 0.0;
  std::size_t tried = 0;
  const std::size_t most = cuts.front().halves    ? kReflexHalves
                           : n > kReflexLargeFace ? 1
                                                  : kReflexCuts;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> done;
  for (const Cut& cut : cuts) {
    if (tried == most) break;
    // Of the halving cuts, the first that gives quads of kReflexHalveBelow or more.
    if (cut.halves && best && best->min_jacobian >= kReflexHalveBelow) break;
    const std::pair<std::uint32_t, std::uint32_t> key = std::minmax(cut.r, cut.t);
    if (std::find(done.begin(), done.end(), key) != done.end()) continue;
    done.push_back(key);
    ++tried;
    const std::uint32_t r = cut.r, t = cut.t, gap = (t + n - r) % n;
    const double h = 0.25 * (edge(r) + edge((r + n - 1) % n) + edge(t) + edge((t + n - 1) % n));
    // Inner nodes k: gap + k + 1 even, spacing nearest h in ratio.
    auto spacing_error = [&](std::int64_t k) { return std::abs(std::log(cut.length / static_cast<double>(k + 1) / h)); };
    std::int64_t k = std::max<std::int64_t>(0, std::llround(cut.length / h) - 1);
    if ((gap + k + 1) % 2 != 0) k = k == 0 || spacing_error(k + 1) < spacing_error(k - 1) ? k + 1 : k - 1;
    Builder m(face, FillKind::Reflex);
    std::vector<std::uint32_t> chord;  // from t to r, inner nodes only
    for (std::int64_t i = 1; i <= k; ++i)
      chord.push_back(m.add(lerp(p[t], p[r], static_cast<double>(i) / static_cast<double>(k + 1))));
    bool ok = true;
    for (int piece = 0; piece < 2 && ok; ++piece) {
      // Piece 0: r .. t along the cycle, then the chord back; piece 1: t .. r, then the chord.
      const std::uint32_t from = piece == 0 ? r : t, to = piece == 0 ? t : r;
      std::vector<std::uint32_t> ids;
      for (std::uint32_t i = from;; i = (i + 1) % n) {
        ids.push_back(i);
        if (i == to) break;
      }
      const auto mark = static_cast<std::uint32_t>(ids.size() - 1);  // first chord edge
      if (piece == 0) ids.insert(ids.end(), chord.begin(), chord.end());
      else ids.insert(ids.end(), chord.rbegin(), chord.rend());
      FaceInput sub;
      for (std::uint32_t id : ids) sub.cycle.push_back(m.pos(id));
      if (sub.cycle.size() < 4 || sub.cycle.size() % 2 != 0) {
        ok = false;
        break;
      }
      sub.sides = piece_sides(sub.cycle, mark);
      // A piece with neither four corners nor a reflex corner to cut again (within the
      // depth) is no better read than the whole face: no cut.
      if (sub.sides.size() != 4 && (depth + 1 > kReflexCutDepth || !has_reflex(sub.cycle))) {
        ok = false;
        break;
      }
      const std::optional<FaceMesh> filled = fill_any(sub, depth + 1);
      if (!filled || !(filled->min_jacobian > kMinValidJacobian)) {
        ok = false;
        break;
      }
      m.embed(*filled, ids);
      // The whole face's score is the least of its quads' (face_score): piece 0's quads
      // already bound it, and a chord that cannot reach the best one's quantised worst need
      // not fill piece 1 (the choice, hence the quads, are the same).
      if (piece == 0 && best &&
          quantised(face_score(m.out.quads, [&](std::uint32_t i) { return m.pos(i); }, face)) <
              quantised(best->min_jacobian)) {
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    FaceMesh out = m.finish();
    const double shape = whole_steps(mean_shape(out, face), kShapeStep);
    if (!best || quantised(out.min_jacobian) > quantised(best->min_jacobian) ||
        (quantised(out.min_jacobian) == quantised(best->min_jacobian) && shape > best_shape)) {
      best = std::move(out);
      best_shape = shape;
    }
  }
  return best;
}

/// Sided (session 28): a face of three or five corners (polygon_corners, as corner_strip
/// reads them) is that many grids round one inner node (sided_fill, the regrid's), placed
/// harmonically (kSidedSweeps) and relaxed. A wedge whose two long sides meet at the axis gets
/// one quad at its apex: cgal_wheel_16_spokes' hub at 1.25 x its size is 16 such wedges of
/// 22.5 degrees, and split put two quads at each apex (0.195), 32 round the hub's centre.
constexpr int kSidedSweeps = 100;

std::optional<FaceMesh> fill_sided(const FaceInput& face) {
  const std::optional<std::vector<std::uint32_t>> corners = polygon_corners(face.cycle);
  if (!corners || (corners->size() != 3 && corners->size() != 5)) return std::nullopt;
  std::vector<int> turn(face.cycle.size(), 0);
  for (std::uint32_t k : *corners) turn[k] = 1;
  std::optional<TurnFill> fill = sided_fill(turn);
  if (!fill) return std::nullopt;
  place_harmonic(*fill, face.cycle, kSidedSweeps);
  Builder m(face, FillKind::Sided);
  for (const Vec2& p : fill->interior) m.add(p);
  for (const auto& q : fill->quads) m.quad(q[0], q[1], q[2], q[3]);
  FaceMesh r = m.finish();
  relax(r, face, 30);
  return r;
}

/// Fan split only for faces of at most this many nodes: one fan round one point suits a small
/// star-shaped face (an L), and in larger faces it never won but cost a fifth of the quads
/// and re-fill stages (cgal_wiggly_03_cgal 0.262 -> 0.236 s, cover_bosses 0.172 -> 0.147 s;
/// of the 20 parts at 1x-3x and adaptive and the 217 generated parts at two sizes and
/// adaptive, 16 meshes changed: worst corner higher on 5, lower on none).
constexpr std::size_t kFanSplitMax = 24;

/// A lattice split of a face of more than kHugeFace nodes whose worst corner is below
/// kAcceptJacobian has its worst quads re-filled as the re-fill does a patch's (refill_face,
/// docs/mesher.md "Huge faces"). Its coarse polygon is every other face node, so a reflex
/// node of the other parity has two quads, each with a corner of half its angle (340 degrees:
/// two corners of 170), and a coarse triangle at a sharp corner can take a flat node between
/// two coarse ones as a corner of 180 degrees; a face of hundreds of nodes has a few of
/// either, and until session 50 its lattice lost to the match (0.1-1 s a face, mean shape
/// 0.85-0.92 against the lattice's 0.95-0.99). The repaired quads replace m when their worst
/// corner is acceptable and no whole kChoiceStep below `best_worst`, the best of the templates
/// before (as the match's must be: match_ok); true then. The re-fill's own fills go through
/// fill_cavity, whose templates are never a huge face's (pick_unstructured without `fans`),
/// so no repair runs inside another.
bool repair_lattice(const FaceInput& face, FaceMesh& m, double best_worst) {
  FaceMesh repaired = m;
  if (refill_face(face.cycle, repaired, kAcceptJacobian, kFaceRefillSweeps) == 0) return false;
  const std::size_t n = face.cycle.size();
  repaired.min_jacobian = face_score(
      repaired.quads, [&](std::uint32_t i) { return i < n ? face.cycle[i] : repaired.interior[i - n]; },
      face);
  if (repaired.min_jacobian < kAcceptJacobian || quantised(repaired.min_jacobian) < best_worst) return false;
  m = std::move(repaired);
  return true;
}

/// In a face of more than kHugeFace nodes the lattice splits are tried first, and the split
/// (O(n^3) in the nodes) and the match (a constrained Delaunay refinement and a matching: up
/// to a second on a face of 900 nodes) only when no acceptable quads so far have a mean shape
/// (mean_shape) of kHugeFaceShape or more, and, where those quads are a repaired lattice's,
/// a worst corner of kRepairedSure or more: on such faces they never won (cgal_wiggly_03_cgal
/// at --size 2.5: its quads stage 7.4 -> 2.9 s on one thread, the same mesh). A repaired
/// lattice wins on mean shape only among quads of its own kChoiceStep of worst corner: the
/// teeth of a ragged side leave it acceptable but below a match's (0.34 against 0.41).
constexpr double kHugeFaceShape = 0.9;
constexpr double kRepairedSure = 0.5;

double sharpest_sine(const std::vector<Vec2>& cycle);

/// Whether the match template's quads may compete (kMatchMinNodes, kMatchSmallFloor,
/// kMatchMoreQuads): its worst corner no whole kChoiceStep below the best acceptable one so far,
/// no more quads than allowed against the pick so far, and in a small face a worst corner of
/// kMatchSmallFloor or more.
bool match_ok(const FaceMesh& m,
              const FaceInput& face,
              const std::optional<FaceMesh>& pick,
              double best_worst) {
  const bool small = face.cycle.size() < kMatchMinNodes;
  if (small && m.min_jacobian < kMatchSmallFloor) return false;
  if (quantised(m.min_jacobian) < best_worst) return false;
  return !pick || static_cast<double>(m.quads.size()) <=
                      kMatchMoreQuads * static_cast<double>(pick->quads.size());
}

/// The reflex cut (recursive: each of its cuts fills both pieces with every template) is not
/// tried once a template before it gave quads whose worst corner is this good or better
/// (quantised): it then hardly ever won, on mean shape alone. cover_bosses' 56-node face took
/// 49 ms on one thread, 42 of them in the cut; with the rule its quads stage 0.054 -> 0.048 s.
/// Of the 277 set meshes (the 20 parts at 1x and 2x, adaptive; the 217 generated parts) 266
/// were the same to the byte; of the 11 others the worst corner was higher on 2, lower on none.
constexpr double kReflexSkipAbove = 0.8;

/// The unstructured templates (split and fan split from either parity, cut; with `fans` (not
/// in a cavity) also the reflex cut (unless kReflexSkipAbove), the lattice split from either
/// parity and the match, fan split only for faces of at most kFanSplitMax nodes); of those whose
/// worst corner is acceptable, the one whose quads are best on average (mean_shape, in whole
/// kShapeStep steps, the first on ties); the match only where match_ok allows. In a face of
/// more than kHugeFace nodes the lattice comes first, repaired where its worst corner is below
/// acceptable (repair_lattice), and the split and the match are skipped after a pick of mean
/// shape kHugeFaceShape. `consider` sees every result but a match that match_ok refuses.
template <class Consider>
std::optional<FaceMesh> pick_unstructured(const FaceInput& face, bool fans, int depth, Consider&& consider) {
  std::optional<FaceMesh> pick;
  double pick_shape = 0.0, best_worst = -1e9;
  bool pick_repaired = false;
  const bool huge = fans && face.cycle.size() > kHugeFace;
  constexpr int kHugeOrder[9] = {6, 7, 0, 1, 2, 3, 4, 5, 8};
  // No template's worst corner is above the sine of the face's sharpest corner.
  const double outline_bound = huge ? quantised(sharpest_sine(face.cycle)) : 0.0;
  for (int step = 0; step < 9; ++step) {
    const int k = huge ? kHugeOrder[step] : step;
    if (!fans && (k == 2 || k == 3 || k >= 5)) continue;
    if (huge && (k < 2 || k == 8) && pick && pick_shape >= whole_steps(kHugeFaceShape, kShapeStep) &&
        (!pick_repaired || pick->min_jacobian >= kRepairedSure ||
         quantised(pick->min_jacobian) >= outline_bound))
      continue;
    if ((k == 2 || k == 3) && face.cycle.size() > kFanSplitMax) continue;
    if (k == 5 && best_worst >= quantised(kReflexSkipAbove)) continue;
    std::optional<FaceMesh> m = k < 2   ? fill_split(face, static_cast<std::uint32_t>(k))
                                : k < 4 ? fill_fan_split(face, static_cast<std::uint32_t>(k - 2))
                                : k < 5 ? fill_cut(face)
                                : k < 6 ? fill_reflex(face, depth)
                                : k < 8 ? fill_lattice(face, static_cast<std::uint32_t>(k - 6))
                                        : fill_match(face);
    const bool repaired = huge && (k == 6 || k == 7) && m && m->min_jacobian < kAcceptJacobian &&
                          repair_lattice(face, *m, best_worst);
    if (k == 8 && m && !match_ok(*m, face, pick, best_worst)) continue;
    if (m && m->min_jacobian >= kAcceptJacobian) {
      best_worst = std::max(best_worst, quantised(m->min_jacobian));
      const double shape = whole_steps(mean_shape(*m, face), kShapeStep);
      // A repaired lattice against quads a whole step better or worse in their worst corner.
      const double qm = quantised(m->min_jacobian), qp = pick ? quantised(pick->min_jacobian) : qm;
      const bool better = !pick || (pick_repaired && qm > qp) || (shape > pick_shape && !(repaired && qm < qp));
      if (better) {
        pick = *m;
        pick_shape = shape;
        pick_repaired = repaired;
      }
    }
    consider(std::move(m));
  }
  return pick;
}

/// The best template so far. A later one must be better by a whole kChoiceStep: relaxation is
/// sensitive to the last bits of the input, and a choice between two nearly equal templates
/// would otherwise differ between poses of one part (and with it the element count).
struct BestFill {
  explicit BestFill(const FaceInput& face) : face_(&face) {}
  const FaceInput* face_;
  std::optional<FaceMesh> best;
  double best_shape = -1.0;  ///< best's mean_shape in steps, once computed (else -1)
  /// Takes m if it is better; true once the best is acceptable.
  bool consider(std::optional<FaceMesh> m, int depth) {
    static const bool debug = std::getenv("LAYTRACKS_DEBUG_FACE") != nullptr;
    if (debug && m) std::fprintf(stderr, "  [%d] %s J=%g\n", depth, to_string(m->kind), m->min_jacobian);
    if (!m) return best && best->min_jacobian >= kAcceptJacobian;
    const auto take = [&](double shape) {
      best = std::move(m);
      best_shape = shape;
    };
    if (!best) {
      take(-1.0);
    } else {
      const double qm = quantised(m->min_jacobian), qb = quantised(best->min_jacobian);
      // Within a step, quads no better than kLastResortJacobian (a corner of 0: three nodes on
      // a line, or +-1e-17 by rounding) lose to quads above it: 0 and 0.0007 share the step
      // [0, 0.05), and the first found stayed (fuzz seed 80080's split_056: a comb of spikes
      // whose split gave 0 and whose pairs 6.9e-4, refused at every size). The bar, not 0,
      // divides them: a flat corner is 0 in one pose and 1e-17 in another.
      const bool passes_bar =
          m->min_jacobian > kLastResortJacobian && !(best->min_jacobian > kLastResortJacobian);
      if (qm > qb || (qm == qb && passes_bar)) {
        take(-1.0);
      } else if (qm == qb && best->min_jacobian < kAcceptJacobian &&
                 m->min_jacobian > kMinValidJacobian && face_->cycle.size() > kLargeFace) {
        if (best_shape < 0.0) best_shape = whole_steps(mean_shape(*best, *face_), kShapeStep);
        const double shape = whole_steps(mean_shape(*m, *face_), kShapeStep);
        if (shape > best_shape) take(shape);
      }
    }
    return best && best->min_jacobian >= kAcceptJacobian;
  }
};

/// Every template in turn; the first good one, else the best.
std::optional<FaceMesh> fill_any(const FaceInput& face, int depth) {
  const std::size_t n = face.cycle.size();
  BestFill b(face);
  auto consider = [&](std::optional<FaceMesh> m) { return b.consider(std::move(m), depth); };
  const std::optional<FaceMesh>& best = b.best;
  const std::vector<Strip> strips = strips_of(face);
  for (const Strip& st : strips)
    if (consider(fill_grid(face, st))) return best;
  for (const Strip& st : strips)
    if (consider(fill_diamond(face, st))) return best;
  for (const Strip& st : strips)
    if (consider(fill_three(face, st))) return best;
  if (n == 4) {
    if (consider(fill_quad(face))) return best;
    if (consider(fill_ring(face))) return best;
  }
  for (const Strip& st : strips)
    if (consider(fill_rows(face, st, depth))) return best;
  bool strip_ok = false;
  for (const Strip& st : strips)
    if (consider(fill_strip(face, st, depth))) {
      strip_ok = true;
      break;
    }
  // A taper may still be a whole kChoiceStep better than an acceptable strip (whose remainder
  // the lattice template fills well enough to be accepted: 0.35 against the taper's 0.42).
  for (const Strip& st : strips)
    if (consider(fill_taper(face, st, depth)) && !strip_ok) return best;
  if (strip_ok) return best;
  // Read by its corners instead of its sides (a face whose rails bend, or a remainder).
  for (FaceMesh& g : corner_grids(face))
    if (consider(std::move(g))) return best;
  if (const std::optional<Strip> st = corner_strip(face.cycle, 0))
    if (consider(fill_three(face, *st))) return best;
  if (consider(fill_arms(face, depth))) return best;
  if (consider(fill_ogrid(face))) return best;
  // The O(n^3) templates only for small faces, or when nothing structured gave valid quads.
  const bool costly_ok = n <= kLargeFace || !best ||
                         best->min_jacobian < (n <= kHugeFace ? kLargeFaceFloor : kHugeFaceFloor);
  if (n >= 6 && costly_ok) {
    std::optional<FaceMesh> pick = pick_unstructured(face, true, depth, consider);
    if (pick) return pick;
  }
  // Grids round one node where no template so far gave acceptable quads (taken earlier, as
  // three grids are from kThreeFloor, they changed 24 of the 323 set meshes, adaptive
  // cgal_sample_0's worst corner 0.530 -> 0.286).
  consider(fill_sided(face));
  // Pairs, O(n^3) and all its corners on the face's nodes, in a large face only when nothing
  // valid came before: on the sets it never won there over a valid fill, and cgal_wiggly_03_cgal
  // at 5x finer spent 0.9 of its 4.2 s in it.
  const bool pairs_ok = n <= kLargeFace || !best || best->min_jacobian < kMinValidJacobian;
  if (n >= 4 && costly_ok && pairs_ok) consider(fill_pairs(face));
  return best;
}

}  // namespace

namespace {

/// The least worst corner fill_face accepts from its best template: kLastResortJacobian, or
/// kNeedleShare x the sine of the face's sharpest corner where that is the smaller (a face
/// whose outline has a needle's tip, a boundary corner of a thousandth of a degree on a
/// fuzzed sawtooth: every quad at that node has that corner, so no template can do better
/// than its sine), never below kDegenerateJacobian.
/// The least sine of a corner of the cycle of at most 90 degrees (1 when none is).
double sharpest_sine(const std::vector<Vec2>& cycle) {
  double sharpest = 1.0;
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    const double a = interior_angle(cycle, i);
    if (a < 0.5 * kPi) sharpest = std::min(sharpest, std::sin(a));
  }
  return sharpest;
}

double last_resort_jacobian(const std::vector<Vec2>& cycle) {
  return std::max(kDegenerateJacobian,
                  std::min(kLastResortJacobian, kNeedleShare * sharpest_sine(cycle)));
}

}  // namespace

std::optional<FaceMesh> fill_kites(const FaceInput& face) { return fill_cut(face, true); }

namespace {

/// FaceFillMemo's bound on what it holds (keys, nodes and quads), far above what it holds: the
/// peak memory of cyl_96_tri_rimfan (three attempts) grows 45.5 -> 45.7 MB with it, of the
/// tray at h = 0.25 (one attempt, 303,000 quads) 156.5 -> 156.8 MB.
constexpr std::size_t kFaceMemoBytes = std::size_t{64} << 20;

/// The bytes of everything the templates read of a face.
std::string face_key(const FaceInput& face) {
  std::string key;
  append_bytes(key, face.cycle.size());
  append_bytes(key, face.cycle);
  append_bytes(key, face.sides.size());
  for (const FaceSide& side : face.sides) {
    append_bytes(key, side.kind);
    append_bytes(key, side.first);
    append_bytes(key, side.edges);
    append_bytes(key, side.joints.size());
    append_bytes(key, side.joints);
  }
  append_bytes(key, face.free_nodes.size());
  for (bool f : face.free_nodes) key.push_back(f ? '1' : '0');
  return key;
}

/// set_face_fill_memo's switch and face_fill_memo_hits' count.
std::atomic<bool> g_face_memo_on{true};
std::atomic<std::size_t> g_face_memo_hits{0};

}  // namespace

struct FaceFillMemo::Held {
  LockedMemo<std::optional<FaceMesh>> answers{kFaceMemoBytes};
};

FaceFillMemo::FaceFillMemo() : held_(std::make_unique<Held>()) {}
FaceFillMemo::~FaceFillMemo() = default;

std::optional<FaceMesh> FaceFillMemo::fill(const FaceInput& face) {
  if (!g_face_memo_on) return fill_any(face, 0);
  std::string key = face_key(face);
  if (const auto known = held_->answers.find(key)) {
    ++g_face_memo_hits;
    return *known;
  }
  std::optional<FaceMesh> computed = fill_any(face, 0);
  if (!computed || (computed->kind != FillKind::Grid && computed->kind != FillKind::Quad)) {
    const std::size_t bytes =
        key.size() + (computed ? computed->interior.size() * sizeof(Vec2) +
                                     computed->quads.size() * sizeof(computed->quads[0])
                               : 0);
    held_->answers.insert(std::move(key), std::make_shared<const std::optional<FaceMesh>>(computed),
                          bytes);
  }
  return computed;
}

FaceMesh fill_face(const FaceInput& face,
                   const std::string& where,
                   bool needle_tips,
                   FaceFillMemo* memo) {
  const std::size_t n = face.cycle.size();
  if (n < 4 || n % 2 != 0) {
    throw InternalError("mesher: " + where + " has " + std::to_string(n) +
                        " boundary nodes; a face needs an even number, at least 4");
  }
  const std::optional<FaceMesh> best = memo ? memo->fill(face) : fill_any(face, 0);
  static const bool debug = std::getenv("LAYTRACKS_DEBUG_FACE") != nullptr;
  // The face's sides (R rail, B boundary: edges @ first node) and cycle, for debugging.
  const auto outline = [&](std::ostream& o, const char* gap) {
    o << gap << "sides:";
    for (const FaceSide& side : face.sides)
      o << " " << (side.kind == FaceSide::Kind::Rail ? "R" : "B") << side.edges << "@" << side.first;
    // Every bit of the nodes (tests/data/faces takes them as they are printed here).
    const std::streamsize was = o.precision(17);
    o << gap << "cycle:";
    for (const Vec2& p : face.cycle) o << " (" << p.x << "," << p.y << ")";
    o.precision(was);
  };
  if (debug && best) {  // after its templates' lines: which face, what won, and its outline
    std::ostringstream d;
    d << "face: " << where << " n=" << n << " -> " << to_string(best->kind) << " " << best->min_jacobian;
    outline(d, " ");
    std::fprintf(stderr, "%s\n", d.str().c_str());
  }
  // A face's own corner of sine s leaves no quad better than s there: a tip sharper than
  // kLastResortJacobian itself is taken at kSharpCornerShare x its sine (a lone needle of a
  // triangle, 2 long and 1e-5 wide: its tip's face is one quad of 1e-5, refused in every
  // attempt, and so was the part).
  const double bar =
      needle_tips ? last_resort_jacobian(face.cycle)
                  : std::min(kLastResortJacobian, kSharpCornerShare * sharpest_sine(face.cycle));
  if (best && best->min_jacobian > bar) return *best;
  // The needle-tip attempt's very last resort: cut, with kites (fill_cut). Only where every
  // template failed in the last attempt, so no part that meshed without it changes.
  if (needle_tips) {
    std::optional<FaceMesh> kites = fill_kites(face);
    if (debug && kites)
      std::fprintf(stderr, "face: %s kites %g\n", where.c_str(), kites->min_jacobian);
    if (kites && kites->min_jacobian > bar) return *kites;
  }
  std::ostringstream s;
  s << "mesher: no template gives valid quads in " << where << " (" << n
    << " boundary nodes, " << face.sides.size() << " sides";
  if (best) s << ", best corner scaled Jacobian " << best->min_jacobian;
  s << ")";
  if (debug) outline(s, "\n");
  throw InternalError(s.str());
}

Vec2 FaceMotion::apply(Vec2 p) const {
  Vec2 d = p - from_centre;
  if (mirrored) d.y = -d.y;
  return to_centre + Vec2{c * d.x - s * d.y, s * d.x + c * d.y};
}

namespace {

/// Per cycle node of a face: whether a side starts there, whether it is a joint of its rail
/// chain, whether it is free; and per edge (k to k + 1) whether it is a rail's.
struct NodeMarks {
  std::vector<bool> corner, joint, free, rail;
  explicit NodeMarks(const FaceInput& f) {
    const std::size_t n = f.cycle.size();
    corner.assign(n, false);
    joint.assign(n, false);
    rail.assign(n, false);
    free.assign(n, false);
    for (const FaceSide& side : f.sides) {
      corner[side.first % n] = true;
      for (std::uint32_t k = 0; k < side.edges; ++k)
        rail[(side.first + k) % n] = side.kind == FaceSide::Kind::Rail;
      for (std::uint32_t j : side.joints) joint[(side.first + j) % n] = true;
    }
    for (std::size_t k = 0; k < n && k < f.free_nodes.size(); ++k) free[k] = f.free_nodes[k];
  }
};

}  // namespace

std::optional<FaceMotion> face_motion(const FaceInput& from, const FaceInput& to, bool turned_only) {
  const std::size_t n = to.cycle.size();
  if (from.cycle.size() != n || from.sides.size() != to.sides.size() || n < 3) return std::nullopt;
  const NodeMarks a(from), b(to);
  const double inv_n = 1.0 / static_cast<double>(n);
  double mean_edge = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    mean_edge += distance(to.cycle[k], to.cycle[(k + 1) % n]) * inv_n;
  const double tolerance = kCongruentTolerance * mean_edge;
  Vec2 to_centre{0.0, 0.0}, from_centre{0.0, 0.0};
  for (std::size_t k = 0; k < n; ++k) {
    to_centre = to_centre + inv_n * to.cycle[k];
    from_centre = from_centre + inv_n * from.cycle[k];
  }
  // Only starts that put to's first side corner on one of from's (any start when it has none).
  std::size_t k0 = 0;
  while (k0 < n && !b.corner[k0]) ++k0;
  const bool cornered = k0 < n;
  if (!cornered) k0 = 0;
  FaceMotion m;
  m.node.resize(n);
  for (int mirrored = 0; mirrored < (turned_only ? 1 : 2); ++mirrored)
    for (std::size_t i0 = 0; i0 < n; ++i0) {
      if (cornered && !a.corner[i0]) continue;
      if (turned_only && i0 != k0) continue;  // node k0 onto node k0: every node onto itself
      // to's node k is from's node shift + k, or shift - k (mirrored: the cycle runs back);
      // node k0 is from's i0.
      const std::size_t shift = mirrored ? (i0 + k0) % n : (i0 + n - k0) % n;
      for (std::size_t k = 0; k < n; ++k)
        m.node[k] = static_cast<std::uint32_t>(mirrored ? (shift + n - k) % n : (shift + k) % n);
      bool same = true;
      for (std::size_t k = 0; k < n && same; ++k) {
        const std::uint32_t i = m.node[k];
        // to's edge k -> k + 1 is from's edge i -> i + 1, or i - 1 -> i when mirrored.
        const std::uint32_t edge = mirrored ? m.node[(k + 1) % n] : i;
        same = a.corner[i] == b.corner[k] && a.joint[i] == b.joint[k] && a.free[i] == b.free[k] &&
               a.rail[edge] == b.rail[k];
      }
      if (!same) continue;
      // The similarity fitted to the nodes about their centres (least squares, closed form).
      double dot_sum = 0.0, cross_sum = 0.0, norm_sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        Vec2 p = from.cycle[m.node[k]] - from_centre;
        if (mirrored) p.y = -p.y;
        const Vec2 q = to.cycle[k] - to_centre;
        dot_sum += dot(p, q);
        cross_sum += cross(p, q);
        norm_sum += dot(p, p);
      }
      if (!(norm_sum > 0.0)) continue;
      m.mirrored = mirrored != 0;
      m.from_centre = from_centre;
      m.to_centre = to_centre;
      m.c = dot_sum / norm_sum;
      m.s = cross_sum / norm_sum;
      for (std::size_t k = 0; k < n && same; ++k)
        same = distance(m.apply(from.cycle[m.node[k]]), to.cycle[k]) <= tolerance;
      if (same) return m;
    }
  return std::nullopt;
}

double leading_edge_key(const FaceInput& face) {
  const std::size_t n = face.cycle.size();
  if (n < 2) return 0.0;
  double perimeter = 0.0;
  for (std::size_t k = 0; k < n; ++k) perimeter += distance(face.cycle[k], face.cycle[(k + 1) % n]);
  const Vec2 first = face.cycle[1] - face.cycle[0];
  return perimeter > 0.0 ? dot(first, first) / (perimeter * perimeter) : 0.0;
}

double face_shape_key(const FaceInput& face) {
  const std::size_t n = face.cycle.size();
  if (n == 0) return 0.0;
  Vec2 centre{0.0, 0.0};
  for (const Vec2& p : face.cycle) centre = centre + (1.0 / static_cast<double>(n)) * p;
  double spread = 0.0, perimeter = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    spread += dot(face.cycle[k] - centre, face.cycle[k] - centre);
    perimeter += distance(face.cycle[k], face.cycle[(k + 1) % n]);
  }
  return perimeter > 0.0 ? spread / (perimeter * perimeter) : 0.0;
}

FaceMesh moved_fill(const FaceMesh& filled, const FaceInput& to, const FaceMotion& motion) {
  const auto n = static_cast<std::uint32_t>(to.cycle.size());
  std::vector<std::uint32_t> rename(n);  // from's cycle node -> to's
  for (std::uint32_t k = 0; k < n; ++k) rename[motion.node[k]] = k;
  FaceMesh out;
  out.kind = filled.kind;
  for (const Vec2& p : filled.interior) out.interior.push_back(motion.apply(p));
  for (const auto& q : filled.quads) {
    std::array<std::uint32_t, 4> r{};
    for (std::size_t i = 0; i < 4; ++i) r[i] = q[i] < n ? rename[q[i]] : q[i];
    if (motion.mirrored) std::swap(r[1], r[3]);
    out.quads.push_back(r);
  }
  const auto pos = [&](std::uint32_t i) { return i < n ? to.cycle[i] : out.interior[i - n]; };
  out.min_jacobian = face_score(out.quads, pos, to);
  return out;
}

std::optional<FaceMesh> fill_cavity(const FaceInput& face) {
  const std::size_t n = face.cycle.size();
  if (n < 4 || n % 2 != 0) return std::nullopt;
  struct NoRelax {
    NoRelax() { relax_off = true; }
    ~NoRelax() { relax_off = false; }
  } no_relax;
  BestFill b(face);
  auto consider = [&](std::optional<FaceMesh> m) { return b.consider(std::move(m), 0); };
  if (n == 4) {
    if (consider(fill_quad(face))) return b.best;
    if (consider(fill_ring(face))) return b.best;
  }
  for (FaceMesh& g : corner_grids(face))
    if (consider(std::move(g))) return b.best;
  if (n >= 6) {
    // No fan split: its 60 untangling sweeps cost half the re-fill's time, and without it the
    // 20 parts' worst quads were as good or better (cgal_wheel_16_spokes 0.747 -> 0.779).
    std::optional<FaceMesh> pick = pick_unstructured(face, false, 0, consider);
    if (pick) return pick;
  }
  if (!b.best || b.best->min_jacobian < kAcceptJacobian) consider(fill_pairs(face));
  if (b.best && b.best->min_jacobian > kMinValidJacobian) return b.best;
  return std::nullopt;
}

}  // namespace laytracks::mesher_detail

namespace laytracks {

void set_face_fill_memo(bool on) { mesher_detail::g_face_memo_on = on; }

std::size_t face_fill_memo_hits() { return mesher_detail::g_face_memo_hits; }

}  // namespace laytracks
