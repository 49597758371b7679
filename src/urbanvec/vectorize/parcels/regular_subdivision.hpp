// Stage E2 of the vectorizer: regular subdivision (spec §3 E2, §9.4 Q16-Q20; thesis §3.4.3 "Regular
// Subdivision", paper §3.4.1): split the largest parcel perpendicular to a random road-facing edge of
// its simplified copy, at a normally distributed position, transfer the cut to the original, and keep
// it only when the four constraints hold.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/vectorize/parcels/parcel_input.hpp"

namespace urbanvec::vectorize::parcels {

struct RegularSubdivisionOptions {
  /// Constraint 1: each new parcel is at least this share of the smallest simulated parcel (spec
  /// §5.4: 75%), unitless.
  double minAreaFraction = 0.75;
  /// [INFERENCE] Constraint 1 shrinks with the vector block when the block is smaller than the
  /// simulated parcels it must hold (an external block the perimeter cut, a block the pavement
  /// narrowed): the threshold is multiplied by min(1, block area / their total area).
  bool scaleMinAreaToBlock = true;
  /// Constraint 2: longest contiguous road frontage of each new parcel (spec §5.4: 0.5 pw), cells.
  double minFrontage = 0.5;
  /// Constraint 3: aspect-ratio threshold (spec §5.4: 0.25), unitless.
  double aspectThreshold = 0.25;
  /// Constraint 3, Q16 flag: compare the children with the parent's aspect instead of the threshold.
  bool compareParentAspect = false;
  /// Constraint 4 applies when residential parcels fill at least this share of the simulated block
  /// (spec §5.4: 70%), unitless.
  double residentialShare = 0.70;
  /// Constraint 4: each child keeps at least this share of its parent's area (spec §5.4: 30%).
  double minChildShare = 0.30;
  /// Tolerance of the simplified copy whose road-facing edges orient the cuts [INFERENCE, §6: 0.5 pw
  /// since block edges are "roughly 1 pw or less"], cells.
  double simplifyTolerance = 0.5;
  /// σ of the cut position along the chosen edge, as a share of its length; resampled into (0, 1)
  /// [INFERENCE, §6: 1/6].
  double positionSigma = 1.0 / 6.0;
  /// Attempts on the largest parcel before trying random parcels [INFERENCE, §6: 20].
  int maxLargestAttempts = 20;
  /// Attempts in all for one new parcel [INFERENCE, §6: 200].
  int maxAttempts = 200;
  /// Choose the road-facing edge with probability proportional to its length (Q17 flag); the default
  /// is uniform over edges.
  bool lengthWeightedEdges = false;
  /// A parcel edge counts as road-facing when it lies within this distance of the block's road-facing
  /// lines [INFERENCE: absorbs rounding of the part-2 adapter], cells.
  double frontageTolerance = 1e-4;
};

/// Road access of parcels: the block's road-facing lines (spec Q17) and the band around them.
/// longest() and within() reuse scratch buffers, so one object serves one thread (each block builds
/// its own).
class RoadFrontage {
 public:
  RoadFrontage(const geos::Context& geos, const MultiLineString& roadFacing, double tolerance);
  /// Longest contiguous length of the parcel boundary lying on road-facing lines (spec E2 constraint
  /// 2), cells: collinear overlaps of ring edges with road-facing segments, chained along the ring.
  /// This is the fast form used inside the split loop.
  double longest(const Polygon& parcel) const;
  /// The same measure with GEOS (Intersection with a tolerance band + LineMerge), for the checkers.
  double longestGeos(const Polygon& parcel) const;
  /// Whether a road-facing line lies within `limit` (cells) of the point; skips segments whose bounding
  /// box is farther than the limit, so it costs a distance only for the few segments near the point.
  bool within(const Vec2& p, double limit) const;
  bool empty() const { return segments_.empty(); }

  /// The road-facing parts of each edge of a ring, as longest() measures them: edge i owns the merged
  /// covered intervals intervals[start[i], start[i + 1]) (lengths along the edge from its first point)
  /// and is length[i] long. An edge's entry depends only on its two end points, so a parcel cut from
  /// another keeps its parent's entries for the edges it inherits (issue 21).
  struct RingCover {
    std::vector<std::pair<double, double>> intervals;
    std::vector<std::uint32_t> start{0};
    std::vector<double> length;
    void clear() {
      intervals.clear();
      start.assign(1, 0);
      length.clear();
    }
    size_t edges() const { return length.size(); }
  };
  /// Appends the entry of the edge a-b to `cover`.
  void coverEdge(const Vec2& a, const Vec2& b, RingCover& cover) const;
  /// Appends edges first .. first + count - 1 of `from` to `cover`.
  static void copyEdges(const RingCover& from, size_t first, size_t count, RingCover& cover);
  /// The entries of every edge of a closed ring.
  void coverRing(const Ring& ring, RingCover& cover) const;
  /// longest() of a ring from its entries: the covered pieces chained along the ring.
  double longestOfCover(const RingCover& cover) const;

 private:
  double longestOnRing(const Ring& ring) const;
  /// Collects into candidates_ each segment registered in a grid cell that the edge a-b, widened by
  /// `margin`, passes through; a segment appears once.
  void segmentsAlong(const Vec2& a, const Vec2& b, double margin) const;
  /// The grid column and row of an x or y coordinate, clamped to the grid.
  int column(double x) const;
  int row(double y) const;
  void buildGrid();
  const geos::Context& geos_;
  double tolerance_;
  MultiLineString lines_;       ///< the road-facing lines, for longestGeos()
  mutable geos::GeomPtr band_;  ///< their band of half-width tolerance, built by longestGeos()
  std::vector<std::array<Vec2, 2>> segments_;
  // Uniform bucket grid over the segments' bounding boxes (cell lists stored contiguously), so a
  // query visits only the segments near a parcel edge instead of all the block's curb segments.
  Vec2 gridOrigin_;
  double cellSize_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> cellStart_;     ///< columns_ * rows_ + 1 offsets into cellSegments_
  std::vector<std::uint32_t> cellSegments_;  ///< segment indices, grouped by cell
  // Scratch reused across calls.
  mutable std::vector<std::uint32_t> candidates_;
  mutable std::vector<std::uint32_t> lastSeen_;  ///< per segment, the query that last collected it
  mutable std::uint32_t query_ = 0;
  mutable std::vector<std::pair<double, double>> edgeCover_;
  mutable RingCover ringCover_;
};

/// The four constraints, with the block's numbers filled in.
struct SplitRules {
  double minArea = 0.0;      ///< cells²
  double minFrontage = 0.5;  ///< cells
  double aspectThreshold = 0.25;
  bool compareParentAspect = false;
  bool residentialRule = false;  ///< constraint 4 active for this block
  double minChildShare = 0.30;
};
SplitRules splitRules(const SimBlockSummary& sim, const RegularSubdivisionOptions& options);

enum class SplitVerdict { Accepted, TooSmall, NoRoadAccess, TooRectangular, UnequalResidential, BadGeometry };
std::string_view verdictName(SplitVerdict verdict);

/// Checks a split of `parent` into `a` and `b` against the four constraints (size, rectangularity,
/// residential variation, then road access, the costliest, last).
SplitVerdict checkSplit(const Polygon& parent, const Polygon& a, const Polygon& b, const SplitRules& rules,
                        const RoadFrontage& frontage);
/// The same with the parent's area and PCA aspect already known (the split loop keeps them per parcel
/// instead of recomputing them on every try).
SplitVerdict checkSplit(double parentArea, double parentAspect, const Polygon& a, const Polygon& b,
                        const SplitRules& rules, const RoadFrontage& frontage);

/// What every split attempt on one parcel shares (issue 21), built once per parcel: per ring, runs of
/// up to 8 edges with their bounding boxes, so an attempt visits only the edges near its cut line;
/// for the outer ring, prefix sums of the area and moment terms about a local origin, so the children's
/// areas and moments come from two prefix differences and three cut terms instead of new rings.
struct SplitIndex {
  struct Run {
    Vec2 centre, half;        ///< bounding box of the run's vertices
    double longestEdge = 0;   ///< cells
    std::uint32_t first = 0;  ///< edges [first, last) of the ring
    std::uint32_t last = 0;
  };
  /// Sums over the outer ring's edges p-q of c = cross(p - origin, q - origin) and the moment terms
  /// c·(px + qx), c·(py + qy), c·(px² + px qx + qx²), c·(py² + py qy + qy²),
  /// c·(px qy + 2 px py + 2 qx qy + qx py) (local coordinates), and for the error bounds the sums of
  /// |px qy| + |py qx| and of |c| in local and in absolute coordinates.
  struct Sums {
    double c = 0, mx = 0, my = 0, ixx = 0, iyy = 0, ixy = 0;
    double productsLocal = 0, crossLocal = 0, products = 0, cross = 0;
  };
  Vec2 origin;
  double maxAbs = 0.0;    ///< largest |coordinate| of the rings (absolute frame), cells
  double maxLocal = 0.0;  ///< largest |coordinate - origin| of the rings, cells
  double diagonal = 0.0;  ///< of the rings' bounding box, cells
  std::vector<Run> runs;
  std::vector<std::uint32_t> ringRuns{0};  ///< ring r owns runs[ringRuns[r], ringRuns[r + 1])
  std::vector<Sums> prefix;                ///< outer ring: prefix[k] sums edges 0..k-1
  bool built = false;
};
SplitIndex buildSplitIndex(const Polygon& polygon);
/// The same into `index`, whose lists' memory is reused.
void buildSplitIndex(const Polygon& polygon, SplitIndex& index);

/// A parcel during subdivision, with its simplified copy and road-facing edges computed on first use.
struct SubdivisionParcel {
  Polygon polygon;
  double area = 0.0;
  bool prepared = false;
  double aspect = 1.0;                         ///< PCA aspect of `polygon`, set by prepare()
  bool aspectKnown = false;                    ///< `aspect` already holds it (split check of the cut)
  std::vector<std::array<Vec2, 2>> roadEdges;  ///< road-facing edges of the simplified copy
  SplitIndex index;                            ///< set by prepare()
  /// Road frontage entries of every edge of each ring (outer, then holes), inherited from the parent
  /// for the edges it shares; empty = not known yet.
  std::vector<RoadFrontage::RingCover> cover;
  SubdivisionParcel() = default;
  explicit SubdivisionParcel(Polygon p);
};

/// Counts of rejected attempts by reason, to explain shortfalls.
struct SplitStats {
  int accepted = 0;
  int rejected[6] = {0, 0, 0, 0, 0, 0};  ///< indexed by SplitVerdict
  /// "no acceptable split (mostly <reason>)"
  std::string shortfallReason() const;
};

/// Computes the aspect and the simplified copy's road-facing edges of `parcel` (trySplit does it on
/// first use).
/// Deterministic and free of randomness, so the tries of a block can share the work on its E1 parcels.
void prepare(SubdivisionParcel& parcel, const RegularSubdivisionOptions& options,
             const RoadFrontage& frontage, const geos::Context& geos);

/// One random split attempt of `parcel`; on acceptance the two children are returned in `out`.
SplitVerdict trySplit(SubdivisionParcel& parcel, const SplitRules& rules,
                      const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
                      const geos::Context& geos, Rng& rng, std::array<Polygon, 2>& out);
/// The same, the children as subdivision parcels that carry their area, aspect and the road frontage
/// entries of their edges.
SplitVerdict trySplit(SubdivisionParcel& parcel, const SplitRules& rules,
                      const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
                      const geos::Context& geos, Rng& rng, std::array<SubdivisionParcel, 2>& out);

/// The split of a prepared parcel along the piece of the line q + s·dir nearest q (the second half
/// of trySplit, after the random draws). With `screen`, a cut whose children clearly fail the size,
/// rectangularity or residential rule is rejected from the parcel's SplitIndex before any child ring is
/// built: the children's areas and moments come from prefix sums with a bound on their rounding
/// error, and only a verdict the bound makes certain is taken (else the children are built and
/// checked as without `screen`), so the verdict is the same either way.
SplitVerdict splitAlong(SubdivisionParcel& parcel, const Vec2& q, const Vec2& dir, const SplitRules& rules,
                        const RoadFrontage& frontage, const geos::Context& geos,
                        std::array<SubdivisionParcel, 2>& out, bool screen = true);

/// Parcels whose memory the split loop reuses (issue 21): the two children of the attempts, and spare
/// parcels a new parcel takes its lists from (the caller may add the parcels of an earlier try).
struct SubdivisionScratch {
  std::array<SubdivisionParcel, 2> children;
  std::vector<SubdivisionParcel> spare;
};

/// Splits (largest first, then random parcels) until `target` parcels exist or no acceptable split is
/// found; returns whether the target was reached.
bool subdivide(std::vector<SubdivisionParcel>& parcels, int target, const SplitRules& rules,
               const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
               const geos::Context& geos, Rng& rng, SplitStats& stats);
/// The same with the caller's scratch parcels (the same result).
bool subdivide(std::vector<SubdivisionParcel>& parcels, int target, const SplitRules& rules,
               const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
               const geos::Context& geos, Rng& rng, SplitStats& stats, SubdivisionScratch& scratch);

}  // namespace urbanvec::vectorize::parcels
