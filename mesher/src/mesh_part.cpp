#include "laytracks/mesher/mesh_part.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fill.hpp"
#include "laytracks/brep/error.hpp"
#include "laytracks/brep/self_contact.hpp"
#include "laytracks/cutgraph/adaptive.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/medial/part_medial.hpp"

namespace laytracks {

double part_extent(const Part& part) {
  // The part's size counts the file's vertices only; an arc can reach far beyond them (a disk
  // of radius 20 given by a chord of 7 and the arc over it: size 7, the default element size
  // 0.17 and 150,000 quads). With the arcs' points too, the larger of the two.
  Vec3 c{0.0, 0.0, 0.0};
  std::size_t n = 0;
  for (const Patch& patch : part.patches)
    for (const Loop& loop : patch.loops)
      for (VertexId v : loop.vertices) {
        c = c + part.vertices[v.index()].position;
        ++n;
      }
  if (n == 0) return part.size;
  c = (1.0 / static_cast<double>(n)) * c;
  double reach = 0.0;
  for (const Patch& patch : part.patches)
    for (const Loop& loop : patch.loops)
      for (VertexId v : loop.vertices) reach = std::max(reach, distance(c, part.vertices[v.index()].position));
  return std::max(part.size, 2.0 * reach);
}

double default_element_size(const Part& part) { return part_extent(part) / 40.0; }

double uniform_element_size(const Part& part,
                            const MeshPartOptions& options,
                            std::optional<double>* capped_from) {
  const double asked = options.size.value_or(part.mesh.size.value_or(default_element_size(part)));
  const double cap = kMaxSizeFraction * part_extent(part);
  if (!(asked > cap)) return asked;
  if (capped_from) *capped_from = asked;
  return cap;
}

namespace {

/// After the late flips (those the smoothing made worthwhile), the nodes within this many rings
/// of quads of a flipped pair are smoothed again, not the whole mesh: cgal_wiggly_03_cgal spent
/// 0.05 s of its 0.37 s smoothing everything again for one flip.
constexpr int kResmoothRings = 3;
/// Rounds of the late slides and flips (session 40: a second and third round took the sets'
/// taper <= 0.8 down on all six sets, 1.1% of the sum, the worst corner lower on one mesh of
/// 402 by 3e-4).
constexpr int kLateRounds = 3;
/// The slides for a taper are undone when the mesh's worst corner ends more than this below
/// where the short-edge slides alone take it (a 45-degree corner moved in its last bits is
/// the same corner).
constexpr double kLateSlideSlack = 1e-3;
/// Boundary pieces split at most this many times in the third attempt (two edges each): the
/// needle faces mended take one or two (docs/mesher.md, "Split boundary pieces").
constexpr int kPieceSplits = 4;
/// Only for a face of at most this many nodes: the needles' faces (6 to 14 nodes); a larger
/// face no template fills (comb_spikes_sector's of 58) was not mended by four splits, which
/// cost 0.9 s before the retry at a smaller size that meshes it. And once per face: a face
/// that one split did not mend was not mended by three more either (fuzz seed 62062's
/// extreme_016, 10 to 16 nodes, at four sizes: 11.8 -> 17.8 s before the size that meshes).
constexpr std::size_t kPieceSplitFaceNodes = 16;
/// Hubs (mesh_part_with_hubs): a part is meshed again without its hubs' rails only when more
/// than this % of its quads are beyond Table III's thresholds (skew, aspect and taper added
/// up: the paper's taper figure, 10.4%): the second run costs as much as the first.
constexpr double kHubTry = 10.4;
/// The mesh without a hub's rails is kept when its quads beyond Table III's thresholds are
/// fewer by this many points of % ...
constexpr double kHubGain = 0.5;
/// ... and its worst corner no lower than min(the first's, kRefillBelowUniform) - this.
constexpr double kHubWorstDrop = 0.05;

/// The smallest corner scaled Jacobian of the mesh's quads, each in its patch's frame.
double worst_scaled_jacobian(const Part& part, const QuadMesh& mesh) {
  double worst = std::numeric_limits<double>::infinity();
  for (const MeshElement& e : mesh.elements) {
    const Frame& frame = part.patches[e.patch.index()].frame;
    std::array<Vec2, 4> p;
    for (std::size_t i = 0; i < 4; ++i) p[i] = frame.to_2d(mesh.nodes[e.nodes[i]]);
    worst = std::min(worst, mesher_detail::min_scaled_jacobian(p[0], p[1], p[2], p[3]));
  }
  return worst;
}

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

CutGraphOptions cut_graph_options(const Part& part,
                                  std::vector<MedialAxis>& axes,
                                  const MeshPartOptions& options,
                                  std::unique_ptr<TrackWidthLaw>& law,
                                  std::optional<double>* size_capped_from) {
  CutGraphOptions cg;
  cg.drop_crowded_rails = options.drop_crowded_rails;
  law.reset();
  if (options.adaptive.value_or(part.mesh.mode == MeshMode::Adaptive)) {
    AdaptiveOptions ao;
    ao.dtheta =
        options.dtheta_deg.value_or(part.mesh.dtheta_deg.value_or(kDefaultDthetaDeg)) * kPi / 180.0;
    if (options.min_size) ao.min_size = *options.min_size;
    if (options.max_size) ao.max_size = *options.max_size;
    law = std::make_unique<TrackWidthLaw>(part, axes, ao);
    cg.adaptive = law.get();
  } else {
    cg.track_width = uniform_element_size(part, options, size_capped_from);
  }
  const double h = law ? law->end_width() : cg.track_width;
  if (h > 0.0)
    for (MedialAxis& axis : axes) axis.choose_round_holes(h);
  return cg;
}

namespace {

/// A part's medial axes and rails (mesh_part's first two stages) and the figures they give
/// (`head`: the mode, the size, the rails' counts and the two stages' times). Filled in place
/// and never moved: the width law and the cut graph read the axes where they are.
struct LaidRails {
  std::vector<MedialAxis> axes;
  std::unique_ptr<TrackWidthLaw> law;
  CutGraph graph;
  MeshPartResult head;
};

void lay_rails(const Part& part,
               const MeshPartOptions& options,
               const StageFn& on_stage,
               LaidRails& laid) {
  auto stage = [&](const char* name) {
    if (on_stage) on_stage(name);
  };
  MeshPartResult& r = laid.head;
  Clock clock;
  stage("medial");
  laid.axes = compute_medial_axes(part);
  r.times.medial = clock.lap();
  stage("rails");
  std::unique_ptr<TrackWidthLaw>& law = laid.law;
  const CutGraphOptions cg = cut_graph_options(part, laid.axes, options, law, &r.size_capped_from);
  // The mode and the size as cut_graph_options chose them.
  r.adaptive = law != nullptr;
  r.size = law ? law->end_width() : cg.track_width;
  if (law) r.dtheta_deg = law->options().dtheta * 180.0 / kPi;
  // A size so small that the mesh could not fit in memory is refused before any work (a
  // rectangle at 1e-10 ran out of memory; at 1e-300 the counts overflowed to a 6-quad mesh).
  if (!law) {
    double area = 0.0;
    for (const Patch& patch : part.patches) area += patch.area;
    const double estimate = area / (r.size * r.size);
    if (!(estimate <= kMaxEstimatedQuads)) {
      std::ostringstream s;
      s << "element size " << r.size << " would give about " << estimate
        << " quads (the part's area " << area << " over the size squared); at most "
        << kMaxEstimatedQuads << " are meshed: choose a larger size";
      throw InputError(s.str());
    }
  }
  laid.graph = build_cut_graph(part, laid.axes, cg);
  const CutGraph& graph = laid.graph;
  if (!graph.problems.empty()) {
    throw InternalError("rails: " + graph.problems.front() + " (" +
                        std::to_string(graph.problems.size()) + " problems)");
  }
  r.rail_chains = graph.chains.size();
  r.spiral_closures = graph.spiral_closures;
  r.loop_closures = graph.loop_closures;
  r.rail_merges = graph.rail_merges;
  r.crowded_rails = graph.crowded_rails;
  r.crowded_seeds = graph.crowded_seeds;
  r.tracks = graph.track_count;
  r.times.rails = clock.lap();
}

/// The quads on laid rails, re-filled, smoothed and checked (mesh_part's stages from "quads"
/// on); the patches in `drop_hubs` without their hubs' rails (docs/mesher.md, "Hubs").
MeshPartResult mesh_on_rails(const Part& part,
                             const MeshPartOptions& options,
                             const StageFn& on_stage,
                             const LaidRails& laid,
                             const std::vector<std::uint32_t>& drop_hubs = {}) {
  auto stage = [&](const char* name) {
    if (on_stage) on_stage(name);
  };
  MeshPartResult r = laid.head;
  const CutGraph& graph = laid.graph;
  const std::unique_ptr<TrackWidthLaw>& law = laid.law;
  Clock clock;
  stage("quads");
  QuadOptions qo;
  qo.size = r.size;
  qo.adaptive = law.get();
  qo.drop_hubs = drop_hubs;
  // A face that no template fills is most often a needle of a sawtooth outline cut off by
  // rails: a second attempt drops those rails (docs/mesher.md, "Sliver caps"). Only then, so
  // that every part meshed at the first attempt keeps its mesh. A third attempt also drops
  // the rails that cross another edge (in a sawtooth's teeth), and lets a face whose own
  // outline has a needle's tip (a corner of a thousandth of a degree) keep a quad as thin as
  // that tip ("Needle tips"). When all fail, the first one's message stands.
  // In the third attempt, a face that no template fills has its boundary piece of the longest
  // mesh edge given two more edges (the needle whose one side is a single long edge, the other
  // bent at reflex vertices that each need an inner edge), up to kPieceSplits times
  // (docs/mesher.md, "Split boundary pieces").
  // The attempts after the first meet most faces unchanged: they take the quads the
  // templates gave them before (the same to the bit; docs/mesher.md, "Retried faces").
  auto face_memo = std::make_unique<mesher_detail::FaceFillMemo>();
  qo.face_memo = face_memo.get();
  QuadResult quads;
  std::exception_ptr first_failure;
  int splits = 0;
  std::vector<std::string> split_faces;  // the faces whose pieces were split
  for (int attempt = 0;;) {
    qo.drop_sliver_caps = attempt >= 1;
    qo.needle_tips = attempt >= 2;
    try {
      quads = build_quads(part, graph, qo);
      break;
    } catch (const UnfilledFace& unfilled) {  // only in the third attempt (needle_tips)
      if (!first_failure) first_failure = std::current_exception();
      if (splits < kPieceSplits && unfilled.nodes <= kPieceSplitFaceNodes &&
          std::find(split_faces.begin(), split_faces.end(), unfilled.where) == split_faces.end() &&
          !unfilled.pieces.empty()) {
        qo.split_pieces.push_back(unfilled.pieces.front());
        split_faces.push_back(unfilled.where);
        ++splits;
      } else {
        std::rethrow_exception(first_failure);
      }
    } catch (const InternalError&) {
      if (!first_failure) first_failure = std::current_exception();
      if (attempt == 2) std::rethrow_exception(first_failure);
      ++attempt;
    }
  }
  qo.face_memo = nullptr;
  face_memo.reset();  // its quads are in the mesh now
  quads.stats.split_pieces = static_cast<std::size_t>(splits);
  r.mesh = std::move(quads.mesh);
  r.stats = quads.stats;
  r.hubs = std::move(quads.hubs);
  r.stats.edge_flips = flip_edges(part, r.mesh);
  r.stats.thin_rows = merge_thin_rows(part, r.mesh);
  r.stats.corner_kites = fold_corner_kites(part, r.mesh);
  r.stats.corner_reliefs = fold_corner_reliefs(part, r.mesh);
  if (!r.adaptive) r.stats.thin_bends = square_thin_bends(part, r.mesh, r.size, options.smooth);
  r.times.quads = clock.lap();
  // The quads round the worst quads filled again where that beats what the smoothing alone
  // could do; before the smoothing, whose result differs between poses of a part (relaxation
  // amplifies rounding), while the templates' nodes do not: the re-fills and so the counts
  // are the same in every pose.
  stage("refill");
  r.stats.cavity_refills =
      refill_cavities(part, r.mesh, options.smooth,
                      r.adaptive ? kRefillBelowAdaptive : kRefillBelowUniform, &r.stats.regrids);
  r.times.refill = clock.lap();
  if (options.smooth > 0) {
    stage("smooth");
    r.before_smoothing = summarize(part, r.mesh);
    smooth_mesh(part, r.mesh, options.smooth);
    // Rail feet crowding an arc point or a vertex slid apart along the boundary, judged on
    // the smoothed quads (counts do not change); then the flips the smoothing made
    // worthwhile, and the nodes round what changed smoothed again.
    struct Late {
      std::size_t slid = 0, for_taper = 0, flips = 0;
    };
    const auto late = [&](QuadMesh& mesh, bool tapered) {
      Late done;
      std::vector<std::uint32_t> slid;
      done.slid = slide_boundary_nodes(part, mesh, &slid, tapered, &done.for_taper);
      std::vector<std::uint32_t> flipped;
      done.flips = flip_edges(part, mesh, &flipped);
      if (done.flips > 0 || !slid.empty()) {
        // Only round what changed: the nodes within kResmoothRings rings of the flipped quads
        // and of the slid nodes.
        std::vector<bool> movable(mesh.nodes.size(), false);
        for (std::uint32_t q : flipped)
          for (std::uint32_t v : mesh.elements[q].nodes) movable[v] = true;
        for (std::uint32_t v : slid) movable[v] = true;
        for (int ring = 1; ring < kResmoothRings; ++ring) {
          std::vector<bool> next = movable;
          for (const MeshElement& e : mesh.elements) {
            if (std::none_of(e.nodes.begin(), e.nodes.end(),
                             [&](std::uint32_t v) { return movable[v]; }))
              continue;
            for (std::uint32_t v : e.nodes) next[v] = true;
          }
          movable = std::move(next);
        }
        smooth_mesh(part, mesh, options.smooth, &movable);
      }
      return done;
    };
    // Feet beside tapered quads slide too, unless the mesh's worst corner ends lower than with
    // the short-edge slides alone (the flips and the smoothing round the slid nodes cascade:
    // docs/mesher.md, "Sliding boundary nodes"). `plain` keeps the smoothed mesh for that.
    QuadMesh plain = r.mesh;
    Late done = late(r.mesh, true);
    if (done.for_taper > 0) {
      const Late plain_done = late(plain, false);
      if (worst_scaled_jacobian(part, r.mesh) <
          worst_scaled_jacobian(part, plain) - kLateSlideSlack) {
        r.mesh = std::move(plain);
        done = plain_done;
      }
    }
    // Again while nodes slide (a slide and the smoothing round it leave the next node's quads
    // tapered or not), up to kLateRounds in all, each kept only when the mesh's worst corner
    // ends no more than kLateSlideSlack lower.
    r.stats.late_rounds = 1;
    for (int round = 1; round < kLateRounds && done.slid > 0; ++round) {
      QuadMesh before = r.mesh;
      const double worst_before = worst_scaled_jacobian(part, r.mesh);
      const Late more = late(r.mesh, true);
      if (worst_scaled_jacobian(part, r.mesh) < worst_before - kLateSlideSlack) {
        r.mesh = std::move(before);
        break;
      }
      done.slid += more.slid;
      done.flips += more.flips;
      ++r.stats.late_rounds;
      if (more.slid == 0) break;
    }
    r.stats.slid_nodes = done.slid;
    r.stats.edge_flips += done.flips;
    r.times.smooth = clock.lap();
  } else {
    r.stats.slid_nodes = slide_boundary_nodes(part, r.mesh);
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

/// The share of a mesh's quads beyond Table III's thresholds (skew, aspect, taper), in %.
double beyond_table3(const QualitySummary& q) {
  return q.measures[0].bad_percent + q.measures[1].bad_percent + q.measures[2].bad_percent;
}

/// Hubs (docs/mesher.md, "Hubs"): a part whose rails meet at a hub in some patch, and whose
/// mesh has more than kHubTry % of its quads beyond Table III's thresholds, is meshed again
/// with those rails gone, and that mesh is kept when its quads beyond Table III's
/// thresholds are fewer by kHubGain points of % and its worst corner is no lower than
/// min(the first's, kRefillBelowUniform) - kHubWorstDrop. Where it gives no mesh, the first
/// stands.
MeshPartResult mesh_part_with_hubs(const Part& part,
                                   const MeshPartOptions& options,
                                   const StageFn& on_stage) {
  LaidRails laid;
  lay_rails(part, options, on_stage, laid);
  MeshPartResult first = mesh_on_rails(part, options, on_stage, laid);
  if (first.hubs.empty() || !(beyond_table3(first.quality) > kHubTry)) return first;
  // The second run starts from the same rails; the stages after them are timed for both runs
  // (the report's seconds add up to what the user waited).
  const auto add_times = [](StageTimes& to, const StageTimes& from) {
    to.quads += from.quads;
    to.refill += from.refill;
    to.smooth += from.smooth;
    to.check += from.check;
  };
  try {
    MeshPartResult second = mesh_on_rails(part, options, on_stage, laid, first.hubs);
    const double worst_first = first.quality.measures[6].worst;
    if (beyond_table3(second.quality) < beyond_table3(first.quality) - kHubGain &&
        second.quality.measures[6].worst >=
            std::min(worst_first, kRefillBelowUniform) - kHubWorstDrop) {
      second.hubs.clear();
      add_times(second.times, first.times);
      return second;
    }
    add_times(first.times, second.times);
  } catch (const InternalError&) {
  }
  return first;
}

}  // namespace

MeshPartResult mesh_part(const Part& part,
                         const MeshPartOptions& options,
                         const StageFn& on_stage) {
  try {
    return mesh_part_with_hubs(part, options, on_stage);
  } catch (const InternalError& e) {
    // A uniform size capped at kMaxSizeFraction x the part's extent asks for the coarsest mesh
    // there is; where that fails (a stadium whose faces at that size are bays round a slot's
    // round end: fuzz seed 44044's extreme_094), the sizes kCappedRetry x the cap are tried in
    // turn; any other uniform size that fails, kFailedRetry x it, unless the outline folds
    // back within kSelfContactRel of the part's size (refused below, as it fails at most
    // sizes: fuzz seed 52052's blob_009 at every share). The same in every pose.
    std::optional<double> asked;
    const double size = uniform_element_size(part, options, &asked);
    // Only on failure: a needle's sides come as close, and such parts mesh.
    const auto contact = closest_self_contact(part, kSelfContactRel * part.size);
    // The first of `shares` x size that meshes, if any.
    const auto retry = [&](const auto& shares) -> std::optional<MeshPartResult> {
      for (const double share : shares) {
        MeshPartOptions smaller = options;
        smaller.size = share * size;
        try {
          LaidRails laid;
          lay_rails(part, smaller, on_stage, laid);
          MeshPartResult r = mesh_on_rails(part, smaller, on_stage, laid);
          r.size_capped_from = asked;
          r.size_failed_at = size;
          r.failed_because = e.what();
          return r;
        } catch (const InternalError&) {
        }
      }
      return std::nullopt;
    };
    bool retried = false;
    if (!options.adaptive.value_or(part.mesh.mode == MeshMode::Adaptive) && (asked || !contact)) {
      if (std::optional<MeshPartResult> r = asked ? retry(kCappedRetry) : retry(kFailedRetry))
        return std::move(*r);
      retried = true;
    }
    if (contact) {
      throw InputError(describe(part, *contact) +
                       "; an outline folded back that close leaves no room for a valid mesh "
                       "(the mesher: " +
                       e.what() + ")");
    }
    // Say what was tried, so that the message is not read as one size's failure alone.
    if (retried) throw InternalError(ladder_failure(e.what(), asked.has_value(), size));
    throw;
  }
}

std::string ladder_failure(const std::string& first, bool capped, double size) {
  const auto listed = [](const auto& shares) {
    std::ostringstream o;
    for (std::size_t i = 0; i < shares.size(); ++i)
      o << (i == 0 ? " " : i + 1 == shares.size() ? " and " : ", ") << shares[i];
    return o.str();
  };
  std::ostringstream tried;
  tried << first << "; tried again at" << (capped ? listed(kCappedRetry) : listed(kFailedRetry))
        << " of the element size " << size << ": no valid mesh either";
  return tried.str();
}

}  // namespace laytracks
