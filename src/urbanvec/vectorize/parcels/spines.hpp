// Stage D6 of the vectorizer: block spines (spec §3 D6, §5.3, §9.3 Q15; thesis §3.4.2, paper §3.3.2).
// Which blocks get a spine, and the method-independent clean-up of the raw medial graph: spanning
// tree, smoothing, branch pruning, end trimming, 20° turning simplification and junction separation.
// The raw graph comes from Zhang-Suen thinning (spine_zhang_suen) or CGAL's straight skeleton
// (spine_skeleton).
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/parcels/parcel_input.hpp"

namespace urbanvec::vectorize::parcels {

/// How the raw medial graph of a block is found (`-spine-method`).
enum class SpineMethod {
  ZhangSuen,  ///< the thesis method: rasterize at pixelsPerCell, Zhang-Suen thinning, re-vectorize
  Skeleton    ///< interior straight skeleton (CGAL) of the lightly simplified block
};

/// `-spine-method` values: "zhang-suen" or "skeleton".
std::string_view spineMethodName(SpineMethod method);
/// Parses a `-spine-method` value (case-sensitive, as GDAL options); nothing when unknown.
std::optional<SpineMethod> parseSpineMethod(std::string_view name);

struct SpineOptions {
  /// Default chosen by measurement (docs/vectorize_parcels.md): the straight skeleton gives lower
  /// cost and no corner stubs.
  SpineMethod method = SpineMethod::Skeleton;
  /// Blocks whose PCA-OBB aspect (width/length) is below this are oblong (spec: "< 1:2"), unitless.
  double oblongAspect = 0.5;
  /// Rasterization resolution for Zhang-Suen, pixels per cell (spec §5.3: 8).
  int pixelsPerCell = 8;
  /// Neighbour-averaging passes over spine vertices [INFERENCE, spec §6: 2].
  int smoothingPasses = 2;
  /// Side branches with fewer edges than this are pruned (spec §5.3: "< 2 edges"), edges.
  int minBranchEdges = 2;
  /// Spine ends closer than this to the block boundary are trimmed (spec §5.3: 1 pw), cells.
  double trimDistance = 1.0;
  /// Summed turning angle that ends a simplified spine edge (spec §5.3: 20°), degrees.
  double turningThreshold = 20.0;
  /// Sum signed turning angles so the pixel staircase's zig-zags cancel [INFERENCE; the spec's
  /// literal reading sums |angle|, which keeps nearly every vertex of a diagonal pixel chain].
  bool signedTurning = true;
  /// Tolerance of the topology-preserving simplification applied before the straight skeleton, so the
  /// ~1-cell boundary jitter does not spawn branches [INFERENCE], cells.
  double skeletonSimplifyTolerance = 0.5;
};

/// An undirected graph of spine vertices (cells) and edges (pairs of vertex indices).
struct SpineGraph {
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 2>> edges;
};

/// Spec D6 "which blocks": internal, and oblong or containing a cul-de-sac.
bool needsSpine(const ParcelBlock& block, const SpineOptions& options);

/// The outline the skeleton is built from: the block simplified (topology kept) by
/// skeletonSimplifyTolerance, or the block itself when that is 0 or splits it.
Polygon skeletonInput(const Polygon& block, const SpineOptions& options, const geos::Context& geos);

/// The raw medial graph by the chosen method (the skeleton falls back to Zhang-Suen when CGAL cannot
/// build one, e.g. on a degenerate polygon).
SpineGraph rawSpineGraph(const Polygon& block, const SpineOptions& options, const geos::Context& geos);

/// Steps 3-8 of D6 on a raw graph: spanning tree (longest edges dropped first, so 8-connected
/// diagonals go before 4-connected edges), largest component, smoothing, pruning, trimming,
/// simplification, junction separation. Returns an empty graph when nothing survives.
SpineGraph cleanSpine(const SpineGraph& raw, const Polygon& block, const SpineOptions& options);

/// The whole of D6 for one polygon.
SpineGraph buildSpine(const Polygon& block, const SpineOptions& options, const geos::Context& geos);

/// The graph's branches (paths between vertices of degree != 2) as line strings.
MultiLineString spineBranches(const SpineGraph& spine);
/// Vertices of degree 1.
std::vector<Vec2> spineEnds(const SpineGraph& spine);
/// Vertex degrees.
std::vector<int> spineDegrees(const SpineGraph& spine);
/// Distance from a point to the nearest ring of the polygon (outer or hole), cells.
double distanceToBoundary(const Polygon& polygon, const Vec2& p);

}  // namespace urbanvec::vectorize::parcels
