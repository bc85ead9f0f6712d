#include "laytracks/io/mesh_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "laytracks/brep/error.hpp"
#include "laytracks/io/svg.hpp"
#include "laytracks/mesher/quality.hpp"

namespace laytracks {
namespace {

constexpr double kLegendHeight = 66.0;

/// Throws unless element e's patch and nodes exist.
void check_element(const Part& part, const QuadMesh& mesh, std::size_t e) {
  const MeshElement& el = mesh.elements[e];
  if (el.patch.index() >= part.patches.size()) {
    throw Error("cannot draw the mesh: element " + std::to_string(e) + " has no patch " +
                std::to_string(el.patch.index()));
  }
  for (std::size_t k = 0; k < (el.is_quad() ? 4u : 3u); ++k) {
    if (el.nodes[k] >= mesh.nodes.size()) {
      throw Error("cannot draw the mesh: element " + std::to_string(e) + " refers to node " +
                  std::to_string(el.nodes[k]) + " of " + std::to_string(mesh.nodes.size()));
    }
  }
}

/// Corners of element e: 4 for a quad, 3 for a triangle.
std::vector<Vec3> corners(const QuadMesh& mesh, std::size_t e) {
  const MeshElement& el = mesh.elements[e];
  std::vector<Vec3> pts;
  for (std::size_t k = 0; k < (el.is_quad() ? 4u : 3u); ++k) pts.push_back(mesh.nodes[el.nodes[k]]);
  return pts;
}

/// Where value v lies on the colour ramp: 0 at c.worst, 1 at c.ideal.
double ramp_at(const MeshColouring& c, double v) {
  if (!std::isfinite(v)) return 0.0;
  return std::clamp((v - c.worst) / (c.ideal - c.worst), 0.0, 1.0);
}

std::string fill_of(const MeshColouring& c, double v) { return ramp_colour(ramp_at(c, v)); }

/// Outline width in pixels for the elements of a patch: thin enough that small elements still
/// show their colour (about 6% of a typical element's side), never invisible.
double outline_width(const Patch& patch, std::size_t elements, double scale) {
  if (elements == 0) return 0.4;
  const double side_px = scale * std::sqrt(patch.area / static_cast<double>(elements));
  return std::clamp(0.06 * side_px, 0.1, 0.6);
}

/// A loop drawn as an open polyline that returns to its start (not a <polygon>: the picture's
/// only polygons are elements).
std::vector<Vec2> closed_run(std::vector<Vec2> pts) {
  if (!pts.empty()) pts.push_back(pts.front());
  return pts;
}

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

/// The colour bar and the counts, starting at picture height y.
void legend(SvgDocument& svg,
            double y,
            const QuadMesh& mesh,
            const MeshColouring& c,
            const std::string& view) {
  const double x0 = 10.0;
  const double w = 240.0;
  for (int i = 0; i < 120; ++i) {
    svg.rect({x0 + 2.0 * i, y}, {x0 + 2.0 * (i + 1), y + 14.0}, ramp_colour(i / 119.0), "none");
  }
  svg.rect({x0, y}, {x0 + w, y + 14.0}, "none", "#222");
  const double bad_at = x0 + w * ramp_at(c, c.bad);
  svg.polyline({{bad_at, y - 3.0}, {bad_at, y + 17.0}}, "#d62728", 1.5);
  // The element farthest from ideal, non-finite values counting as `worst`.
  double extreme = std::numeric_limits<double>::quiet_NaN();
  for (double v : c.value) {
    const double x = std::isfinite(v) ? v : c.worst;
    if (std::isnan(extreme) || ramp_at(c, x) < ramp_at(c, extreme) ||
        (ramp_at(c, x) == ramp_at(c, extreme) && std::abs(x - c.ideal) > std::abs(extreme - c.ideal)))
      extreme = x;
  }
  if (!c.value.empty()) {
    const double at = x0 + w * ramp_at(c, extreme);
    svg.polyline({{at - 4.0, y + 22.0}, {at, y + 15.0}, {at + 4.0, y + 22.0}}, "#222", 1.2);
  }
  svg.text({x0, y + 32.0}, format("%g", c.worst), 10.0, "middle");
  svg.text({bad_at, y + 32.0}, format("%g", c.bad), 10.0, "middle");
  svg.text({x0 + w * 0.5, y + 32.0}, format("%g", 0.5 * (c.worst + c.ideal)), 10.0, "middle");
  svg.text({x0 + w, y + 32.0}, format("%g", c.ideal), 10.0, "middle");
  std::size_t quads = 0;
  for (const MeshElement& el : mesh.elements) quads += el.is_quad() ? 1u : 0u;
  std::string label = c.name + " (bad " + c.bad_when + " " + format("%g", c.bad) + ", red)";
  if (!c.value.empty()) {
    label += std::string(c.worst < c.ideal ? ": smallest " : ": largest ") +
             format("%.3f", extreme) + " (marked)";
  }
  svg.text({x0 + w + 14.0, y + 11.0}, label, 12.0);
  const std::size_t triangles = mesh.elements.size() - quads;
  svg.text({x0, y + 50.0},
           "mesh, " + view + " view: " + std::to_string(quads) + " quads, " +
               (triangles ? std::to_string(triangles) + " triangles, " : std::string()) +
               std::to_string(mesh.nodes.size()) + " nodes; patch boundaries bold",
           12.0);
}

void write_unfolded(std::ostream& out,
                    const Part& part,
                    const QuadMesh& mesh,
                    const MeshColouring& colouring) {
  const std::size_t n = part.patches.size();
  const PatchGrid grid(n);
  SvgDocument svg(grid.width(), grid.height() + kLegendHeight);
  std::vector<Panel> panels;
  std::vector<std::size_t> count(n, 0);
  for (const MeshElement& el : mesh.elements) ++count[el.patch.index()];
  std::vector<double> outline(n, 0.4);
  for (std::size_t p = 0; p < n; ++p) {
    Box2 box;
    for (const auto& loop : part.patches[p].polygon.loops) {
      for (Vec2 q : loop) box.add(q);
    }
    panels.push_back(grid.panel(p, box));
    svg.text(grid.title_at(p),
             part.patches[p].name + "  (" + std::to_string(count[p]) + " elements)", 14.0);
    outline[p] = outline_width(part.patches[p], count[p], panels[p].scale());
  }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const std::size_t p = mesh.elements[e].patch.index();
    std::vector<Vec2> pts;
    for (const Vec3& x : corners(mesh, e)) {
      pts.push_back(panels[p].map(part.patches[p].frame.to_2d(x)));
    }
    svg.polyline(pts, "#333", outline[p], true, fill_of(colouring, colouring.value[e]));
  }
  for (std::size_t p = 0; p < n; ++p) {
    for (const auto& loop : part.patches[p].polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(panels[p].map(q));
      svg.polyline(closed_run(std::move(pts)), "#000", 1.8);
    }
  }
  legend(svg, grid.height() + 8.0, mesh, colouring, "unfolded");
  out << svg.str();
}

void write_oblique(std::ostream& out,
                   const Part& part,
                   const QuadMesh& mesh,
                   const MeshColouring& colouring) {
  const ObliqueCamera cam;
  Box2 box;
  for (const BrepVertex& v : part.vertices) box.add(cam.screen(v.position));
  for (const Vec3& x : mesh.nodes) box.add(cam.screen(x));
  const double size = 900.0;
  SvgDocument svg(size, size + kLegendHeight);
  const Panel panel(box, 0.0, 0.0, size, size, 24.0);
  const std::size_t n = part.patches.size();
  std::vector<std::vector<std::size_t>> by_patch(n);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const std::size_t p = mesh.elements[e].patch.index();
    by_patch[p].push_back(e);
  }
  // Patches far to near (painter's order by the depth of their frame origins).
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t p = 0; p < n; ++p) order.push_back({cam.depth(part.patches[p].frame.origin), p});
  std::sort(order.begin(), order.end());
  for (const auto& [depth, p] : order) {
    (void)depth;
    const Patch& patch = part.patches[p];
    const double width = outline_width(patch, by_patch[p].size(), panel.scale());
    for (const std::size_t e : by_patch[p]) {
      std::vector<Vec2> pts;
      for (const Vec3& x : corners(mesh, e)) pts.push_back(panel.map(cam.screen(x)));
      svg.polyline(pts, "#333", width, true, fill_of(colouring, colouring.value[e]));
    }
    for (const auto& loop : patch.polygon.loops) {
      std::vector<Vec2> pts;
      for (Vec2 q : loop) pts.push_back(panel.map(cam.screen(patch.frame.to_3d(q))));
      svg.polyline(closed_run(std::move(pts)), "#000", 1.6);
    }
  }
  legend(svg, size + 8.0, mesh, colouring, "oblique");
  out << svg.str();
}

}  // namespace

const std::vector<std::string>& colour_measures() {
  static const std::vector<std::string> names{"jacobian", "taper", "skew", "aspect", "edge-ratio"};
  return names;
}

MeshColouring colour_by(const std::string& measure, const Part& part, const QuadMesh& mesh) {
  using T = QualityThresholds;
  MeshColouring c;
  if (measure == "jacobian") {
    c = {"scaled Jacobian", {}, 0.0, 1.0, T::kScaledJacobian, "<="};
  } else if (measure == "taper") {
    c = {"taper", {}, 0.0, 1.0, T::kTaper, "<="};
  } else if (measure == "skew") {
    c = {"skew [deg]", {}, 90.0, 0.0, T::kSkewDeg, ">="};
  } else if (measure == "aspect") {
    c = {"aspect ratio", {}, 10.0, 1.0, T::kAspectRatio, ">="};
  } else if (measure == "edge-ratio") {
    c = {"edge ratio", {}, 10.0, 1.0, T::kEdgeRatio, ">="};
  } else {
    throw Error("no measure '" + measure + "' to colour by: jacobian, taper, skew, aspect or edge-ratio");
  }
  c.value.reserve(mesh.elements.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    check_element(part, mesh, e);
    const MeshElement& el = mesh.elements[e];
    if (!el.is_quad()) {  // a triangle (a mesh from elsewhere) is drawn as the worst
      c.value.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const QuadQuality q = measure_quad({mesh.nodes[el.nodes[0]], mesh.nodes[el.nodes[1]],
                                        mesh.nodes[el.nodes[2]], mesh.nodes[el.nodes[3]]},
                                       part.patches[el.patch.index()].frame.n);
    c.value.push_back(measure == "jacobian" ? q.scaled_jacobian
                      : measure == "taper"  ? q.taper
                      : measure == "skew"   ? q.skew_deg
                      : measure == "aspect" ? q.aspect_ratio
                                            : q.edge_ratio);
  }
  return c;
}

void write_mesh_svg(std::ostream& out,
                    const Part& part,
                    const QuadMesh& mesh,
                    const MeshColouring& colouring,
                    MeshView view) {
  if (colouring.value.size() != mesh.elements.size()) {
    throw Error("cannot draw the mesh: " + std::to_string(colouring.value.size()) + " " +
                colouring.name + " values for " + std::to_string(mesh.elements.size()) +
                " elements");
  }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) check_element(part, mesh, e);
  if (view == MeshView::kOblique) {
    write_oblique(out, part, mesh, colouring);
  } else {
    write_unfolded(out, part, mesh, colouring);
  }
}

}  // namespace laytracks
