#include "laytracks/mesher/mesh_part.hpp"

#include <chrono>

#include "laytracks/brep/error.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/medial/part_medial.hpp"

namespace laytracks {

double default_element_size(const Part& part) { return part.size / 40.0; }

namespace {

class Clock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

MeshPartResult mesh_part(const Part& part, const MeshPartOptions& options, const StageFn& on_stage) {
  auto stage = [&](const char* name) {
    if (on_stage) on_stage(name);
  };
  MeshPartResult r;
  r.size = options.size.value_or(part.mesh.size.value_or(default_element_size(part)));
  Clock clock;
  stage("medial");
  const std::vector<MedialAxis> axes = compute_medial_axes(part);
  r.times.medial = clock.lap();
  stage("rails");
  CutGraphOptions cg;
  cg.track_width = r.size;
  const CutGraph graph = build_cut_graph(part, axes, cg);
  if (!graph.problems.empty()) {
    throw InternalError("rails: " + graph.problems.front() + " (" +
                        std::to_string(graph.problems.size()) + " problems)");
  }
  r.rail_chains = graph.chains.size();
  r.tracks = graph.track_count;
  r.times.rails = clock.lap();
  stage("quads");
  QuadOptions qo;
  qo.size = r.size;
  QuadResult quads = build_quads(part, graph, qo);
  r.mesh = std::move(quads.mesh);
  r.stats = quads.stats;
  r.times.quads = clock.lap();
  if (options.smooth > 0) {
    stage("smooth");
    r.before_smoothing = summarize(part, r.mesh);
    smooth_mesh(part, r.mesh, options.smooth);
    r.times.smooth = clock.lap();
  }
  stage("check");
  r.check = check_mesh(part, r.mesh);
  r.quality = summarize(part, r.mesh);
  if (options.smooth <= 0) r.before_smoothing = r.quality;
  r.times.check = clock.lap();
  if (!r.check.valid()) {
    std::string first = r.check.failures.empty() ? "" : r.check.failures.front().message;
    throw InvalidMeshError("the mesh failed its self-check, nothing written: " + first,
                           std::move(r.mesh), r.check);
  }
  return r;
}

}  // namespace laytracks
