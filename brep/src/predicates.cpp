// The only brep translation unit that includes CGAL: exact predicates (EPICK) and
// CGAL::box_intersection_d. Everything else in brep sees plain Vec2/Box types (predicates.hpp).
#include "predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

namespace laytracks::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Segment = Kernel::Segment_2;
using CgalBox2 = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
using CgalBox3 = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

Point to_cgal(Vec2 p) { return Point(p.x, p.y); }

/// CGAL boxes carrying their index in `boxes`.
std::vector<CgalBox2> to_cgal_boxes(const std::vector<Box2>& boxes) {
  std::vector<CgalBox2> out;
  out.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    double lo[2] = {boxes[i].lo.x, boxes[i].lo.y};
    double hi[2] = {boxes[i].hi.x, boxes[i].hi.y};
    out.emplace_back(lo, hi, i);
  }
  return out;
}

/// CGAL boxes carrying their index in `boxes`.
std::vector<CgalBox3> to_cgal_boxes(const std::vector<Box3>& boxes) {
  std::vector<CgalBox3> out;
  out.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    double lo[3] = {boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z};
    double hi[3] = {boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z};
    out.emplace_back(lo, hi, i);
  }
  return out;
}

/// Bipartite closed-box search over two CGAL box sets (consumed: the search reorders them).
template <class Box>
IndexPairs bipartite(std::vector<Box> a, std::vector<Box> b) {
  IndexPairs pairs;
  if (a.empty() || b.empty()) return pairs;
  auto report = [&pairs](const Box& x, const Box& y) { pairs.emplace_back(x.info(), y.info()); };
  CGAL::box_intersection_d(a.begin(), a.end(), b.begin(), b.end(), report, std::ptrdiff_t(10),
                           CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
  return pairs;
}

}  // namespace

int orientation(Vec2 a, Vec2 b, Vec2 c) {
  switch (CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c))) {
    case CGAL::LEFT_TURN:
      return 1;
    case CGAL::RIGHT_TURN:
      return -1;
    default:
      return 0;
  }
}

bool collinear_are_ordered(Vec2 p, Vec2 q, Vec2 r) {
  return CGAL::collinear_are_ordered_along_line(to_cgal(p), to_cgal(q), to_cgal(r));
}

bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return CGAL::do_intersect(Segment(to_cgal(a), to_cgal(b)), Segment(to_cgal(c), to_cgal(d)));
}

IndexPairs overlapping_boxes(const std::vector<Box2>& boxes) {
  IndexPairs pairs;
  std::vector<CgalBox2> cgal_boxes = to_cgal_boxes(boxes);
  auto report = [&pairs](const CgalBox2& x, const CgalBox2& y) {
    pairs.emplace_back(std::min(x.info(), y.info()), std::max(x.info(), y.info()));
  };
  CGAL::box_self_intersection_d(cgal_boxes.begin(), cgal_boxes.end(), report, std::ptrdiff_t(10),
                                CGAL::Box_intersection_d::CLOSED);
  return pairs;
}

IndexPairs overlapping_boxes(const std::vector<Box2>& a, const std::vector<Box2>& b) {
  return bipartite(to_cgal_boxes(a), to_cgal_boxes(b));
}

IndexPairs overlapping_boxes(const std::vector<Box3>& a, const std::vector<Box3>& b) {
  return bipartite(to_cgal_boxes(a), to_cgal_boxes(b));
}

}  // namespace laytracks::detail
