#include "laytracks/io/svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace laytracks {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

}  // namespace

Panel::Panel(Box2 world, double x, double y, double width, double height, double margin)
    : world_lo_(world.lo), height_(height), y_(y) {
  const double ww = std::max(world.hi.x - world.lo.x, 1e-300);
  const double wh = std::max(world.hi.y - world.lo.y, 1e-300);
  scale_ = std::min((width - 2 * margin) / ww, (height - 2 * margin) / wh);
  // Centre the drawing in the panel.
  offset_ = {x + 0.5 * (width - scale_ * ww), 0.5 * (height - scale_ * wh)};
}

Vec2 Panel::map(Vec2 p) const {
  return {offset_.x + scale_ * (p.x - world_lo_.x),
          y_ + height_ - offset_.y - scale_ * (p.y - world_lo_.y)};
}

SvgDocument::SvgDocument(double width, double height) : width_(width), height_(height) {}

void SvgDocument::polyline(const std::vector<Vec2>& pts,
                           const std::string& stroke,
                           double width,
                           bool closed,
                           const std::string& fill) {
  body_ += closed ? "<polygon points=\"" : "<polyline points=\"";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i) body_ += ' ';
    body_ += num(pts[i].x) + "," + num(pts[i].y);
  }
  body_ += "\" fill=\"" + fill + "\" stroke=\"" + stroke + "\" stroke-width=\"" + num(width) +
           "\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n";
}

void SvgDocument::circle(Vec2 c, double r, const std::string& fill, const std::string& stroke) {
  body_ += "<circle cx=\"" + num(c.x) + "\" cy=\"" + num(c.y) + "\" r=\"" + num(r) + "\" fill=\"" +
           fill + "\" stroke=\"" + stroke + "\"/>\n";
}

void SvgDocument::text(Vec2 at, const std::string& s, double size, const std::string& anchor) {
  body_ += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y) + "\" font-size=\"" + num(size) +
           "\" font-family=\"sans-serif\" text-anchor=\"" + anchor + "\">" + xml_escape(s) +
           "</text>\n";
}

void SvgDocument::rect(Vec2 lo, Vec2 hi, const std::string& fill, const std::string& stroke) {
  body_ += "<rect x=\"" + num(lo.x) + "\" y=\"" + num(lo.y) + "\" width=\"" + num(hi.x - lo.x) +
           "\" height=\"" + num(hi.y - lo.y) + "\" fill=\"" + fill + "\" stroke=\"" + stroke +
           "\"/>\n";
}

std::string SvgDocument::str() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
         "width=\"" +
         num(width_) + "\" height=\"" + num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " +
         num(height_) +
         "\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n" +
         body_ + "</svg>\n";
}

std::string ramp_colour(double t) {
  // A few stops of the viridis map, linearly interpolated.
  static const std::array<std::array<double, 3>, 5> stops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (stops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double f = t - static_cast<double>(i);
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x",
                static_cast<int>(std::lround(stops[i][0] + f * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + f * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + f * (stops[i + 1][2] - stops[i][2]))));
  return buf;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

PatchGrid::PatchGrid(std::size_t patches) {
  const std::size_t n = std::max<std::size_t>(1, patches);
  cols = std::min<std::size_t>(n, static_cast<std::size_t>(std::ceil(std::sqrt(double(n)))));
  cols = std::max<std::size_t>(1, cols);
  rows = (n + cols - 1) / cols;
  cell = n == 1 ? 640.0 : 360.0;
}

Panel PatchGrid::panel(std::size_t p, Box2 box) const {
  const double x0 = cell * static_cast<double>(p % cols);
  const double y0 = (cell + head) * static_cast<double>(p / cols);
  return Panel(box, x0, y0 + head, cell, cell, 16.0);
}

Vec2 PatchGrid::title_at(std::size_t p) const {
  return {cell * static_cast<double>(p % cols) + 8.0,
          (cell + head) * static_cast<double>(p / cols) + 18.0};
}

}  // namespace laytracks
