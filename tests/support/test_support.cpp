#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "laytracks/brep/build.hpp"
#include "laytracks/io/brep_json.hpp"

namespace laytracks::test {

namespace fs = std::filesystem;

std::string cases_dir() { return LAYTRACKS_CASES_DIR; }
std::string test_data_dir() { return LAYTRACKS_TEST_DATA_DIR; }
std::string samples_dir() { return LAYTRACKS_SAMPLES_DIR; }

std::vector<std::string> all_case_files() {
  std::vector<std::string> files;
  for (const std::string& dir : {cases_dir(), samples_dir()}) {
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".json") {
        files.push_back(entry.path().string());
      }
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

Part load_part(const std::string& path) { return build_part(read_brep_json(path)); }

Vec3 Transform::apply(Vec3 p) const {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + t.x,
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + t.y,
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + t.z};
}

Transform rotation(Vec3 axis, double angle) {
  const Vec3 a = normalized(axis);
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double k = 1.0 - c;
  Transform r;
  r.m[0][0] = c + a.x * a.x * k;
  r.m[0][1] = a.x * a.y * k - a.z * s;
  r.m[0][2] = a.x * a.z * k + a.y * s;
  r.m[1][0] = a.y * a.x * k + a.z * s;
  r.m[1][1] = c + a.y * a.y * k;
  r.m[1][2] = a.y * a.z * k - a.x * s;
  r.m[2][0] = a.z * a.x * k - a.y * s;
  r.m[2][1] = a.z * a.y * k + a.x * s;
  r.m[2][2] = c + a.z * a.z * k;
  return r;
}

Transform scaling(double s) {
  Transform r;
  for (int i = 0; i < 3; ++i) r.m[i][i] = s;
  return r;
}

Transform mirror_x() {
  Transform r;
  r.m[0][0] = -1.0;
  return r;
}

Transform translation(Vec3 t) {
  Transform r;
  r.t = t;
  return r;
}

Transform compose(const Transform& second, const Transform& first) {
  Transform r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += second.m[i][k] * first.m[k][j];
      r.m[i][j] = s;
    }
  }
  r.t = second.apply(first.t);
  return r;
}

RawPart transformed(const RawPart& raw, const Transform& t) {
  RawPart out = raw;
  for (Vec3& v : out.vertices) v = t.apply(v);
  for (RawArc& a : out.arcs) a.via = t.apply(a.via);
  double scale = std::cbrt(std::fabs(t.m[0][0] * (t.m[1][1] * t.m[2][2] - t.m[1][2] * t.m[2][1]) -
                                     t.m[0][1] * (t.m[1][0] * t.m[2][2] - t.m[1][2] * t.m[2][0]) +
                                     t.m[0][2] * (t.m[1][0] * t.m[2][1] - t.m[1][1] * t.m[2][0])));
  if (out.mesh.size) out.mesh.size = *out.mesh.size * scale;
  return out;
}

}  // namespace laytracks::test
