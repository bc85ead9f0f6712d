// Algorithm III along one CUT-SEG (march_tracks): where the CUT-VERTs go for a given width law.
#include <catch2/catch.hpp>
#include <cmath>

#include "corridors.hpp"

using laytracks::cutgraph_detail::kManyCutsRatio;
using laytracks::cutgraph_detail::kOneCutRatio;
using laytracks::cutgraph_detail::march_tracks;

TEST_CASE("a constant width paves a CUT-SEG with equal tracks from both ends", "[adaptive]") {
  const auto at = march_tracks(10.0, [](double) { return 1.0; });
  REQUIRE(at.size() == 9);
  for (std::size_t k = 0; k < at.size(); ++k) CHECK(at[k] == Approx(static_cast<double>(k + 1)));
}

TEST_CASE("the 0.7 / 1.3 rule: no CUT-VERT, one in the ratio of the end widths, or more",
          "[adaptive]") {
  // Ends of widths 1 and 3: 4 in all.
  const auto width = [](double length) {
    return [length](double x) { return x < 0.5 * length ? 1.0 : 3.0; };
  };
  CHECK(march_tracks(0.69 * 4.0, width(0.69 * 4.0)).empty());
  const auto one = march_tracks(4.0, width(4.0));
  REQUIRE(one.size() == 1);
  CHECK(one[0] == Approx(1.0));  // P0 + L / (1 + 3 / 1)
  const auto mid = march_tracks(1.2 * 4.0, width(1.2 * 4.0));
  REQUIRE(mid.size() == 1);
  CHECK(mid[0] == Approx(1.2));
  CHECK(march_tracks(1.31 * 4.0, width(1.31 * 4.0)).size() >= 2);
  CHECK(kOneCutRatio == 0.7);
  CHECK(kManyCutsRatio == 1.3);
}

TEST_CASE("a width growing away from a corner grades the tracks geometrically", "[adaptive]") {
  // Delta S = 0.2 x (distance from the corner at 0) + 0.01: a corner of the radius law.
  const auto w = [](double x) { return 0.2 * x + 0.01; };
  const auto at = march_tracks(10.0, w);
  REQUIRE(at.size() > 10);
  double prev = 0.0;
  for (std::size_t k = 0; k < at.size(); ++k) {
    INFO("cut " << k << " at " << at[k]);
    REQUIRE(at[k] > prev);
    const double track = at[k] - prev;
    // Each track is the width at its narrow end, or within the ratio rule's bounds of it.
    CHECK(track >= 0.5 * w(prev));
    CHECK(track <= 2.0 * w(at[k]));
    prev = at[k];
  }
  CHECK(at.front() == Approx(0.01));  // the first track: the end width
  CHECK(at.back() < 10.0);
}
