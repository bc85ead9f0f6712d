#include "laytracks/io/medial_output.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "laytracks/io/svg.hpp"

namespace laytracks {

void write_medial_json(std::ostream& out, const Part& part, const std::vector<MedialAxis>& axes) {
  nlohmann::ordered_json doc;
  doc["units"] = part.units;
  auto& patches = doc["patches"] = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < axes.size(); ++p) {
    const Frame& f = part.patches[p].frame;
    nlohmann::ordered_json jp;
    jp["name"] = part.patches[p].name;
    auto& verts = jp["vertices"] = nlohmann::ordered_json::array();
    for (const MaVertex& v : axes[p].vertices()) {
      const Vec3 x = f.to_3d(v.position);
      verts.push_back({{"xyz", {x.x, x.y, x.z}}, {"radius", v.radius}, {"degree", v.degree}});
    }
    auto& edges = jp["edges"] = nlohmann::ordered_json::array();
    for (const MaEdge& e : axes[p].edges()) edges.push_back({e.a.index(), e.b.index()});
    patches.push_back(std::move(jp));
  }
  out << doc.dump(1) << '\n';
}

void write_medial_svg(std::ostream& out, const Part& part, const std::vector<MedialAxis>& axes) {
  const std::size_t n = axes.size();
  const std::size_t cols = std::max<std::size_t>(
      1, std::min<std::size_t>(n, static_cast<std::size_t>(std::ceil(std::sqrt(double(n))))));
  const std::size_t rows = (n + cols - 1) / cols;
  const double cell = n == 1 ? 640.0 : 360.0;
  const double title = 24.0;
  const double legend = 40.0;
  SvgDocument svg(cell * static_cast<double>(cols),
                  (cell + title) * static_cast<double>(rows) + legend);
  double max_radius = 0.0;
  for (const auto& ma : axes) {
    for (const auto& v : ma.vertices()) max_radius = std::max(max_radius, v.radius);
  }
  for (std::size_t p = 0; p < n; ++p) {
    const MedialAxis& ma = axes[p];
    const double x0 = cell * static_cast<double>(p % cols);
    const double y0 = (cell + title) * static_cast<double>(p / cols);
    Box2 box;
    for (const auto& loop : ma.polygon().loops) {
      for (Vec2 q : loop) box.add(q);
    }
    const Panel panel(box, x0, y0 + title, cell, cell, 16.0);
    svg.text({x0 + 8, y0 + 18},
             part.patches[p].name + "  (" + std::to_string(ma.branch_points().size()) +
                 " branch points)",
             14.0);
    for (const auto& loop : ma.polygon().loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(panel.map(q));
      svg.polyline(pts, "#222", 1.5, true, "#f4f1ea");
    }
    const double chord = 2.0 / panel.scale();  // about 2 px
    for (std::size_t e = 0; e < ma.edges().size(); ++e) {
      std::vector<Vec2> pts;
      for (Vec2 q : ma.sample_edge(MaEdgeId(e), chord)) pts.push_back(panel.map(q));
      const MaEdge& me = ma.edges()[e];
      const double r = 0.5 * (ma.vertex(me.a).radius + ma.vertex(me.b).radius);
      svg.polyline(pts, ramp_colour(max_radius > 0 ? r / max_radius : 0.0), 2.0);
    }
    for (MaVertexId b : ma.branch_points()) {
      svg.circle(panel.map(ma.vertex(b).position), 3.5, "#d62728", "white");
    }
    if (ma.edges().empty()) {
      for (const auto& v : ma.vertices())
        svg.circle(panel.map(v.position), 3.5, "#d62728", "white");
    }
  }
  // Legend: the radius ramp and the branch-point marker.
  const double ly = (cell + title) * static_cast<double>(rows) + 8.0;
  for (int i = 0; i < 100; ++i) {
    svg.rect({10.0 + 2.0 * i, ly}, {12.0 + 2.0 * i, ly + 12.0}, ramp_colour(i / 99.0), "none");
  }
  char label[96];
  std::snprintf(label, sizeof label, "radius 0 .. %.4g %s", max_radius, part.units.c_str());
  svg.text({216.0, ly + 11.0}, label, 12.0);
  svg.circle({430.0, ly + 6.0}, 3.5, "#d62728", "white");
  svg.text({440.0, ly + 11.0}, "branch point", 12.0);
  out << svg.str();
}

}  // namespace laytracks
