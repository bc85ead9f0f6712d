// laytracks batch INPUTS... -o OUTDIR [--format F] [-j N] [--size W | --adaptive ...]
//                 [--smooth N] [--chord-tol T] [--quiet]
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <system_error>
#include <thread>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "meshing.hpp"

namespace laytracks::cli {

const char* const kBatchHelp =
    "usage: laytracks batch INPUTS... -o OUTDIR [--format msh|vtu|bdf|inp|obj|off] [-j N]\n"
    "                       [--size W | --adaptive [--dtheta DEG] [--min-size S]\n"
    "                       [--max-size S]] [--smooth N] [--chord-tol T] [--quiet]\n"
    "\n"
    "Meshes many parts in parallel, each exactly as `laytracks mesh` does (checked by\n"
    "quality.md before it is written), and writes OUTDIR/<name>.<format> for every part that\n"
    "meshes. A part that is refused or fails is reported with its message, and the others go\n"
    "on; nothing is written for it (a file left in OUTDIR by an earlier run stays as it was).\n"
    "\n"
    "INPUTS are any mix of\n"
    "  part files     a JSON part (brep/1), whatever its extension but .txt and .list\n"
    "  folders        every *.json inside, recursively, sorted by path (files inside OUTDIR\n"
    "                 are skipped)\n"
    "  list files     a .txt or .list file: one input (part file, folder or list file) per\n"
    "                 line; blank lines and lines starting with # are skipped; relative paths\n"
    "                 are taken from the list file's folder\n"
    "Parts are meshed in the order given; a file given twice is meshed once. An input that does\n"
    "not exist is a command-line error (status 2), found before any work. <name> is the part\n"
    "file's name without its extension; when two parts have the same name, each of them is\n"
    "written as <name>-<folder>, <folder> being the name of the folder that holds it, and if\n"
    "that is still not unique, -2, -3, ... are added in input order.\n"
    "\n"
    "Progress goes to stderr: a bar redrawn in place when stderr is a terminal, else one line\n"
    "per finished part. The end is a table on stdout, one row per part in input order\n"
    "(whatever the threads did): status (ok; refused: the part file is unreadable or breaks a\n"
    "rule of brep-json.md; failed: the mesher could not mesh it, its mesh failed its check, or\n"
    "its file could not be written), quads, nodes, smallest scaled Jacobian, % of quads with\n"
    "skew >= 30, aspect >= 5 and taper <= 0.8, seconds, and the error; then the totals.\n"
    "OUTDIR/batch-report.json holds the same rows, for scripts (written atomically, last).\n"
    "\n"
    "  -o OUTDIR        the output folder, made if missing\n"
    "  --format F       msh (default), vtu, bdf, inp, obj or off\n"
    "  -j N             parts meshed at once (default: the number of hardware threads);\n"
    "                   each part's passes use the hardware threads / N\n"
    "The meshing options apply to every part, as in `laytracks mesh`:\n"
    LAYTRACKS_MESHING_OPTIONS_HELP
    "  --quiet          no progress on stderr (the table is still printed)\n"
    "\n"
    "exit status: 0 every part meshed and written; 3 some part failed in the mesher (a face no\n"
    "template meshes, a mesh failing its check); else 4 some mesh file could not be written;\n"
    "else 1 some part was refused; 2 wrong command line or a missing input (nothing done).\n";

namespace {

namespace fs = std::filesystem;

/// One part to mesh.
struct Job {
  fs::path input;    ///< as found (the path given, or under a folder or list file given)
  std::string name;  ///< output file name without extension, unique in the batch
};

/// What became of one part.
struct Row {
  Status status = kOk;  ///< kOk, kInputRefused, kInternal or kIo
  std::string error;
  double size = 0.0;  ///< uniform: the element size; adaptive: MIN_END_WIDTH
  /// Uniform: the size asked for when no valid mesh came there (MeshPartResult::size_failed_at)
  double size_failed = 0.0;
  bool adaptive = false;
  double neighbour_ratio = 1.0;  ///< the worst size ratio of two neighbouring quads
  double fine_coarse = 1.0;      ///< mean size of the finest tenth over the coarsest tenth
  std::size_t quads = 0;
  std::size_t nodes = 0;
  double min_jacobian = 0.0;
  double skew_bad = 0.0;
  double aspect_bad = 0.0;
  double taper_bad = 0.0;
  double seconds = 0.0;
};

const char* status_word(Status s) {
  switch (s) {
    case kOk:
      return "ok";
    case kInputRefused:
      return "refused";
    default:
      return "failed";
  }
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_list_file(const fs::path& p) {
  const std::string ext = lower(p.extension().string());
  return ext == ".txt" || ext == ".list";
}

/// True when `p` lies inside folder `dir` (both made absolute and normal, no file access).
bool inside(const fs::path& p, const fs::path& dir) {
  const fs::path a = fs::absolute(p).lexically_normal();
  const fs::path d = fs::absolute(dir).lexically_normal();
  const auto mismatch = std::mismatch(d.begin(), d.end(), a.begin(), a.end());
  return mismatch.first == d.end() || (std::next(mismatch.first) == d.end() &&
                                       mismatch.first->empty());  // d ends with a separator
}

/// Expands the inputs into part files, in order. Throws UsageError naming every input that
/// does not exist (with the list file and line when it came from one).
class InputExpander {
 public:
  explicit InputExpander(fs::path outdir) : outdir_(std::move(outdir)) {}

  void add(const fs::path& input, const std::string& from = "") {
    std::error_code ec;
    const fs::file_status st = fs::status(input, ec);
    if (!fs::exists(st)) {
      missing_.push_back((from.empty() ? "" : from + ": ") + "\"" + input.string() + "\"");
      return;
    }
    if (fs::is_directory(st)) {
      add_folder(input);
    } else if (is_list_file(input)) {
      add_list(input);
    } else {
      add_part(input);
    }
  }

  std::vector<fs::path> parts() const {
    if (!missing_.empty()) {
      std::string names;
      for (const std::string& m : missing_) names += (names.empty() ? "" : ", ") + m;
      throw UsageError("batch: no such input" + std::string(missing_.size() > 1 ? "s: " : ": ") +
                       names);
    }
    if (parts_.empty()) {
      throw UsageError(std::string("batch: the inputs hold no part file") +
                       (skipped_in_outdir_ ? " (files inside OUTDIR are skipped)" : ""));
    }
    return parts_;
  }

 private:
  void add_part(const fs::path& p) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(p, ec);
    if (ec) key = fs::absolute(p).lexically_normal();
    if (seen_.insert(key.string()).second) parts_.push_back(p);
  }

  void add_folder(const fs::path& dir) {
    std::vector<fs::path> found;
    bool skipped_here = false;
    std::error_code ec;
    for (fs::recursive_directory_iterator
             it(dir, fs::directory_options::skip_permission_denied, ec),
         end;
         !ec && it != end; it.increment(ec)) {
      std::error_code kind;
      if (inside(it->path(), outdir_)) {  // our own outputs, the report among them
        if (it->is_directory(kind)) it.disable_recursion_pending();
        skipped_here = true;
        continue;
      }
      if (it->is_regular_file(kind) && lower(it->path().extension().string()) == ".json") {
        found.push_back(it->path());
      }
    }
    if (ec) throw Error("cannot read the folder " + dir.string() + ": " + ec.message());
    std::sort(found.begin(), found.end());
    skipped_in_outdir_ = skipped_in_outdir_ || skipped_here;
    if (found.empty() && !skipped_here) {
      std::fprintf(stderr, "laytracks: note: %s holds no .json file\n", dir.string().c_str());
    }
    for (const fs::path& p : found) add_part(p);
  }

  void add_list(const fs::path& list) {
    std::error_code ec;
    const std::string key = fs::weakly_canonical(list, ec).string();
    if (!open_lists_.insert(key).second) {
      throw UsageError("batch: the list file " + list.string() + " names itself (through " +
                       std::to_string(open_lists_.size()) + " list files)");
    }
    std::ifstream in(list);
    if (!in) throw InputError("cannot read the list file " + list.string());
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      const auto last = line.find_last_not_of(" \t\r");
      fs::path entry(line.substr(first, last - first + 1));
      if (entry.is_relative()) entry = list.parent_path() / entry;
      add(entry, list.string() + ":" + std::to_string(number));
    }
    open_lists_.erase(key);
  }

  fs::path outdir_;
  std::vector<fs::path> parts_;
  std::set<std::string> seen_;
  std::set<std::string> open_lists_;  ///< list files being read, to refuse a cycle
  bool skipped_in_outdir_ = false;
  std::vector<std::string> missing_;
};

/// Output names: the file stem; stems shared by several parts get "-<parent folder>", then
/// "-2", "-3", ... in input order while a name is still taken.
std::vector<Job> name_jobs(const std::vector<fs::path>& parts) {
  std::map<std::string, std::size_t> stem_count;
  for (const fs::path& p : parts) ++stem_count[p.stem().string()];
  std::vector<Job> jobs;
  std::set<std::string> taken;
  for (const fs::path& p : parts) {
    std::string name = p.stem().string();
    if (stem_count[name] > 1) {
      const std::string folder =
          fs::absolute(p).lexically_normal().parent_path().filename().string();
      if (!folder.empty()) name += "-" + folder;
    }
    std::string unique = name;
    for (int k = 2; !taken.insert(unique).second; ++k) unique = name + "-" + std::to_string(k);
    jobs.push_back({p, unique});
  }
  return jobs;
}

/// Meshes one part and writes its file; every error becomes the row's status and message.
Row run_job(const Job& job, const MeshingOptions& options, const fs::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  Row row;
  bool writing = false;
  try {
    const Part part = read_part(job.input.string(), options.build);
    const MeshPartResult r = mesh_part(part, options.mesh);
    row.size = r.size;
    if (r.size_failed_at) row.size_failed = *r.size_failed_at;
    row.adaptive = r.adaptive;
    row.neighbour_ratio = r.quality.worst_neighbour_ratio;
    row.fine_coarse = r.quality.fine_coarse_ratio;
    row.quads = r.quality.quads;
    row.nodes = r.quality.nodes;
    const auto& m = r.quality.measures;
    row.min_jacobian = m[6].worst;
    row.skew_bad = m[0].bad_percent;
    row.aspect_bad = m[1].bad_percent;
    row.taper_bad = m[2].bad_percent;
    writing = true;  // from here on, a failure is the write's
    write_part_mesh(out.string(), part, r.mesh);
  } catch (const InputError& e) {
    row.status = kInputRefused;
    row.error = e.what();
  } catch (const InternalError& e) {  // InvalidMeshError too
    row.status = kInternal;
    row.error = e.what();
  } catch (const Error& e) {
    row.status = writing ? kIo : kInternal;
    row.error = e.what();
  } catch (const std::exception& e) {
    row.status = kInternal;
    row.error = e.what();
  }
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

/// One line, for a table cell or a progress line: newlines and tabs become spaces.
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return s;
}

/// Progress on stderr, called by the workers under a lock.
class Progress {
 public:
  Progress(std::size_t total, bool quiet)
      : total_(total), quiet_(quiet), terminal_(isatty(STDERR_FILENO) != 0) {
    if (!quiet_ && terminal_) draw();
  }

  void finished(const Job& job, const Row& row) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    if (row.status == kInputRefused) ++refused_;
    if (row.status != kOk && row.status != kInputRefused) ++failed_;
    if (quiet_) return;
    const int width = static_cast<int>(std::to_string(total_).size());
    std::string line;
    if (row.status == kOk) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "ok, %zu quads, min scaled Jacobian %.3f, %.2f s", row.quads,
                    row.min_jacobian, row.seconds);
      line = buf;
      if (row.size_failed > 0.0) {
        std::snprintf(buf, sizeof buf, " (meshed at size %g: at %g no valid mesh came)", row.size,
                      row.size_failed);
        line += buf;
      }
    } else {
      line = std::string(status_word(row.status)) + ": " + one_line(row.error);
    }
    if (terminal_) {
      // Failures are kept above the bar; successes only move it.
      if (row.status != kOk) {
        std::fprintf(stderr, "\r%-*s\r%s: %s\n", static_cast<int>(bar_width_), "", job.name.c_str(),
                     line.c_str());
      }
      draw();
    } else {
      std::fprintf(stderr, "[%*zu/%zu] %s: %s\n", width, done_, total_, job.name.c_str(),
                   line.c_str());
    }
    std::fflush(stderr);
  }

  void end() {
    if (!quiet_ && terminal_) std::fprintf(stderr, "\n");
  }

 private:
  void draw() {
    constexpr std::size_t kBar = 30;
    const std::size_t filled = total_ ? done_ * kBar / total_ : kBar;
    std::string s = "[" + std::string(filled, '#') + std::string(kBar - filled, '.') + "] " +
                    std::to_string(done_) + "/" + std::to_string(total_) + " parts";
    if (refused_) s += "  " + std::to_string(refused_) + " refused";
    if (failed_) s += "  " + std::to_string(failed_) + " failed";
    bar_width_ = std::max(bar_width_, s.size());
    std::fprintf(stderr, "\r%-*s", static_cast<int>(bar_width_), s.c_str());
    std::fflush(stderr);
  }

  std::mutex mutex_;
  std::size_t total_;
  bool quiet_;
  bool terminal_;
  std::size_t done_ = 0;
  std::size_t refused_ = 0;
  std::size_t failed_ = 0;
  std::size_t bar_width_ = 0;
};

void print_table(const std::vector<Job>& jobs,
                 const std::vector<Row>& rows,
                 double wall,
                 std::size_t threads) {
  std::size_t w = 4;
  for (const Job& j : jobs) w = std::max(w, j.name.size());
  const int pw = static_cast<int>(w);
  std::printf("%-*s  %-7s %9s %9s %8s %8s %8s %8s %8s  %s\n", pw, "part", "status", "quads",
              "nodes", "min SJ", "skew%", "aspect%", "taper%", "seconds", "error");
  std::size_t ok = 0, refused = 0, failed = 0, quads = 0, nodes = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Row& r = rows[i];
    if (r.status == kOk) {
      ++ok;
      quads += r.quads;
      nodes += r.nodes;
      std::printf("%-*s  %-7s %9zu %9zu %8.3f %8.1f %8.1f %8.1f %8.2f\n", pw, jobs[i].name.c_str(),
                  "ok", r.quads, r.nodes, r.min_jacobian, r.skew_bad, r.aspect_bad, r.taper_bad,
                  r.seconds);
    } else {
      (r.status == kInputRefused ? refused : failed) += 1;
      std::printf("%-*s  %-7s %9s %9s %8s %8s %8s %8s %8.2f  %s\n", pw, jobs[i].name.c_str(),
                  status_word(r.status), "-", "-", "-", "-", "-", "-", r.seconds,
                  one_line(r.error).c_str());
    }
  }
  std::printf(
      "%zu part%s: %zu ok, %zu refused, %zu failed; %zu quads, %zu nodes; wall time %.2f s with "
      "%zu thread%s\n",
      jobs.size(), jobs.size() == 1 ? "" : "s", ok, refused, failed, quads, nodes, wall, threads,
      threads == 1 ? "" : "s");
  std::printf(
      "(skew%%, aspect%%, taper%%: %% of quads with skew >= 30, aspect >= 5, taper <= "
      "0.8)\n");
}

void write_report(const fs::path& path,
                  const std::vector<Job>& jobs,
                  const std::vector<Row>& rows,
                  const std::vector<fs::path>& outputs,
                  const std::string& format,
                  const MeshingOptions& options,
                  double wall,
                  std::size_t threads) {
  nlohmann::ordered_json doc;
  doc["format"] = format;
  doc["size"] = options.mesh.size ? nlohmann::ordered_json(*options.mesh.size) : nullptr;
  doc["adaptive"] = options.mesh.adaptive.value_or(false);
  doc["dtheta_deg"] =
      options.mesh.dtheta_deg ? nlohmann::ordered_json(*options.mesh.dtheta_deg) : nullptr;
  doc["smooth"] = options.mesh.smooth;
  doc["chord_tol"] =
      options.build.chord_tol ? nlohmann::ordered_json(*options.build.chord_tol) : nullptr;
  doc["threads"] = threads;
  auto& parts = doc["parts"] = nlohmann::ordered_json::array();
  std::size_t ok = 0, refused = 0, failed = 0, quads = 0, nodes = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Row& r = rows[i];
    nlohmann::ordered_json p;
    p["part"] = jobs[i].name;
    p["input"] = jobs[i].input.string();
    p["status"] = status_word(r.status);
    if (r.status == kOk) {
      ++ok;
      quads += r.quads;
      nodes += r.nodes;
      p["output"] = outputs[i].string();
      p["mode"] = r.adaptive ? "adaptive" : "uniform";
      p[r.adaptive ? "min_end_width" : "size"] = r.size;
      p["quads"] = r.quads;
      p["nodes"] = r.nodes;
      p["min_scaled_jacobian"] = r.min_jacobian;
      p["skew_bad_percent"] = r.skew_bad;
      p["aspect_bad_percent"] = r.aspect_bad;
      p["taper_bad_percent"] = r.taper_bad;
      p["worst_neighbour_size_ratio"] = r.neighbour_ratio;
      p["fine_coarse_size_ratio"] = r.fine_coarse;
      p["error"] = nullptr;
    } else {
      (r.status == kInputRefused ? refused : failed) += 1;
      p["output"] = nullptr;
      p["error"] = r.error;
    }
    p["seconds"] = r.seconds;
    parts.push_back(std::move(p));
  }
  doc["totals"] = {{"parts", jobs.size()}, {"ok", ok},       {"refused", refused},
                   {"failed", failed},     {"quads", quads}, {"nodes", nodes},
                   {"seconds", wall}};
  write_file_atomically(path.string(), [&](std::ostream& o) { o << doc.dump(2) << '\n'; });
}

}  // namespace

int run_batch(const std::vector<std::string>& argv_in) {
  // -jN is -j N.
  std::vector<std::string> argv;
  for (const std::string& a : argv_in) {
    if (a.size() > 2 && a.compare(0, 2, "-j") == 0 &&
        std::isdigit(static_cast<unsigned char>(a[2]))) {
      argv.push_back("-j");
      argv.push_back(a.substr(2));
    } else {
      argv.push_back(a);
    }
  }
  const Args args = meshing_args(argv, {"-o", "--format", "-j"}, {"--quiet"});
  if (args.positional().empty()) throw UsageError("batch needs at least one input");
  const auto outdir_arg = args.value("-o");
  if (!outdir_arg) throw UsageError("batch needs -o OUTDIR");
  const fs::path outdir(*outdir_arg);
  std::string format = lower(args.value("--format").value_or("msh"));
  if (!format.empty() && format[0] == '.') format.erase(0, 1);
  {
    std::string known;
    bool ok = false;
    for (const std::string& e : mesh_output_extensions()) {
      ok = ok || e == "." + format;
      known += (known.empty() ? "" : " ") + e.substr(1);
    }
    if (!ok) throw UsageError("--format is one of " + known + ", got \"" + format + "\"");
  }
  std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
  if (const auto j = args.count("-j", 1024)) {
    if (*j < 1) throw UsageError("option -j needs a whole number from 1 to 1024, got \"0\"");
    threads = static_cast<std::size_t>(*j);
  }
  const MeshingOptions options = meshing_options(args);
  const bool quiet = args.flag("--quiet");
  const auto t0 = std::chrono::steady_clock::now();

  InputExpander expander(outdir);
  for (const std::string& in : args.positional()) expander.add(in);
  const std::vector<Job> jobs = name_jobs(expander.parts());

  {
    std::error_code ec;
    if (fs::exists(outdir, ec) && !fs::is_directory(outdir, ec)) {
      throw Error("cannot make the output folder " + outdir.string() + ": a file has that name");
    }
    fs::create_directories(outdir, ec);
    if (ec) throw Error("cannot make the output folder " + outdir.string() + ": " + ec.message());
  }
  std::vector<fs::path> outputs;
  for (const Job& job : jobs) outputs.push_back(outdir / (job.name + "." + format));

  threads = std::min(threads, jobs.size());
  // Parts at once share the cores: each part's passes get the rest (1 with -j at the core
  // count; all of them for one part at a time).
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  set_mesher_threads(std::max<std::size_t>(1, cores / std::max<std::size_t>(1, threads)));
  std::vector<Row> rows(jobs.size());
  Progress progress(jobs.size(), quiet);
  std::atomic<std::size_t> next{0};
  const auto worker = [&]() {
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      rows[i] = run_job(jobs[i], options, outputs[i]);
      progress.finished(jobs[i], rows[i]);
    }
  };
  std::vector<std::thread> pool;
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  } catch (const std::system_error&) {
    // No more threads to be had: the ones running (and this one) share the parts.
  }
  threads = pool.size() + 1;
  worker();
  for (std::thread& t : pool) t.join();
  progress.end();

  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_table(jobs, rows, wall, threads);
  std::fflush(stdout);
  write_report(outdir / "batch-report.json", jobs, rows, outputs, format, options, wall, threads);

  bool internal = false, io = false, refused = false;
  for (const Row& r : rows) {
    internal = internal || r.status == kInternal;
    io = io || r.status == kIo;
    refused = refused || r.status == kInputRefused;
  }
  return internal ? kInternal : io ? kIo : refused ? kInputRefused : kOk;
}

}  // namespace laytracks::cli
