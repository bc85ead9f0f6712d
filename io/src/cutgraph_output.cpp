#include "laytracks/io/cutgraph_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "laytracks/io/svg.hpp"

namespace laytracks {
namespace {

/// A light colour for corridor i: hues spread by the golden angle.
std::string corridor_colour(std::size_t i) {
  const double h = std::fmod(static_cast<double>(i) * 137.508, 360.0);
  char buf[48];
  std::snprintf(buf, sizeof buf, "hsl(%.0f,70%%,72%%)", h);
  return buf;
}

/// Points of a loop from parameter u0 to u1 (u = segment + s, wrapping).
std::vector<Vec2> loop_piece(const std::vector<Vec2>& loop, double u0, double u1) {
  const std::size_t n = loop.size();
  const auto at = [&](double u) {
    double w = std::fmod(u, static_cast<double>(n));
    if (w < 0) w += static_cast<double>(n);
    const std::size_t i = std::min(static_cast<std::size_t>(w), n - 1);
    return lerp(loop[i], loop[(i + 1) % n], w - static_cast<double>(i));
  };
  std::vector<Vec2> pts{at(u0)};
  for (double k = std::floor(u0) + 1.0; k < u1; k += 1.0) pts.push_back(at(k));
  pts.push_back(at(u1));
  return pts;
}

}  // namespace

void write_rails_svg(std::ostream& out,
                     const Part& part,
                     const std::vector<MedialAxis>& axes,
                     const CutGraph& graph,
                     const std::string& title) {
  const std::size_t n = part.patches.size();
  const PatchGrid grid(n);
  SvgDocument svg(grid.width(), grid.height() + 30.0);
  std::vector<Panel> panels;
  for (std::size_t p = 0; p < n; ++p) {
    Box2 box;
    for (const auto& loop : part.patches[p].polygon.loops) {
      for (Vec2 q : loop) box.add(q);
    }
    panels.push_back(grid.panel(p, box));
    svg.text(grid.title_at(p), part.patches[p].name, 14.0);
    for (const auto& loop : part.patches[p].polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(panels[p].map(q));
      svg.polyline(pts, "none", 0.0, true, "#f4f1ea");
    }
  }
  for (const CorridorPiece& c : corridor_pieces(part, axes, graph)) {
    const auto& loop = part.patches[c.patch.index()].polygon.loops[c.loop];
    std::vector<Vec2> pts = loop_piece(loop, c.u0, c.u1);
    pts.push_back(c.ma1);
    pts.push_back(c.ma0);
    for (Vec2& q : pts) q = panels[c.patch.index()].map(q);
    svg.polyline(pts, "none", 0.0, true, corridor_colour(c.corridor));
  }
  for (std::size_t p = 0; p < n; ++p) {
    const MedialAxis& ma = axes[p];
    const double chord = 2.0 / panels[p].scale();
    for (std::size_t e = 0; e < ma.edges().size(); ++e) {
      std::vector<Vec2> pts;
      for (Vec2 q : ma.sample_edge(MaEdgeId(e), chord)) pts.push_back(panels[p].map(q));
      svg.polyline(pts, "#888", 1.0);
    }
    for (const auto& loop : part.patches[p].polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(panels[p].map(q));
      svg.polyline(pts, "#222", 1.5, true);
    }
  }
  for (const RailSegment& s : graph.segments) {
    const CutVert& c = graph.cuts[s.cut.index()];
    const Panel& panel = panels[c.patch.index()];
    const bool source = graph.macuts[s.ma.index()].branch;  // source rails meet branch points
    svg.polyline({panel.map(c.position), panel.map(graph.macuts[s.ma.index()].point.position)},
                 source ? "#d62728" : "#1f5fbf", source ? 1.4 : 0.8);
  }
  const double ly = grid.height() + 20.0;
  svg.text({10.0, ly}, title + ": source rails red, track rails blue, medial axis grey", 12.0);
  out << svg.str();
}

void write_rails_oblique_svg(std::ostream& out,
                             const Part& part,
                             const std::vector<MedialAxis>& axes,
                             const CutGraph& graph,
                             const std::string& title) {
  const ObliqueCamera cam;
  Box2 box;
  for (const BrepVertex& v : part.vertices) box.add(cam.screen(v.position));
  const double size = 900.0;
  SvgDocument svg(size, size + 30.0);
  const Panel panel(box, 0.0, 0.0, size, size, 24.0);
  const auto at = [&](PatchId p, Vec2 q) {
    return panel.map(cam.screen(part.patches[p.index()].frame.to_3d(q)));
  };
  // Patches far to near (painter's order by the depth of their centroids).
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    order.push_back({cam.depth(part.patches[p].frame.origin), p});
  }
  std::sort(order.begin(), order.end());
  const std::vector<CorridorPiece> pieces = corridor_pieces(part, axes, graph);
  for (const auto& [depth, p] : order) {
    (void)depth;
    const PatchId pid(p);
    for (const auto& loop : part.patches[p].polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(at(pid, q));
      svg.polyline(pts, "none", 0.0, true, "#f4f1ea");
    }
    for (const CorridorPiece& c : pieces) {
      if (c.patch != pid) continue;
      std::vector<Vec2> pts = loop_piece(part.patches[p].polygon.loops[c.loop], c.u0, c.u1);
      pts.push_back(c.ma1);
      pts.push_back(c.ma0);
      for (Vec2& q : pts) q = at(pid, q);
      svg.polyline(pts, "none", 0.0, true, corridor_colour(c.corridor));
    }
    for (const RailSegment& s : graph.segments) {
      const CutVert& c = graph.cuts[s.cut.index()];
      if (c.patch != pid) continue;
      const bool source = graph.macuts[s.ma.index()].branch;
      svg.polyline({at(pid, c.position), at(pid, graph.macuts[s.ma.index()].point.position)},
                   source ? "#d62728" : "#1f5fbf", source ? 1.2 : 0.6);
    }
    for (const auto& loop : part.patches[p].polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(at(pid, q));
      svg.polyline(pts, "#222", 1.4, true);
    }
  }
  svg.text({10.0, size + 20.0}, title + " (oblique view): source rails red, track rails blue",
           12.0);
  out << svg.str();
}

}  // namespace laytracks
