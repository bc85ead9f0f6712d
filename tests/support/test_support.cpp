#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

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

RawPart icosphere(int level, double r, double jitter) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p = (r / norm(p)) * p;
  std::vector<std::array<std::size_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> mid;
    const auto middle = [&](std::size_t a, std::size_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const Vec3 m = 0.5 * (v[a] + v[b]);
      v.push_back((r / norm(m)) * m);
      return mid[key] = v.size() - 1;
    };
    std::vector<std::array<std::size_t, 3>> g;
    for (const auto& [a, b, c] : f) {
      const std::size_t ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
      g.insert(g.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    f = std::move(g);
  }
  if (jitter > 0.0) {
    std::uint32_t state = 12345u;  // a linear congruential sequence: the same on every platform
    for (Vec3& p : v) {
      state = state * 1664525u + 1013904223u;
      const double u = static_cast<double>(state >> 8) / static_cast<double>(1u << 24);  // [0, 1)
      p = (1.0 + jitter * (u - 0.5)) * p;
    }
  }
  RawPart raw;
  raw.vertices = v;
  const auto id = [](std::size_t k) { return static_cast<std::int64_t>(k); };
  for (std::size_t i = 0; i < f.size(); ++i)
    raw.patches.push_back({"f" + std::to_string(i), {{id(f[i][0]), id(f[i][1]), id(f[i][2])}}});
  return raw;
}

RawPart torus(int nu, int nv, double R, double r) {
  constexpr double kTau = 6.283185307179586;
  RawPart raw;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = kTau * i / nu, w = kTau * j / nv;
      raw.vertices.push_back(
          {(R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w)});
    }
  }
  const auto id = [&](int i, int j) { return static_cast<std::int64_t>((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      raw.patches.push_back({"q" + std::to_string(i) + "_" + std::to_string(j),
                             {{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}}});
  return raw;
}

}  // namespace laytracks::test
