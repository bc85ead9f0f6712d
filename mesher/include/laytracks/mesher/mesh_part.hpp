// The whole pipeline for one part: medial axes, rails, quads, smoothing, the self-check.
// Shared by `laytracks mesh`, `batch`, the benchmark and the tests.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/error.hpp"
#include "laytracks/brep/part.hpp"
#include "laytracks/cutgraph/adaptive.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/check.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// The part's extent: the larger of Part::size and twice the largest distance of a loop point
/// (vertices and arc points) from their centroid (the same in every pose).
double part_extent(const Part& part);

/// Default element size when neither the command line nor the part's mesh.size gives one:
/// 1/40 of part_extent.
double default_element_size(const Part& part);

/// The largest uniform element size, as a fraction of part_extent. A larger size is capped to
/// it. Beyond it every rail gets one step, faces come down to a handful of nodes, and the
/// templates fail: of the 5 fuzzed parts meshed at 1.5 to 20 times their extent, all passed
/// capped at 0.25 and at 0.35, one failed at 0.5, four at 1.
constexpr double kMaxSizeFraction = 0.25;
/// When the mesh fails at a capped size (mesh_part), these shares of the cap are tried in turn.
constexpr std::array<double, 3> kCappedRetry = {0.8, 0.64, 0.5};
/// When the mesh fails at a uniform size that was not capped (an internal error: no template
/// fills a face, or the self-check refuses the mesh), these shares of it are tried in turn
/// (mesh_part), the same in every pose; the size asked for stays in size_failed_at. Fuzz seed
/// 48048's split_083 (a comb of spikes of 0.05 degrees in one face) fails at its size and
/// meshes at 0.9 of it. Not tried where the outline folds back within kSelfContactRel of the
/// part's size (refused as folded, as before).
constexpr std::array<double, 5> kFailedRetry = {0.9, 0.8, 0.64, 0.5, 0.4};

/// The error of a part that no size of the ladder meshed: the first size's failure `first`,
/// then "; tried again at 0.9, 0.8, 0.64, 0.5 and 0.4 of the element size S: no valid mesh
/// either" (kFailedRetry; kCappedRetry when the size was `capped`).
std::string ladder_failure(const std::string& first, bool capped, double size);

/// The threads each mesh_part call uses for its passes (face fills, re-fill, smoothing); 0
/// (the default): as many as the machine has. LAYTRACKS_THREADS in the environment, when set,
/// takes precedence. The output does not depend on it. `batch`, which meshes several parts at
/// once, gives each its share of the cores.
void set_mesher_threads(std::size_t threads);

/// Default smoothing sweeps of `laytracks mesh` (docs/mesher.md says why).
constexpr int kDefaultSmooth = 10;

/// Uniform mode refuses (InputError) an element size that would give more quads than this,
/// estimated as the part's area over the size squared: about 10 GB of mesh.
constexpr double kMaxEstimatedQuads = 5e7;

struct MeshPartOptions {
  std::optional<double> size;  ///< element size; default: mesh.size, else default_element_size
  int smooth = kDefaultSmooth;  ///< Laplacian sweeps over interior nodes (0: none)
  /// Adaptive mode (Algorithm III); default: the part's mesh.mode.
  std::optional<bool> adaptive;
  /// Delta theta_in of adaptive mode, degrees; default: mesh.dtheta_deg, else
  /// kDefaultDthetaDeg.
  std::optional<double> dtheta_deg;
  std::optional<double> min_size;  ///< adaptive: no track narrower (default MIN_END_WIDTH)
  std::optional<double> max_size;  ///< adaptive: no track wider (default: no bound)
  /// CutGraphOptions::drop_crowded_rails (false only in tests of what follows on crowded rails).
  bool drop_crowded_rails = true;
};

/// The uniform element size: the options' size, else the part's mesh.size, else
/// default_element_size; capped at kMaxSizeFraction x part_extent, in which case `capped_from`
/// (when given) receives the size asked for.
double uniform_element_size(const Part& part,
                            const MeshPartOptions& options,
                            std::optional<double>* capped_from = nullptr);

/// Seconds spent in each stage.
struct StageTimes {
  double medial = 0.0;
  double rails = 0.0;
  double quads = 0.0;
  double refill = 0.0;  ///< refill_cavities
  double smooth = 0.0;
  double check = 0.0;
};

struct MeshPartResult {
  QuadMesh mesh;
  double size = 0.0;  ///< uniform: the element size; adaptive: MIN_END_WIDTH (the finest)
  /// Uniform: the size asked for when it was larger than kMaxSizeFraction x part_extent and
  /// `size` is that cap instead.
  std::optional<double> size_capped_from;
  /// Uniform: the size asked for (or its cap) when no valid mesh came there and `size` is a
  /// share of it (kFailedRetry, kCappedRetry); `failed_because` says why it failed.
  std::optional<double> size_failed_at;
  std::string failed_because;
  bool adaptive = false;
  double dtheta_deg = 0.0;  ///< adaptive: Delta theta_in
  QuadStats stats;
  /// Patches with a hub whose rails stayed (QuadResult::hubs); mesh_part builds such a part
  /// again without them and keeps the better mesh (docs/mesher.md, "Hubs").
  std::vector<std::uint32_t> hubs;
  std::size_t rail_chains = 0;
  std::size_t spiral_closures = 0;  ///< rails ended on a point of their edge (CutGraph)
  std::size_t loop_closures = 0;    ///< rails landed on their own chain's earlier crossing
  std::size_t rail_merges = 0;      ///< rails landed on another chain's point close by
  std::size_t crowded_rails = 0;    ///< source points of crowded rail sets not laid (CutGraph)
  std::size_t crowded_seeds = 0;    ///< crowded track seeds not laid (CutGraph)
  std::size_t tracks = 0;
  StageTimes times;
  MeshCheck check;                ///< of the final mesh: valid, or mesh_part threw
  QualitySummary before_smoothing;  ///< figures of the mesh as built
  QualitySummary quality;           ///< figures of the final mesh
};

/// Called when a stage starts: its name ("medial", "rails", "quads", "smooth", "check").
using StageFn = std::function<void(const char*)>;

/// Error thrown when the mesh fails its self-check: the check and the mesh, to dump.
class InvalidMeshError : public InternalError {
 public:
  InvalidMeshError(const std::string& what, QuadMesh mesh, MeshCheck check)
      : InternalError(what), mesh_(std::move(mesh)), check_(std::move(check)) {}
  const QuadMesh& mesh() const { return mesh_; }
  const MeshCheck& check() const { return check_; }

 private:
  QuadMesh mesh_;
  MeshCheck check_;
};

/// The cut-graph options for these meshing options: the uniform track width, or in adaptive
/// mode the width law, which `law` receives (it must outlive the options). Also chooses, at
/// that element size (adaptive: the law's finest width), which round holes the axes map along
/// rays from their centres (MedialAxis::choose_round_holes). `size_capped_from`, when given,
/// receives the size asked for if uniform_element_size capped it.
CutGraphOptions cut_graph_options(const Part& part,
                                  std::vector<MedialAxis>& axes,
                                  const MeshPartOptions& options,
                                  std::unique_ptr<TrackWidthLaw>& law,
                                  std::optional<double>* size_capped_from = nullptr);

/// When meshing fails and a patch's boundary comes within this x the part's size of itself
/// away from its corners (closest_self_contact), the part is refused for that (InputError,
/// naming the place) rather than reported as the mesher's failure. Outlines folded back that
/// close (fuzzed noisy outlines: 2.3e-9 to 2.5e-8 x the size) leave slivers with no room for
/// nodes 1e-9 x the size apart (quality.md, rule 5); parts that mesh are never refused for it
/// (needles whose sides come within 2e-8 x the size mesh, docs/mesher.md "Needle tips").
constexpr double kSelfContactRel = 1e-7;

/// Meshes the part and checks the result by quality.md. Throws InvalidMeshError (the failed
/// rules, with places) when the mesh is not valid, and InternalError when a stage fails;
/// InputError instead of either when the part's boundary comes within kSelfContactRel x its
/// size of itself.
MeshPartResult mesh_part(const Part& part,
                         const MeshPartOptions& options = {},
                         const StageFn& on_stage = {});

}  // namespace laytracks
