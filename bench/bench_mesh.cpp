// Benchmark: the whole meshing pipeline (laytracks::mesh_part) on one part at several sizes.
// Prints, per size, the seconds of each stage (medial, rails, quads, smooth, check), the total,
// quads per second and the quality figures of the final mesh (quality.md), as an aligned table.
// Not a test: run it by hand in a Release build, or through bench/run-bench.sh.
//
//   build/bench/bench_mesh PART.json [--size W ...] [--target-quads N ...] [--dtheta DEG ...]
//                          [--smooth N]
//                          [--repeat K] [--chord-tol T] [--json OUT.json] [--msh DIR] [--quiet]
//
// --dtheta takes one or more angles: adaptive mode (docs/adaptive.md) at each.
// --size takes one or more element sizes (or repeat the flag); --target-quads one or more quad
// counts, each turned into a size as follows. The quad count of a uniform mesh goes as
// area / h^2, so h0 = sqrt(area / min(N, 2000)) is meshed first (cheap); while that mesh has
// fewer than N / 16 quads, h is scaled by sqrt(quads / goal) for a goal of 16x the quads but
// at most N / 8, and meshed again (so calibrating costs well under the final mesh). The last
// calibration mesh gives h = h_k sqrt(quads_k / N), and the row is measured there. If its quad
// count is more than 10% off N, h is scaled once more by sqrt(quads / N) and the row measured
// again (it replaces the first). A calibration mesh the mesher refuses is retried at 0.9 h
// (three times at most); if none succeeds, the last good calibration is extrapolated, and
// without one h = sqrt(area / N) is used.
// Without --size and --target-quads the part's default size is used (mesh.size, else 1/40 of
// its size), as `laytracks mesh` does.
//
// A size the mesher refuses (laytracks::Error) is a row "refused: <message>", not a crash.
// With --repeat K every row is meshed K times and the run with the smallest total is reported.
// Times are wall seconds (steady_clock); the JSON adds the processor seconds of mesh_part as
// "cpu" (std::clock), which other work on a shared machine disturbs less.
// --msh DIR writes the mesh of every row to DIR/<part>-<row>.msh (for `laytracks quality`).
// Exit status: 0 (also when rows are refused), 1 when the part cannot be read, 2 for a wrong
// command line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "laytracks/brep/build.hpp"
#include "laytracks/brep/error.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/mesher/mesh_part.hpp"

using namespace laytracks;

namespace {

const char* const kUsage =
    "usage: bench_mesh PART.json [--size W ...] [--target-quads N ...] [--dtheta DEG ...]\n"
    "                  [--smooth N]\n"
    "                  [--repeat K] [--chord-tol T] [--json OUT.json] [--msh DIR] [--quiet]\n";

/// What one row asks for: a size, a quad count, or the part's default size.
struct Request {
  enum class Kind { Default, Size, Target, Dtheta } kind = Kind::Default;
  double value = 0.0;
};

struct Options {
  std::string part;
  std::vector<Request> requests;
  int smooth = kDefaultSmooth;
  int repeat = 1;
  std::optional<double> chord_tol;
  std::optional<std::string> json;
  std::optional<std::string> msh_dir;
  bool quiet = false;
};

/// One meshing run: the result figures, or the refusal.
struct Run {
  double size = 0.0;
  bool ok = false;
  std::string message;  ///< why the mesher refused, when !ok
  std::size_t quads = 0;
  std::size_t nodes = 0;
  StageTimes times;
  double total = 0.0;  ///< wall seconds of mesh_part
  double cpu = 0.0;    ///< processor seconds of mesh_part (std::clock: the process, all threads)
  bool valid = false;
  QualitySummary quality;
  QualitySummary before_smoothing;  ///< the mesh as the templates built it
  QuadMesh mesh;                    ///< kept only when --msh asks for it
};

struct Row {
  Request request;
  Run run;
  std::vector<Run> calibration;  ///< the meshes that chose the size (--target-quads)
};

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "bench_mesh: %s\n%s", what.c_str(), kUsage);
  std::exit(2);
}

double positive(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(v > 0.0) || !std::isfinite(v)) {
    usage_error(flag + " needs a positive number, not \"" + text + "\"");
  }
  return v;
}

bool is_flag(const std::string& s) { return s.size() > 1 && s[0] == '-' && s[1] == '-'; }

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size() || is_flag(args[i + 1])) usage_error(a + " needs a value");
      return args[++i];
    };
    if (a == "--size" || a == "--target-quads" || a == "--dtheta") {
      const Request::Kind kind = a == "--size"           ? Request::Kind::Size
                                 : a == "--target-quads" ? Request::Kind::Target
                                                         : Request::Kind::Dtheta;
      o.requests.push_back({kind, positive(a, value())});
      while (i + 1 < args.size() && !is_flag(args[i + 1])) {
        o.requests.push_back({kind, positive(a, args[++i])});
      }
    } else if (a == "--smooth") {
      const std::string& v = value();
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || n < 0 || n > 100000) usage_error("--smooth needs a count, not " + v);
      o.smooth = static_cast<int>(n);
    } else if (a == "--repeat") {
      o.repeat = static_cast<int>(positive(a, value()));
    } else if (a == "--chord-tol") {
      o.chord_tol = positive(a, value());
    } else if (a == "--json") {
      o.json = value();
    } else if (a == "--msh") {
      o.msh_dir = value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (is_flag(a) || !o.part.empty()) {
      usage_error("unexpected argument \"" + a + "\"");
    } else {
      o.part = a;
    }
  }
  if (o.part.empty()) usage_error("a PART.json is needed");
  if (o.requests.empty()) o.requests.push_back({});
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Meshes the part once at `size` (the part's default when nullopt), or in adaptive mode at
/// `dtheta` degrees when that is given.
Run mesh_once(const Part& part, std::optional<double> size, int smooth, bool keep_mesh,
              std::optional<double> dtheta = std::nullopt) {
  Run r;
  MeshPartOptions options;
  options.size = size;
  options.smooth = smooth;
  options.adaptive = dtheta.has_value();
  options.dtheta_deg = dtheta;
  r.size = size.value_or(part.mesh.size.value_or(default_element_size(part)));
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  try {
    MeshPartResult m = mesh_part(part, options);
    r.total = seconds_since(t0);
    r.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    r.ok = true;
    r.size = m.size;
    r.quads = m.mesh.elements.size();
    r.nodes = m.mesh.nodes.size();
    r.times = m.times;
    r.valid = m.check.valid();
    r.quality = std::move(m.quality);
    r.before_smoothing = std::move(m.before_smoothing);
    if (keep_mesh) r.mesh = std::move(m.mesh);
  } catch (const InvalidMeshError& e) {
    // Not a refusal but a bug: the mesh was built and failed its own check.
    r.total = seconds_since(t0);
    r.message = std::string("the mesh failed its self-check (a bug): ") + e.what();
  } catch (const Error& e) {
    r.total = seconds_since(t0);
    r.message = e.what();
  }
  return r;
}

/// The best (smallest total) of `repeat` runs; a refusal is not repeated.
Run mesh_timed(const Part& part, std::optional<double> size, const Options& o,
               std::optional<double> dtheta = std::nullopt) {
  Run best = mesh_once(part, size, o.smooth, o.msh_dir.has_value(), dtheta);
  for (int k = 1; k < o.repeat && best.ok; ++k) {
    Run again = mesh_once(part, size, o.smooth, o.msh_dir.has_value(), dtheta);
    if (again.ok && again.total < best.total) best = std::move(again);
  }
  return best;
}

double part_area(const Part& part) {
  double a = 0.0;
  for (const Patch& p : part.patches) a += p.area;
  return a;
}

/// The size for about `target` quads, by the procedure in the header comment. The
/// calibration meshes are appended to `calibration`.
double size_for(const Part& part, double target, const Options& o, std::vector<Run>& calibration) {
  const double area = part_area(part);
  double h = std::sqrt(area / std::min(target, 2000.0));
  std::optional<double> extrapolated;  // from the last calibration mesh that succeeded
  for (int step = 0; step < 10; ++step) {
    Run r = mesh_once(part, h, o.smooth, false);
    for (int retry = 0; retry < 3 && !r.ok; ++retry) {
      calibration.push_back(std::move(r));
      h *= 0.9;
      r = mesh_once(part, h, o.smooth, false);
    }
    const bool ok = r.ok;
    const double quads = static_cast<double>(r.quads);
    calibration.push_back(std::move(r));
    if (!ok) break;
    extrapolated = h * std::sqrt(quads / target);
    if (quads >= target / 16.0) break;
    // The next calibration mesh: at most 16x this one and at most target / 8.
    h *= std::sqrt(quads / std::min(16.0 * quads, target / 8.0));
  }
  return extrapolated.value_or(std::sqrt(area / target));
}

void print_header(const Part& part, const std::string& path, double area) {
  std::printf("%s: %zu patches, area %.6g %s^2\n", path.c_str(), part.patches.size(), area,
              part.units.c_str());
  std::printf("%10s %9s %9s %7s %7s %8s %7s %7s %7s %8s %8s %9s %7s %7s %7s %7s %5s\n", "size", "quads",
              "nodes", "medial", "rails", "quads", "refill", "smooth", "check", "total", "cpu", "quads/s",
              "min SJ", "skew30", "asp5", "tap0.8", "valid");
}

void print_row(const Run& r) {
  if (!r.ok) {
    std::string msg = r.message;
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    std::printf("%10.5g refused: %s\n", r.size, msg.c_str());
    return;
  }
  const auto& m = r.quality.measures;
  std::printf(
      "%10.5g %9zu %9zu %7.3f %7.3f %8.3f %7.3f %7.3f %7.3f %8.3f %8.3f %9.0f %7.3f %6.1f%% %6.2f%% "
      "%6.1f%% %5s\n",
      r.size, r.quads, r.nodes, r.times.medial, r.times.rails, r.times.quads, r.times.refill, r.times.smooth,
      r.times.check, r.total, r.cpu, r.total > 0 ? static_cast<double>(r.quads) / r.total : 0.0,
      m[6].worst, m[0].bad_percent, m[1].bad_percent, m[2].bad_percent, r.valid ? "yes" : "NO");
}

/// The summary as `laytracks quality --json` writes it (write_quality_json), so that our
/// figures and Gmsh's are read from the same keys.
nlohmann::ordered_json summary_json(const QualitySummary& q) {
  std::ostringstream o;
  write_quality_json(o, q, false);
  return nlohmann::ordered_json::parse(o.str());
}

nlohmann::ordered_json run_json(const Run& r) {
  nlohmann::ordered_json j;
  j["size"] = r.size;
  j["status"] = r.ok ? "ok" : "refused";
  if (!r.ok) {
    j["message"] = r.message;
    j["seconds_until_refused"] = r.total;
    return j;
  }
  j["quads"] = r.quads;
  j["nodes"] = r.nodes;
  j["seconds"] = {{"medial", r.times.medial},
                  {"rails", r.times.rails},
                  {"quads", r.times.quads},
                  {"refill", r.times.refill},
                  {"smooth", r.times.smooth},
                  {"check", r.times.check},
                  {"total", r.total},
                  {"cpu", r.cpu}};
  j["quads_per_second"] = r.total > 0 ? static_cast<double>(r.quads) / r.total : 0.0;
  j["valid"] = r.valid;
  j["quality"] = summary_json(r.quality);
  j["quality_before_smoothing"] = summary_json(r.before_smoothing);
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  Part part;
  try {
    BuildOptions build_options;
    build_options.chord_tol = o.chord_tol;
    part = build_part(read_brep_json(o.part), build_options);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_mesh: %s\n", e.what());
    return 1;
  }
  const double area = part_area(part);
  if (!o.quiet) print_header(part, o.part, area);

  std::vector<Row> rows;
  for (const Request& req : o.requests) {
    Row row;
    row.request = req;
    if (req.kind == Request::Kind::Target) {
      const double h = size_for(part, req.value, o, row.calibration);
      row.run = mesh_timed(part, h, o);
      const double quads = static_cast<double>(row.run.quads);
      if (row.run.ok && std::abs(quads - req.value) > 0.1 * req.value) {
        row.calibration.push_back(std::move(row.run));
        row.run = mesh_timed(part, h * std::sqrt(quads / req.value), o);
      }
    } else if (req.kind == Request::Kind::Dtheta) {
      row.run = mesh_timed(part, std::nullopt, o, req.value);
    } else {
      row.run = mesh_timed(
          part, req.kind == Request::Kind::Size ? std::optional<double>(req.value) : std::nullopt,
          o);
    }
    if (!o.quiet) {
      print_row(row.run);
      std::fflush(stdout);
    }
    if (o.msh_dir && row.run.ok) {
      std::filesystem::create_directories(*o.msh_dir);
      const std::string file =
          (std::filesystem::path(*o.msh_dir) / (std::filesystem::path(o.part).stem().string() +
                                                "-" + std::to_string(rows.size()) + ".msh"))
              .string();
      write_mesh(file, part, row.run.mesh);
      row.run.mesh = {};
    }
    rows.push_back(std::move(row));
  }

  if (o.json) {
    nlohmann::ordered_json doc;
    doc["part"] = o.part;
    doc["patches"] = part.patches.size();
    doc["area"] = area;
    doc["chord_tol"] = part.chord_tol;
    doc["smooth"] = o.smooth;
    doc["repeat"] = o.repeat;
    nlohmann::ordered_json out_rows = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& row = rows[i];
      nlohmann::ordered_json j = run_json(row.run);
      nlohmann::ordered_json req;
      switch (row.request.kind) {
        case Request::Kind::Default:
          req = "default";
          break;
        case Request::Kind::Size:
          req = {{"size", row.request.value}};
          break;
        case Request::Kind::Target:
          req = {{"target_quads", row.request.value}};
          break;
        case Request::Kind::Dtheta:
          req = {{"adaptive_dtheta_deg", row.request.value}};
          break;
      }
      j["request"] = req;
      if (o.msh_dir && row.run.ok) {
        j["msh"] =
            (std::filesystem::path(*o.msh_dir) /
             (std::filesystem::path(o.part).stem().string() + "-" + std::to_string(i) + ".msh"))
                .string();
      }
      if (!row.calibration.empty()) {
        nlohmann::ordered_json cal = nlohmann::ordered_json::array();
        for (const Run& c : row.calibration) {
          cal.push_back({{"size", c.size},
                         {"status", c.ok ? "ok" : "refused"},
                         {"quads", c.quads},
                         {"seconds", c.total}});
        }
        j["calibration"] = cal;
      }
      out_rows.push_back(j);
    }
    doc["rows"] = out_rows;
    std::ofstream f(*o.json);
    f << doc.dump(2) << '\n';
    if (!f) {
      std::fprintf(stderr, "bench_mesh: cannot write %s\n", o.json->c_str());
      return 1;
    }
  }
  return 0;
}
