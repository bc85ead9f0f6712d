// The quad measures of ../shared/spec/quality.md and the summary figures of a whole mesh.
#include "laytracks/mesher/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "laytracks/mesher/check.hpp"
#include "patch_quads.hpp"

namespace laytracks {
namespace {

constexpr double kDeg = 180.0 / kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The angle between two vectors in degrees, [0, 180]; 0 when either is zero.
double angle_between(Vec3 a, Vec3 b) {
  if (dot(a, a) == 0.0 || dot(b, b) == 0.0) return 0.0;
  return std::atan2(norm(cross(a, b)), dot(a, b)) * kDeg;
}

}  // namespace

QuadQuality measure_quad(const std::array<Vec3, 4>& corners, Vec3 normal) {
  const Vec3 n = normalized(normal);
  const Vec3 c = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
  // Corners relative to the centroid (translation invariance), then projected on the plane.
  std::array<Vec3, 4> r{};
  std::array<Vec3, 4> q{};
  for (std::size_t i = 0; i < 4; ++i) {
    r[i] = corners[i] - c;
    q[i] = r[i] - dot(r[i], n) * n;
  }
  QuadQuality out;

  std::array<double, 4> len{};
  for (std::size_t i = 0; i < 4; ++i) len[i] = norm(q[(i + 1) % 4] - q[i]);
  const double longest = *std::max_element(len.begin(), len.end());
  const double shortest = *std::min_element(len.begin(), len.end());
  out.edge_ratio = shortest > 0.0 ? longest / shortest : kInf;

  // Corner i: a = P(i+1) - Pi (along edge i), b = P(i-1) - Pi (back along edge i-1).
  std::array<double, 4> area{};
  double jacobian = kInf;
  double min_angle = kInf;
  double max_angle = -kInf;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t prev = (i + 3) % 4;
    const Vec3 a = q[(i + 1) % 4] - q[i];
    const Vec3 b = q[prev] - q[i];
    const double turn = dot(n, cross(a, b));
    area[i] = 0.5 * turn;
    double sj = 0.0;
    double angle = 0.0;
    if (len[i] > 0.0 && len[prev] > 0.0) {
      sj = std::clamp(turn / (len[i] * len[prev]), -1.0, 1.0);
      angle = std::atan2(turn, dot(a, b)) * kDeg;
      if (angle < 0.0) angle += 360.0;
    }
    jacobian = std::fmin(jacobian, sj);
    min_angle = std::fmin(min_angle, angle);
    max_angle = std::fmax(max_angle, angle);
  }
  out.scaled_jacobian = jacobian;
  out.min_angle_deg = min_angle;
  out.max_angle_deg = max_angle;

  const double mean_area = 0.25 * (area[0] + area[1] + area[2] + area[3]);
  const double min_area = *std::min_element(area.begin(), area.end());
  out.taper = mean_area > 0.0 ? min_area / mean_area : -kInf;

  // Midlines d1 = M23 - M41 and d2 = M34 - M12.
  const Vec3 d1 = 0.5 * ((q[1] + q[2]) - (q[3] + q[0]));
  const Vec3 d2 = 0.5 * ((q[2] + q[3]) - (q[0] + q[1]));
  const double l1 = norm(d1);
  const double l2 = norm(d2);
  if (l1 > 0.0 && l2 > 0.0) {
    // The acute angle between the two lines, in [0, 90].
    const double acute = std::atan2(norm(cross(d1, d2)), std::fabs(dot(d1, d2))) * kDeg;
    out.skew_deg = std::fmax(0.0, 90.0 - acute);
    out.aspect_ratio = std::fmax(l1, l2) / std::fmin(l1, l2);
  } else {
    out.skew_deg = 90.0;
    out.aspect_ratio = kInf;
  }

  // Warp on the corners as given: the two triangles beside each diagonal, both turning the
  // quad's way round.
  const Vec3 t013 = cross(r[1] - r[0], r[2] - r[0]);  // (P1, P2, P3)
  const Vec3 t023 = cross(r[2] - r[0], r[3] - r[0]);  // (P1, P3, P4)
  const Vec3 t124 = cross(r[2] - r[1], r[3] - r[1]);  // (P2, P3, P4)
  const Vec3 t142 = cross(r[3] - r[1], r[0] - r[1]);  // (P2, P4, P1)
  out.warp_deg = std::fmax(angle_between(t013, t023), angle_between(t124, t142));

  bool finite = true;
  for (const Vec3& p : corners) finite = finite && is_finite(p);
  out.inverted = !finite || !(out.scaled_jacobian > 0.0);
  return out;
}

QuadQuality measure_planar_quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const auto lift = [](Vec2 p) { return Vec3{p.x, p.y, 0.0}; };
  return measure_quad({lift(a), lift(b), lift(c), lift(d)}, Vec3{0.0, 0.0, 1.0});
}

bool beyond_table_iii(const QuadQuality& m) {
  return m.taper <= QualityThresholds::kTaper || m.skew_deg >= QualityThresholds::kSkewDeg ||
         m.aspect_ratio >= QualityThresholds::kAspectRatio;
}

namespace {

/// The value of measure m (in QualitySummary::measures order) of a quad.
double value_of(const QuadQuality& q, std::size_t m) {
  switch (m) {
    case 0:
      return q.skew_deg;
    case 1:
      return q.aspect_ratio;
    case 2:
      return q.taper;
    case 3:
      return q.warp_deg;
    case 4:
      return q.min_angle_deg;
    case 5:
      return q.max_angle_deg;
    case 6:
      return q.scaled_jacobian;
    default:
      return q.edge_ratio;
  }
}

struct MeasureDef {
  const char* name;
  const char* bad_when;
  bool higher_is_worse;
  std::vector<double> bins;
  bool (*bad)(double);
};

/// count bounds (from + i step) / denom, computed so that 0.3 is the double nearest 0.3.
std::vector<double> steps(int from, int step, int count, double denom = 1.0) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(static_cast<double>(from + step * i) / denom);
  return v;
}

const std::array<MeasureDef, 8>& measure_defs() {
  using T = QualityThresholds;
  static const std::vector<double> ratio_bins{1.0, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0};
  static const std::array<MeasureDef, 8> defs{{
      {"skew_deg", ">= 30", true, steps(0, 5, 18), [](double v) { return v >= T::kSkewDeg; }},
      {"aspect_ratio", ">= 5", true, ratio_bins, [](double v) { return v >= T::kAspectRatio; }},
      {"taper", "<= 0.8", false, steps(0, 1, 10, 10.0), [](double v) { return v <= T::kTaper; }},
      {"warp_deg",
       ">= 10",
       true,
       {0.0, 1.0, 2.0, 5.0, 10.0, 20.0, 45.0, 90.0},
       [](double v) { return v >= T::kWarpDeg; }},
      {"min_angle_deg", "< 45", false, steps(0, 5, 37),
       [](double v) { return v < T::kMinAngleDeg; }},
      {"max_angle_deg", "> 135", true, steps(0, 5, 37),
       [](double v) { return v > T::kMaxAngleDeg; }},
      {"scaled_jacobian", "<= 0.2", false, steps(-10, 1, 20, 10.0),
       [](double v) { return v <= T::kScaledJacobian; }},
      {"edge_ratio", ">= 5", true, ratio_bins, [](double v) { return v >= T::kEdgeRatio; }},
  }};
  return defs;
}

/// The q-quantile of v (linear between closest ranks); v is reordered.
double percentile(std::vector<double>& v, double q) {
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto k = static_cast<std::size_t>(std::floor(pos));
  const double frac = pos - static_cast<double>(k);
  const auto kth = v.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(v.begin(), kth, v.end());
  const double lo = *kth;
  if (frac == 0.0 || k + 1 >= v.size()) return lo;
  const double hi = *std::min_element(kth + 1, v.end());
  return lo == hi ? lo : lo + frac * (hi - lo);
}

MeasureSummary summarize_measure(const MeasureDef& def, std::vector<double>& values) {
  MeasureSummary s;
  s.name = def.name;
  s.bad_when = def.bad_when;
  s.histogram.lower_bounds = def.bins;
  s.histogram.counts.assign(def.bins.size(), 0);
  if (values.empty()) return s;
  double sum = 0.0;
  double worst = values[0];
  std::size_t bad = 0;
  for (double v : values) {
    sum += v;
    worst = def.higher_is_worse ? std::fmax(worst, v) : std::fmin(worst, v);
    if (def.bad(v)) ++bad;
    const auto it = std::upper_bound(def.bins.begin(), def.bins.end(), v);
    const std::size_t bin =
        it == def.bins.begin() ? 0 : static_cast<std::size_t>(it - def.bins.begin()) - 1;
    ++s.histogram.counts[bin];
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.worst = worst;
  s.bad_percent = 100.0 * static_cast<double>(bad) / n;
  s.p5 = percentile(values, 0.05);
  s.p95 = percentile(values, 0.95);
  return s;
}

}  // namespace

QualitySummary summarize(const Part& part, const QuadMesh& mesh) {
  QualitySummary out;
  out.elements = mesh.elements.size();
  out.nodes = mesh.nodes.size();
  // Each quad measured on its own (on all cores, in blocks), then gathered in element order.
  struct Measured {
    bool quad = false, ok = false;
    QuadQuality q{};
    double size = 0.0;
  };
  std::vector<Measured> measured(mesh.elements.size());
  constexpr std::size_t kBlock = 1024;
  mesher_detail::parallel_for((mesh.elements.size() + kBlock - 1) / kBlock, [&](std::size_t b) {
    const std::size_t last = std::min(mesh.elements.size(), (b + 1) * kBlock);
    for (std::size_t ei = b * kBlock; ei < last; ++ei) {
      const MeshElement& e = mesh.elements[ei];
      Measured& m = measured[ei];
      m.quad = e.is_quad();
      if (!m.quad) continue;
      bool ok = e.patch.index() < part.patches.size();
      std::array<Vec3, 4> corners{};
      for (std::size_t i = 0; i < 4 && ok; ++i) {
        ok = e.nodes[i] < mesh.nodes.size() && is_finite(mesh.nodes[e.nodes[i]]);
        if (ok) corners[i] = mesh.nodes[e.nodes[i]];
      }
      m.ok = ok;
      if (!ok) continue;
      const Vec3 normal = part.patches[e.patch.index()].frame.n;
      m.q = measure_quad(corners, normal);
      const double area = 0.5 * std::abs(dot(normal, cross(corners[2] - corners[0],
                                                           corners[3] - corners[1])));
      m.size = std::sqrt(area);
    }
  });
  std::array<std::vector<double>, 8> values;
  std::size_t bad_angle = 0;
  // Sizes of the measured quads, for the size grading.
  std::vector<double> size_of(mesh.elements.size(), 0.0);
  for (std::size_t ei = 0; ei < mesh.elements.size(); ++ei) {
    const Measured& got = measured[ei];
    if (!got.quad) {
      ++out.triangles;
      ++out.invalid_elements;
      continue;
    }
    ++out.quads;
    if (!got.ok) {
      ++out.invalid_elements;
      continue;
    }
    const QuadQuality& q = got.q;
    ++out.measured;
    size_of[ei] = got.size;
    out.min_size = out.measured == 1 ? size_of[ei] : std::min(out.min_size, size_of[ei]);
    out.max_size = std::max(out.max_size, size_of[ei]);
    if (q.inverted) ++out.invalid_elements;
    if (q.min_angle_deg < QualityThresholds::kMinAngleDeg ||
        q.max_angle_deg > QualityThresholds::kMaxAngleDeg) {
      ++bad_angle;
    }
    for (std::size_t m = 0; m < 8; ++m) values[m].push_back(value_of(q, m));
  }
  for (std::size_t m = 0; m < 8; ++m)
    out.measures[m] = summarize_measure(measure_defs()[m], values[m]);
  std::vector<double> sizes;
  for (std::size_t ei = 0; ei < mesh.elements.size(); ++ei)
    if (size_of[ei] > 0.0) sizes.push_back(size_of[ei]);
  if (!sizes.empty()) {
    std::sort(sizes.begin(), sizes.end());
    const std::size_t tenth = std::max<std::size_t>(1, sizes.size() / 10);
    double fine = 0.0, coarse = 0.0;
    for (std::size_t k = 0; k < tenth; ++k) {
      fine += sizes[k];
      coarse += sizes[sizes.size() - 1 - k];
    }
    out.fine_coarse_ratio = fine / coarse;
  }
  // Neighbours across each edge of the measured quads: consecutive uses of one edge compared,
  // in (edge, element) order, as a sort of all the edges would pair them.
  const mesher_detail::EdgesByNode edges = mesher_detail::edges_by_lower_node(
      mesh, [&](std::size_t ei) { return measured[ei].quad && measured[ei].ok; });
  std::vector<double> ratios;
  for (std::size_t a = 0; a + 1 < edges.start.size(); ++a) {
    const auto first = edges.uses.begin() + edges.start[a], last = edges.uses.begin() + edges.start[a + 1];
    for (auto i = first; i != last && i + 1 != last; ++i) {
      if (i->first != (i + 1)->first) continue;
      const double x = size_of[i->second], y = size_of[(i + 1)->second];
      if (x > 0.0 && y > 0.0) ratios.push_back(std::max(x, y) / std::min(x, y));
    }
  }
  if (!ratios.empty()) {
    std::sort(ratios.begin(), ratios.end());
    out.worst_neighbour_ratio = ratios.back();
    out.p95_neighbour_ratio = percentile(ratios, 0.95);
  }
  if (out.measured > 0) {
    out.bad_angle_percent =
        100.0 * static_cast<double>(bad_angle) / static_cast<double>(out.measured);
  }
  return out;
}

namespace {

nlohmann::ordered_json summary_json(const QualitySummary& summary, bool histograms) {
  using json = nlohmann::ordered_json;
  json j;
  j["elements"] = summary.elements;
  j["nodes"] = summary.nodes;
  j["quads"] = summary.quads;
  j["triangles"] = summary.triangles;
  j["invalid_elements"] = summary.invalid_elements;
  j["measured"] = summary.measured;
  j["bad_angle_percent"] = summary.bad_angle_percent;
  j["size"] = {{"min", summary.min_size},
               {"max", summary.max_size},
               {"fine_coarse_ratio", summary.fine_coarse_ratio},
               {"worst_neighbour_ratio", summary.worst_neighbour_ratio},
               {"p95_neighbour_ratio", summary.p95_neighbour_ratio}};
  json measures = json::object();
  for (const MeasureSummary& m : summary.measures) {
    json e;
    e["bad_when"] = m.bad_when;
    e["mean"] = m.mean;
    e["worst"] = m.worst;
    e["p5"] = m.p5;
    e["p95"] = m.p95;
    e["bad_percent"] = m.bad_percent;
    if (histograms) {
      e["histogram"]["lower_bounds"] = m.histogram.lower_bounds;
      e["histogram"]["counts"] = m.histogram.counts;
    }
    measures[m.name] = std::move(e);
  }
  j["measures"] = std::move(measures);
  return j;
}

}  // namespace

void write_quality_json(std::ostream& out, const QualitySummary& summary, bool histograms) {
  out << summary_json(summary, histograms).dump(2) << "\n";
}

void write_quality_json(std::ostream& out, const QualitySummary& summary, const MeshCheck& check,
                        bool histograms) {
  using json = nlohmann::ordered_json;
  json j = summary_json(summary, histograms);
  j["valid"] = check.valid();
  json counts = json::object();
  for (int rule = 1; rule <= 6; ++rule)
    counts[std::to_string(rule)] = check.counts[static_cast<std::size_t>(rule)];
  j["failure_counts"] = std::move(counts);
  json failures = json::array();
  for (const MeshFailure& f : check.failures)
    failures.push_back(json{{"rule", f.rule}, {"message", f.message}});
  j["failures"] = std::move(failures);
  out << j.dump(2) << "\n";
}

}  // namespace laytracks
