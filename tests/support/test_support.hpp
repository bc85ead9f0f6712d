// Helpers shared by the tests: where the test parts are, and how to load them.
#pragma once

#include <string>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/brep/raw_part.hpp"

namespace laytracks::test {

/// ../shared/cases and its external/ folder.
std::string cases_dir();
/// tests/data in the repository.
std::string test_data_dir();
/// samples/ in the repository.
std::string samples_dir();

/// Every *.json under ../shared/cases (including external/) and samples/, sorted.
std::vector<std::string> all_case_files();

/// Reads and builds a part file (throws on any error).
Part load_part(const std::string& path);

/// A rigid or similarity transform applied to a RawPart: every vertex and arc via point.
struct Transform {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< linear part
  Vec3 t;                                              ///< translation
  Vec3 apply(Vec3 p) const;
};
Transform rotation(Vec3 axis, double angle_rad);
Transform scaling(double s);
Transform mirror_x();
Transform translation(Vec3 t);
Transform compose(const Transform& second, const Transform& first);  ///< second after first
RawPart transformed(const RawPart& raw, const Transform& t);

/// A faceted closed shell: 20 x 4^level triangles on a sphere of radius r (the icosahedron's
/// faces split into four, level times, the new vertices pushed out to the sphere). With
/// jitter > 0 each vertex is then moved out or in by up to jitter / 2 x r (a fixed
/// pseudo-random sequence): irregular triangles, as a tessellated part has.
RawPart icosphere(int level, double r, double jitter = 0.0);

/// A faceted torus: nu x nv planar quads (isosceles trapezoids), major radius R, minor r.
RawPart torus(int nu, int nv, double R, double r);

}  // namespace laytracks::test
