#include "laytracks/brep/polygon.hpp"

namespace laytracks {

double twice_signed_area(const std::vector<Vec2>& loop) {
  // Shoelace about the first vertex: smaller terms, less cancellation far from the origin.
  if (loop.size() < 3) return 0.0;
  const Vec2 o = loop[0];
  double a = 0.0;
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) a += cross(loop[i] - o, loop[i + 1] - o);
  return a;
}

}  // namespace laytracks
