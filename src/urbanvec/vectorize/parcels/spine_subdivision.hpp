// Stage E1 of the vectorizer: spine-based subdivision (spec §3 E1, §9.3 Q14; thesis §3.4.3 "Spine-Based
// Subdivision", paper §3.4.1). Also the GEOS face-building helper E2 reuses for its splits.
#pragma once

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/vectorize/parcels/spines.hpp"

namespace urbanvec::vectorize::parcels {

struct SpineSubdivisionOptions {
  /// The documents' literal rule, "discard the spine if the simulated count exceeds the number of
  /// spine ends", instead of the rationale's "discard if the ends exceed the simulated count" (Q14).
  bool literalDiscardRule = false;
  /// An end's boundary connector follows the spine's own direction when that hit is at most this
  /// factor farther than the closest boundary point [INFERENCE: on a symmetric end the closest point
  /// is a tie between three sides; following the spine closes the long-axis cut], unitless.
  double alongSpineFactor = 1.25;
  /// Also discard the spine when its parcels cannot hold the simulated count at the size of the
  /// smallest simulated parcel (Σ floor(face area / smallest) < N_sim) [INFERENCE: otherwise E2's
  /// minimum-size constraint makes the target unreachable, e.g. a 16×6 block with three 32-cell
  /// parcels halved by its spine].
  bool capacityCheck = true;
};

struct SpineParcels {
  bool used = false;       ///< true when `parcels` comes from the spine
  bool discarded = false;  ///< a spine existed but the end-count rule (or a failed build) discarded it
  int ends = 0;            ///< spine ends
  MultiPolygon parcels;
};

/// The faces of polygon ∪ cuts that lie inside `polygon` (GEOSNode + GEOSPolygonize). Cuts may
/// overshoot the boundary; dangling and overshooting pieces are dropped. The faces tile the polygon.
MultiPolygon facesInside(const geos::Context& geos, const GEOSGeometry* polygon, const MultiLineString& cuts);

/// The connector from a spine end to the block boundary (spec E1: "to the closest point on the
/// vectorized block"), ending a hair beyond the boundary so noding closes it. `previous` is the end's
/// neighbour on the spine.
LineString endConnector(const geos::Context& geos, const GEOSGeometry* blockBoundary, const Vec2& end,
                        const Vec2& previous, const SpineSubdivisionOptions& options);

/// E1 for one block: spine branches plus one connector per end, polygonized; unused (used = false)
/// when there is no spine, or the end-count rule (or the capacity check, given the smallest simulated
/// parcel in cells²) discards it.
SpineParcels spineSubdivision(const Polygon& block, const SpineGraph& spine, int simParcels,
                              double smallestSimParcel, const SpineSubdivisionOptions& options,
                              const geos::Context& geos);

}  // namespace urbanvec::vectorize::parcels
