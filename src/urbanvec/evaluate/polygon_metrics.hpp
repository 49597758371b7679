// Block and parcel metrics of the evaluator (issue 2 §3, "blocks" and "parcels"): polygons made
// valid for overlay and indexed in a GEOS STRtree, best-IoU block matching, parcel-to-block
// assignment, gaps and overlaps between the parcels of a block, and land-use shares.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::evaluate {

/// The polygonal features of a layer, ready for overlay: each made valid (GEOSMakeValid) when it is
/// not, with its area, and indexed by envelope. Features without a polygonal geometry are skipped.
class PolygonLayer {
 public:
  PolygonLayer(const geos::Context& ctx, const Layer& layer);
  ~PolygonLayer();
  PolygonLayer(const PolygonLayer&) = delete;
  PolygonLayer& operator=(const PolygonLayer&) = delete;

  std::size_t size() const { return geometries_.size(); }
  /// Polygons that failed GEOSisValid (including rings too short to build), before repair.
  std::size_t invalidCount() const { return invalid_; }
  const GEOSGeometry* geometry(std::size_t i) const { return geometries_[i].get(); }
  const GEOSPreparedGeometry* prepared(std::size_t i) const;
  double area(std::size_t i) const { return areas_[i]; }
  /// Index of the polygon's feature in the source layer.
  std::size_t featureIndex(std::size_t i) const { return features_[i]; }
  /// Polygons whose envelope meets the envelope of `g`, in ascending order.
  std::vector<std::size_t> candidates(const GEOSGeometry* g) const;

 private:
  const geos::Context& ctx_;
  std::vector<geos::GeomPtr> geometries_;
  std::vector<double> areas_;
  std::vector<std::size_t> features_;
  std::size_t invalid_ = 0;
  GEOSSTRtree* tree_ = nullptr;
  mutable std::vector<const GEOSPreparedGeometry*> prepared_;
};

/// For each truth block, the result block of largest intersection over union (none when no result
/// block overlaps it) and that IoU (0 when none).
struct BlockMatching {
  std::vector<std::optional<std::size_t>> bestResult;
  std::vector<double> bestIoU;
};

BlockMatching matchBlocks(const geos::Context& ctx, const PolygonLayer& truth, const PolygonLayer& result,
                          const Progress& progress = {});

/// The block holding each parcel's interior point (GEOSPointOnSurface); the lowest block index when
/// blocks overlap; none when no block holds it.
std::vector<std::optional<std::size_t>> assignToBlocks(const geos::Context& ctx, const PolygonLayer& parcels,
                                                       const PolygonLayer& blocks);

/// Gaps and overlaps between the parcels assigned to each block, summed over blocks with parcels.
struct Coverage {
  double blockArea = 0.0;  ///< total area of blocks with at least one parcel
  double gapArea = 0.0;    ///< block area covered by none of its parcels
  double overlapArea =
      0.0;  ///< block area covered by two or more of its parcels (counted once per extra layer)
  std::size_t blocks = 0;
};

Coverage parcelCoverage(const geos::Context& ctx, const PolygonLayer& parcels, const PolygonLayer& blocks,
                        const std::vector<std::optional<std::size_t>>& parcelBlock,
                        const Progress& progress = {});

/// A land-use field value as a class name: codes (as in landuse.tif) and names in any spelling give
/// landUseName(); "undeveloped" (the vectorizer's parcels without a use) gives "unused"; other text is
/// kept in lower case; null gives "".
std::string landUseKey(const FieldValue& value);

/// Sum over classes of |a share - b share|, shares being area / total area of each side (0..2);
/// a side with no area has every share 0.
double landUseShareError(const std::map<std::string, double>& a, const std::map<std::string, double>& b);

}  // namespace urbanvec::evaluate
