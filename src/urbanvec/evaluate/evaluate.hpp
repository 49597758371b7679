// Evaluation of a vector city against the truth it was gridded from (issue 2 §3): road centreline
// distances and smoothness, block matching by intersection over union, and parcel counts, land-use
// shares, gaps, overlaps and validity. A metric whose layers are missing is absent (std::nullopt),
// never zero, so a naive baseline with fewer layers is not scored as perfect or as failing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::evaluate {

/// The layers of one city; an absent layer leaves its metrics absent.
struct CityLayers {
  std::optional<Layer> roads;    ///< centrelines (LineString or MultiLineString)
  std::optional<Layer> blocks;   ///< Polygon or MultiPolygon
  std::optional<Layer> parcels;  ///< Polygon or MultiPolygon
};

/// The land-use grid the truth was rasterised on (landuse.tif codes; 2 and 3 are roads), in the
/// truth's CRS: it tells which truth blocks a vectorizer can match at all.
struct LandUseCells {
  GridSpec spec;
  Grid<std::uint8_t> codes;
};

/// Both cities in the same projected CRS in metres.
struct EvaluationInput {
  CityLayers result;
  CityLayers truth;
  double cellSize = 0.0;  ///< metres per cell of the grid the truth was rasterised on
  /// When given, the block report adds the matched share among the matchable truth blocks.
  std::optional<LandUseCells> landUse;
};

struct EvaluateOptions {
  /// Road ends closer than this join when the networks are noded for their graph figures, in cells
  /// (a vectorizer's segments meet exactly; OSM-made truth pieces meet within rounding).
  double networkSnapCells = 0.01;
  /// Spacing of the sample points along road centrelines, in cells (the issue asks for a quarter cell).
  double sampleSpacingCells = 0.25;
  /// Field holding a road's class (no unit); roads without it are all counted.
  std::string roadClassField = "road_class";
  /// Road classes that are not roads (the staircase around the city is `perimeter`).
  std::vector<std::string> excludedRoadClasses = {"perimeter"};
  /// Smallest intersection over union (ratio, 0..1) for a truth block to count as matched.
  double blockMatchIoU = 0.7;
  /// Truth blocks smaller than this many cells are not counted in the block matching (issue 4:
  /// "truth blocks (area >= 4 cells)"): a block of a cell or two is below what the grid can hold.
  double minTruthBlockCells = 4.0;
  /// Upper edges of the bend-size classes of the turning breakdown, in degrees, ascending (issue 20:
  /// < 5, 5-20, 20-45, > 45): each vertex's turn is counted in the class of its own size.
  std::vector<double> bendClassEdges = {5.0, 20.0, 45.0};
  /// Turns of at least this many degrees are the "sharp" turning compared by sharpTurningRatio.
  double sharpBendDegrees = 20.0;
  /// A truth block can be matched when at least this share (0..1) of its area lies on land cells
  /// (codes other than roads 2, 3) of the land-use grid: a vector block is the land between curbs,
  /// close to the union of land cells, so a block mostly under road cells cannot reach the IoU.
  double matchableLandShare = 0.7;
  /// Sample points per cell edge when measuring a truth block's share on land cells (n x n per cell).
  int landShareSubsamples = 4;
  /// Field of the result parcels holding the land use (class name, or class code as in landuse.tif).
  std::string resultLandUseField = "land_use";
  /// Field of the truth parcels holding the land use.
  std::string truthLandUseField = "land_use";
};

/// Nearest-centreline distances of points sampled along one set of roads to the other set.
struct DistanceSummary {
  std::size_t samples = 0;
  double medianMetres = 0.0;
  double p95Metres = 0.0;
  double medianCells = 0.0;
  double p95Cells = 0.0;
};

/// The road network as a graph (core/planar_graph: lines noded where they cross or touch, ends within
/// a snap tolerance joined): what distances and turning do not see — fragmentation into pieces and
/// dangling ends.
struct NetworkSummary {
  std::size_t intersections = 0;  ///< nodes of degree 3 or more
  std::size_t deadEnds = 0;       ///< nodes of degree 1
  std::size_t components = 0;     ///< connected pieces of the network
};

struct RoadReport {
  std::optional<std::size_t> truthLines;  ///< road features counted (excluded classes left out)
  std::optional<std::size_t> resultLines;
  std::optional<double> truthLengthKm;
  std::optional<double> resultLengthKm;
  std::optional<DistanceSummary> truthToResult;  ///< samples on the truth, distance to the result
  std::optional<DistanceSummary> resultToTruth;
  std::optional<double> truthTurningPerKm;  ///< degrees of turning per km of road
  std::optional<double> resultTurningPerKm;
  /// result / truth turning per km; absent when either side is absent or the truth never turns.
  std::optional<double> turningRatio;
  /// EvaluateOptions::bendClassEdges used, and the turning per km in each bend-size class (one more
  /// entry than edges).
  std::vector<double> bendClassEdges;
  std::optional<std::vector<double>> truthTurningByBend;
  std::optional<std::vector<double>> resultTurningByBend;
  double sharpBendDegrees = 0.0;                 ///< EvaluateOptions::sharpBendDegrees used
  std::optional<double> truthSharpTurningPerKm;  ///< turning in bends >= sharpBendDegrees, per km
  std::optional<double> resultSharpTurningPerKm;
  std::optional<double> sharpTurningRatio;  ///< result / truth of the above; absent when the truth has none
  std::optional<NetworkSummary> truthNetwork;
  std::optional<NetworkSummary> resultNetwork;
};

struct BlockReport {
  double iouThreshold = 0.0;                   ///< EvaluateOptions::blockMatchIoU used for matchedCount
  std::optional<std::size_t> truthCount;       ///< truth blocks of at least minTruthBlockCells
  std::optional<std::size_t> truthSmallCount;  ///< truth blocks left out as too small
  double minTruthBlockCells = 0.0;             ///< EvaluateOptions::minTruthBlockCells used
  std::optional<std::size_t> resultCount;
  std::optional<std::size_t> matchedCount;  ///< truth blocks whose best result block reaches the IoU
  std::optional<double> matchedShare;       ///< matchedCount / truthCount
  /// The same over the truth blocks whose `kind` is `internal` (enclosed by roads); absent when the
  /// truth has no kind field. External truth faces run to the grid's edge, which no vectorizer draws.
  std::optional<std::size_t> internalTruthCount;
  std::optional<std::size_t> internalMatchedCount;
  std::optional<double> internalMatchedShare;
  /// The same over the matchable truth blocks: not `external` and with at least
  /// EvaluateOptions::matchableLandShare of their area on land cells; absent without the land-use grid.
  double matchableLandShare = 0.0;
  std::optional<std::size_t> matchableTruthCount;
  std::optional<std::size_t> matchableMatchedCount;
  std::optional<double> matchableMatchedShare;
  std::optional<double> meanBestIoU;              ///< mean over truth blocks of the best IoU (0 when none)
  std::optional<std::size_t> resultInvalidCount;  ///< result blocks failing GEOSisValid
};

struct ParcelReport {
  std::optional<std::size_t> truthCount;
  std::optional<std::size_t> resultCount;
  std::optional<std::size_t> comparedBlocks;  ///< matched blocks holding at least one truth parcel
  /// Result parcels / truth parcels in a matched block pair: mean and median over compared blocks.
  std::optional<double> countRatioMean;
  std::optional<double> countRatioMedian;
  /// Sum over land uses of |result share - truth share| of parcel area per compared block (0..2),
  /// averaged over compared blocks.
  std::optional<double> landUseErrorMean;
  /// Area of result blocks covered by none of their parcels / area of result blocks with parcels.
  std::optional<double> gapShare;
  /// Area covered by two or more parcels of the same block / area of result blocks with parcels.
  std::optional<double> overlapShare;
  std::optional<std::size_t> invalidCount;  ///< result parcels failing GEOSisValid
  std::optional<double> invalidShare;       ///< invalidCount / result parcels with a geometry
};

/// A bounding box in the CRS of the evaluation (the truth's, metres).
struct Extent {
  double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;
};

/// The box around every coordinate of the layers a city has; nothing when they hold none.
std::optional<Extent> cityExtent(const CityLayers& city);

/// Share (0..1) of the polygon's area on cells whose code is not a road (2, 3), estimated on n x n
/// points per cell; points outside the grid count as not on land. 0 for a polygon covering no point.
double landShare(const Polygon& polygon, const LandUseCells& cells, int subsamples);

/// True when the two boxes share at least a point.
bool extentsOverlap(const Extent& a, const Extent& b);

struct EvaluationReport {
  double cellSize = 0.0;               ///< metres
  std::optional<Extent> resultExtent;  ///< of every result layer read
  std::optional<Extent> truthExtent;   ///< of every truth layer read
  /// False when both cities have an extent and the boxes are disjoint (e.g. one carries a wrong CRS
  /// label): the distances and matches then measure how far apart the layers lie, not the result.
  bool layersOverlap = true;
  RoadReport roads;
  BlockReport blocks;
  ParcelReport parcels;
};

/// Measures `input.result` against `input.truth`. Throws urbanvec::Error (InvalidOption) for a cell
/// size or option out of range, Cancelled when progress asks to stop.
EvaluationReport evaluate(const EvaluationInput& input, const EvaluateOptions& options = {},
                          const Progress& progress = {});

}  // namespace urbanvec::evaluate
