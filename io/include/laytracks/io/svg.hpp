// A small SVG writer for the pictures of every stage: panels, polylines, disks, labels.
#pragma once

#include <string>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks {

/// Maps a world box into a rectangle of the picture, keeping the aspect ratio, y up.
class Panel {
 public:
  Panel(Box2 world, double x, double y, double width, double height, double margin);
  Vec2 map(Vec2 p) const;
  double scale() const { return scale_; }

 private:
  Vec2 world_lo_;
  Vec2 offset_;
  double scale_ = 1.0;
  double height_ = 0.0;
  double y_ = 0.0;
};

/// An oblique camera for pictures of a whole part: the viewer is towards +x, -y, +z (front
/// right, above); screen y points up.
struct ObliqueCamera {
  Vec3 right = normalized(Vec3{1.0, 1.0, 0.0});
  Vec3 toward = normalized(Vec3{1.0, -1.0, 0.9});  ///< from the part towards the viewer
  Vec3 up = normalized(cross(toward, right));
  /// Screen coordinates of a point (a Panel maps them into the picture).
  Vec2 screen(Vec3 p) const { return {dot(p, right), dot(p, up)}; }
  /// Larger is nearer the viewer: draw far to near.
  double depth(Vec3 p) const { return dot(p, toward); }
};

class SvgDocument {
 public:
  SvgDocument(double width, double height);
  /// Appends an element; coordinates are picture coordinates (use Panel::map).
  void polyline(const std::vector<Vec2>& pts,
                const std::string& stroke,
                double width,
                bool closed = false,
                const std::string& fill = "none");
  void circle(Vec2 c, double r, const std::string& fill, const std::string& stroke = "none");
  void text(Vec2 at, const std::string& s, double size, const std::string& anchor = "start");
  void rect(Vec2 lo, Vec2 hi, const std::string& fill, const std::string& stroke);
  std::string str() const;

 private:
  double width_;
  double height_;
  std::string body_;
};

/// The unfolded view of a part: one square panel per patch, in a grid of ceil(sqrt(n))
/// columns, each under a title line.
struct PatchGrid {
  std::size_t cols = 1;
  std::size_t rows = 1;
  double cell = 640.0;  ///< panel side, pixels
  double head = 24.0;   ///< title line above each panel
  explicit PatchGrid(std::size_t patches);
  double width() const { return cell * static_cast<double>(cols); }
  double height() const { return (head + cell) * static_cast<double>(rows); }
  /// The panel of patch p (fitting the box of its polygon) and where its title goes.
  Panel panel(std::size_t p, Box2 box) const;
  Vec2 title_at(std::size_t p) const;
};

/// A colour for t in [0, 1]: dark blue (0) through green to yellow (1), like viridis.
std::string ramp_colour(double t);
/// Escapes &, <, > and quotes for text and attributes.
std::string xml_escape(const std::string& s);

}  // namespace laytracks
