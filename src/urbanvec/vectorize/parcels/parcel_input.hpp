// The plain per-block interface of vectorizer part 3 (spec stages D6 and E1-E6). The lead adapts the
// block outlines of part 2 (D1-D5) to ParcelBlock; everything here is in the spec's internal frame
// (spec §0): x east, y north, 1 unit = 1 cell (pw). Conversion to metres happens at output only
// (parcelDensity takes the cell size).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/landuse.hpp"

namespace urbanvec::vectorize::parcels {

/// One simulated parcel of the block's matched simulated block(s) (spec §2.2 SimParcel).
struct SimParcel {
  std::int32_t id = 0;
  LandUse use = LandUse::Unused;
  double cells = 0.0;       ///< patch count = area in cells²
  double population = 0.0;  ///< people
  Vec2 centre;              ///< mean of the patch centres, internal frame (cells)
};

/// The simulated side of a vector block: the union of its matched simulated blocks (spec D5: "merge
/// their parcel lists and areas").
struct SimBlockSummary {
  double area = 0.0;             ///< patches of the simulated block(s), cells²
  double developedArea = 0.0;    ///< patches with a developed use (residential..park), cells²
  double undevelopedArea = 0.0;  ///< unused patches inside the block, cells²
  /// Patches of the block(s) per land-use code, cells²; the use shares of Eq. 3.3. Empty = the
  /// parcels' cells stand in (a parcel's cells can lie partly in other blocks, so they only do when
  /// every parcel lies wholly inside).
  std::vector<double> useArea;
  std::vector<SimParcel> parcels;
};

/// The area of each land-use class in the simulated block(s), cells², indexed by LandUse code: the
/// block's own patches (useArea), or its parcels' cells when those are not known. The use shares of
/// Eq. 3.3 (E4, E5) and the checkers' use L1 both read it.
inline std::array<double, kLandUseClassCount> simulatedUseAreas(const SimBlockSummary& sim) {
  std::array<double, kLandUseClassCount> areas{};
  if (!sim.useArea.empty()) {
    for (int use = 0; use < kLandUseClassCount; ++use) areas[use] = sim.useArea.at(static_cast<size_t>(use));
  } else {
    for (const SimParcel& p : sim.parcels) areas[static_cast<size_t>(p.use)] += p.cells;
  }
  return areas;
}

/// One vector block as D1-D5 leave it (spec §2.2 VecBlock), in cell units.
struct ParcelBlock {
  std::int64_t blockId = 0;  ///< also the seed stream when seedStream is unset: deriveSeed(runSeed, blockId)
  /// The block's seed stream, deriveSeed(runSeed, seedStream), when set: vectorizeCity sets it from the
  /// block's first simulated cell in the whole raster, so a block draws alike in every window (tiles).
  std::optional<std::uint64_t> seedStream;
  Polygon polygon;           ///< valid polygon, may have holes
  bool external = false;     ///< external (city-edge) block: never gets a spine (spec D6)
  bool hasCulDeSac = false;  ///< the boundary includes edges of a cul-de-sac octagon (spec D6)
  /// The parts of the block boundary that are curbs (road-derived, spec D1 provenance). Road access of
  /// parcels (E2 constraint 2) is measured along these. They must lie on the polygon boundary.
  MultiLineString roadFacing;
  /// PCA oriented bounding box of the polygon (spec D1). Negative = compute with orientedBox().
  double obbAspect = -1.0;    ///< width / length in (0, 1]
  double obbDiagonal = -1.0;  ///< BBD, cells
  SimBlockSummary sim;
};

/// PCA oriented bounding box (spec D1: area-weighted second moments of the polygon).
struct OrientedBox {
  Vec2 centre;
  Vec2 axis;            ///< unit vector of the long side
  double length = 0.0;  ///< long extent, cells
  double width = 0.0;   ///< short extent, cells
  double aspect() const { return length > 0.0 ? width / length : 1.0; }
  double diagonal() const { return std::hypot(width, length); }
};

/// Area-weighted first and second moments of a polygon (holes subtract), whatever ring orientation.
struct PolygonMoments {
  double area = 0.0;
  Vec2 centroid;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;  ///< central second moments divided by area, cells²
};

/// `ringAreas`, when given, holds signedArea() of the outer ring and then of each hole, so a caller
/// that already has them saves a pass over the rings.
inline PolygonMoments polygonMoments(const Polygon& polygon, const double* ringAreas = nullptr) {
  double a = 0.0, mx = 0.0, my = 0.0, ixx = 0.0, iyy = 0.0, ixy = 0.0;
  size_t ringIndex = 0;
  auto addRing = [&](const Ring& ring, double sign) {
    const double ringArea = ringAreas ? ringAreas[ringIndex] : signedArea(ring);
    ++ringIndex;
    const double orientation = ringArea >= 0.0 ? sign : -sign;
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2& p = ring[i];
      const Vec2& q = ring[i + 1];
      const double c = cross(p, q) * orientation;
      a += c / 2.0;
      mx += (p.x + q.x) * c / 6.0;
      my += (p.y + q.y) * c / 6.0;
      ixx += (p.x * p.x + p.x * q.x + q.x * q.x) * c / 12.0;
      iyy += (p.y * p.y + p.y * q.y + q.y * q.y) * c / 12.0;
      ixy += (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) * c / 24.0;
    }
  };
  addRing(polygon.outer, 1.0);
  for (const Ring& h : polygon.holes) addRing(h, -1.0);
  PolygonMoments m;
  m.area = a;
  if (a <= 0.0) {
    // Degenerate polygon: fall back to the vertex mean so callers still get a usable centre.
    for (const Vec2& p : polygon.outer) m.centroid += p;
    if (!polygon.outer.empty()) m.centroid = m.centroid / static_cast<double>(polygon.outer.size());
    m.area = 0.0;
    return m;
  }
  m.centroid = {mx / a, my / a};
  m.sxx = ixx / a - m.centroid.x * m.centroid.x;
  m.syy = iyy / a - m.centroid.y * m.centroid.y;
  m.sxy = ixy / a - m.centroid.x * m.centroid.y;
  return m;
}

/// PCA oriented bounding box: principal axis of the area-weighted covariance, extents of the outer
/// ring projected on both axes (spec D1; §11.4 check 28). `ringAreas` as for polygonMoments().
inline OrientedBox orientedBox(const Polygon& polygon, const double* ringAreas = nullptr) {
  const PolygonMoments m = polygonMoments(polygon, ringAreas);
  // The principal axis is at angle θ with (cos 2θ, sin 2θ) ∝ (sxx - syy, 2 sxy); the half-angle
  // formulas give cos θ and sin θ (θ in (-π/2, π/2], as 0.5·atan2 gives) without atan2/cos/sin, since
  // the split loop of E2 calls this for every child of every try. The larger of the two halves is
  // taken from its square root and the other from sin 2θ = 2 sin θ cos θ, which keeps full precision.
  const double cos2 = m.sxx - m.syy, sin2 = 2.0 * m.sxy;
  const double radius = std::sqrt(cos2 * cos2 + sin2 * sin2);
  Vec2 u{1.0, 0.0};
  if (radius > 0.0) {
    if (cos2 >= 0.0) {
      u.x = std::sqrt(0.5 * (1.0 + cos2 / radius));
      u.y = sin2 / (2.0 * radius * u.x);
    } else {
      u.y = std::copysign(std::sqrt(0.5 * (1.0 - cos2 / radius)), sin2);
      u.x = sin2 / (2.0 * radius * u.y);
    }
  }
  const Vec2 v{-u.y, u.x};
  double minU = 1e300, maxU = -1e300, minV = 1e300, maxV = -1e300;
  for (const Vec2& p : polygon.outer) {
    const Vec2 d = p - m.centroid;
    minU = std::min(minU, dot(d, u));
    maxU = std::max(maxU, dot(d, u));
    minV = std::min(minV, dot(d, v));
    maxV = std::max(maxV, dot(d, v));
  }
  OrientedBox box;
  if (polygon.outer.empty()) return box;
  const double eu = maxU - minU, ev = maxV - minV;
  const Vec2 mid = m.centroid + u * (0.5 * (minU + maxU)) + v * (0.5 * (minV + maxV));
  box.centre = mid;
  box.axis = eu >= ev ? u : v;
  box.length = std::max(eu, ev);
  box.width = std::min(eu, ev);
  return box;
}

/// One output parcel (CONVENTIONS.md `parcels` layer, before the world transform).
struct VectorParcel {
  Polygon polygon;           ///< cells
  bool undeveloped = false;  ///< "negative" parcel (spec E3); then `use` is LandUse::Unused
  LandUse use = LandUse::Unused;
  double population = 0.0;  ///< people
  double area = 0.0;        ///< cells²
};

/// One row of the `vectorize_report` table, plus the reasons the lead needs for the quality checks.
struct BlockReport {
  std::int64_t blockId = 0;
  int simParcels = 0;     ///< simulated parcels of the block
  int targetParcels = 0;  ///< simulated count plus the E3 undeveloped extras of the kept try
  int parcels = 0;        ///< parcels produced
  int tries = 0;          ///< generate-and-test iterations run (spec E5)
  double cost = 0.0, costUse = 0.0, costDistance = 0.0, costSize = 0.0;  ///< of the kept try
  int splitAttempts = 0;  ///< E2 split attempts over all tries (accepted + rejected), for profiling
  int shortTries = 0;     ///< tries that ended below their target parcel count
  int relaxedRules = 0;   ///< relaxation rounds the kept result needed (ParcelsOptions::relaxationRounds)
  bool hasSpine = false;
  bool spineDiscarded = false;  ///< spine built but not used for parcels (spec E1 end-count rule)
  /// Empty when parcels == targetParcels; otherwise why fewer parcels were made.
  std::string shortfall;
  double simPopulation = 0.0;      ///< total population of the simulated parcels
  double ignoredPopulation = 0.0;  ///< population of uses with no vector parcel (spec E6 "ignore")
  int ignoredUses = 0;             ///< number of such uses
};

/// The result for one block.
struct BlockParcels {
  MultiLineString spine;  ///< cells; empty when the block has no spine
  std::vector<VectorParcel> parcels;
  BlockReport report;
};

/// Population per m² of a parcel whose area is in cells², for cells of `cellSize` metres (spec E6,
/// §11.7 check 39). Zero for an empty parcel.
inline double parcelDensity(double population, double areaCells, double cellSize) {
  const double m2 = areaCells * cellSize * cellSize;
  return m2 > 0.0 ? population / m2 : 0.0;
}

}  // namespace urbanvec::vectorize::parcels
