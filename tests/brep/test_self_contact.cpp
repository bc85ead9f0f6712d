// closest_self_contact: where a patch's boundary comes closest to itself away from its corners.
#include <catch2/catch.hpp>

#include "laytracks/brep/self_contact.hpp"
#include "parts.hpp"

namespace laytracks::test {
namespace {

/// A 10 x 10 square with a slit 2g wide and 8 long cut in from its left side (vertices 4-7).
RawPart slit_square(double g) {
  return make_part({{0, 0, 0},
                    {10, 0, 0},
                    {10, 10, 0},
                    {0, 10, 0},
                    {0, 5 + g, 0},
                    {8, 5 + g, 0},
                    {8, 5 - g, 0},
                    {0, 5 - g, 0}},
                   {patch("plate", {{0, 1, 2, 3, 4, 5, 6, 7}})});
}

}  // namespace

TEST_CASE("a slit's two sides are a self-contact, named by vertex and segment", "[brep]") {
  const double g = 1e-7;
  const Part part = build_part(slit_square(g));
  const auto c = closest_self_contact(part, 1e-6);
  REQUIRE(c);
  // Vertex 4 (0, 5 + g) against the segment from 6 to 7 (the slit's other side): 2g. Equal
  // distances go to the first vertex, then the first segment.
  CHECK(c->patch.index() == 0);
  CHECK(c->vertex == 4);
  CHECK(c->seg == 6);
  CHECK(c->distance == Approx(2 * g).epsilon(1e-6));
  const std::string text = describe(part, *c);
  CHECK_THAT(text, Catch::Contains("patch \"plate\" (index 0)"));
  CHECK_THAT(text, Catch::Contains("vertex 4 at (0, 5.0000001, 0)"));
  CHECK_THAT(text, Catch::Contains("the segment from vertex 6 to vertex 7 of the outer loop"));
  // Nothing within less than the slit's width.
  CHECK_FALSE(closest_self_contact(part, 1.9 * g));
}

TEST_CASE("a needle's two sides are no self-contact; a hole near the outline is", "[brep]") {
  // A notch 2 wide at its mouth narrowing over 1000 to a tip of 0.11 degrees: its sides come
  // within any distance of each other near the tip, but they meet there, as a needle's do.
  // (A notch 2e-7 wide at its mouth would be a contact: the mouth's corners.)
  const Part notch = build_part(make_part(
      {{0, 0, 0}, {1010, 0, 0}, {1010, 10, 0}, {0, 10, 0}, {0, 6, 0}, {1000, 5, 0}, {0, 4, 0}},
      {patch("notch", {{0, 1, 2, 3, 4, 5, 6}})}));
  CHECK_FALSE(closest_self_contact(notch, 1.9));
  CHECK(closest_self_contact(notch, 2.1));
  // A triangular hole whose corner comes within 1e-6 of the outline's right side.
  const Part hole = build_part(make_part(
      {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {5, 4, 0}, {10 - 1e-6, 5, 0}, {5, 6, 0}},
      {patch("holed", {{0, 1, 2, 3}, {4, 5, 6}})}));
  const auto c = closest_self_contact(hole, 1e-3);
  REQUIRE(c);
  CHECK(c->loop == 1);
  CHECK(c->seg_loop == 0);
  CHECK(c->distance == Approx(1e-6).epsilon(1e-6));
  CHECK_THAT(describe(hole, *c),
             Catch::Contains(
                 "of loop 1 (a hole) and the segment from vertex 1 to vertex 2 of the outer loop"));
}

}  // namespace laytracks::test
