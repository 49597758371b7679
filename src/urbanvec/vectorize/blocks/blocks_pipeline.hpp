// Vectorizer part 2: stages C and D1-D5 of shared/specs/sexton-vectorizer.md run in order on the plain
// road-network interface (road_network.hpp), producing the `pavement`, `blocks` and `water` layers of
// CONVENTIONS.md in world coordinates, plus per-block data for the next stages (D6 spines, E parcels).
//
// Also the invariant checker of issue 4: validity, overlaps, tiling, outline smoothness, IoU against
// truth blocks and failsafe use, runnable on any pavement/blocks/water layers (e.g. real output).
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/blocks/block_matching.hpp"
#include "urbanvec/vectorize/blocks/block_outline.hpp"
#include "urbanvec/vectorize/blocks/external_blocks.hpp"
#include "urbanvec/vectorize/blocks/water_split.hpp"
#include "urbanvec/vectorize/pavement/road_geometry.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"

namespace urbanvec::vectorize {

struct BlocksOptions {
  RoadGeometryOptions road;        ///< stage C
  BlockOutlineOptions outline;     ///< stage D1
  WaterSplitOptions water;         ///< stage D2
  ExternalBlocksOptions external;  ///< stages D3 + D4
  BlockMatchingOptions matching;   ///< stage D5
};

/// What the next stages need about one block, aligned with the features of BlocksResult::blocks.
struct BlockInfo {
  int blockId = 0;  ///< the block_id field
  bool internal = true;
  /// SimulatedBlock::id of every simulated block matched to this block, most cells first.
  std::vector<int> simBlockIds;
  /// Indices into SimulatedCity::blocks, same order as simBlockIds.
  std::vector<int> simBlockIndices;
  Polygon shape;             ///< internal frame (cells), outer ring clockwise
  double areaCells = 0.0;    ///< in cells^2
  OrientedBox obb;           ///< PCA box in cells (aspect drives D6, diagonal is BBD in cells)
  double obbDiagonal = 0.0;  ///< the OBB diagonal in world units (metres)
  /// The block outline touches a cul-de-sac octagon (spec D6 "pierced" block).
  bool hasCulDeSac = false;
};

struct BlocksStats {
  int simulatedBlocks = 0;
  int matchedSimulatedBlocks = 0;
  int failsafeUses = 0;          ///< D5 failsafe matches
  int failsafeWithParcels = 0;   ///< of those, simulated blocks listing parcels
  int overlapUses = 0;           ///< D5 matches by cell overlap
  int underPavement = 0;         ///< simulated blocks without parcels left under pavement
  int majorityUses = 0;          ///< D5 centre/parcel picks overruled by the cell majority
  int boundaryLines = 0;         ///< perimeter-class segments
  int deletedBoundaryLines = 0;  ///< removed by D3
  int droppedExternalFaces = 0;  ///< D4 faces that were not external land
  int waterSplitBlocks = 0;      ///< blocks that met water in D2
  int shoreScraps = 0;           ///< D2 pieces without simulated land, moved to the water layer
  int convexHullFallbacks = 0;   ///< stage C intersection polygons replaced by their hull
  int absorbedSlivers = 0;       ///< D1 faces below minBlockArea merged into the pavement
};

struct BlocksResult {
  Layer pavement;  ///< pavement_id, kind (segment/intersection/cul_de_sac), road_class
  /// block_id, kind (internal/external), sim_block_id, area (world units^2), has_spine (0 here; D6
  /// sets it), obb_aspect, obb_diagonal (world units)
  Layer blocks;
  Layer water;  ///< water_id
  std::vector<BlockInfo> blockInfo;
  MultiPolygon perimeter;       ///< area inside the outer road perimeter, world coordinates
  MultiPolygon perimeterCells;  ///< the same in the internal frame
  BlockMatching matching;       ///< D5 result per simulated block (vector block = blockInfo index)
  BlocksStats stats;
};

/// Runs C -> D1 -> D3 -> D4 -> D2 -> D5. `grid` maps the internal frame to the world:
/// world = grid.transform.pixelToWorld(x, grid.height - y). Throws urbanvec::Error (InvalidInput)
/// when the city's land-use grid does not have the grid's size or the network is malformed.
BlocksResult vectorizeBlocks(const RoadNetwork& network, const SimulatedCity& city, const GridSpec& grid,
                             const BlocksOptions& options = {}, const Progress& progress = {});

// ---- Invariant checker ----

struct BlocksQualityTargets {
  /// Largest total pairwise overlap of pavement pieces, as a share of the pavement area.
  double maxPavementOverlapShare = 1e-6;
  /// Largest overlap of blocks with pavement, water or other blocks, as a share of the block area.
  double maxBlockOverlapShare = 1e-6;
  /// Largest uncovered area inside the perimeter, as a share of the perimeter area.
  double maxTilingGapShare = 1e-6;
  /// Smallest share of truth blocks (of at least minTruthBlockCells) matched with IoU >= truthIoU.
  double minTruthMatchShare = 0.9;
  double truthIoU = 0.7;            ///< no unit
  double minTruthBlockCells = 4.0;  ///< truth blocks smaller than this (cells^2) are not counted
  /// Largest share of outline vertices with a turn of 90° ± squareTurnToleranceDegrees.
  double maxSquareTurnShare = 0.05;
  double squareTurnToleranceDegrees = 5.0;  ///< degrees
  /// Largest share of simulated blocks matched by the failsafe.
  double maxFailsafeShare = 0.02;
};

struct BlocksCheckInput {
  const Layer* pavement = nullptr;  ///< polygons
  const Layer* blocks = nullptr;    ///< polygons with a `kind` field (internal/external)
  const Layer* water = nullptr;     ///< optional
  /// The area inside the road perimeter; when empty, the filled outline of pavement + internal blocks.
  MultiPolygon perimeter;
  const Layer* truthBlocks = nullptr;  ///< optional, same CRS
  double cellSize = 1.0;               ///< world units per cell
  int failsafeUses = -1;               ///< -1 when unknown
  int simulatedBlocks = 0;
};

struct BlocksCheckReport {
  int polygons = 0;
  int invalidPolygons = 0;
  double pavementArea = 0.0;
  double pavementOverlapArea = 0.0;
  double blockArea = 0.0;
  double blockPavementOverlapArea = 0.0;
  double blockWaterOverlapArea = 0.0;
  double blockBlockOverlapArea = 0.0;
  double perimeterArea = 0.0;
  double tilingGapArea = 0.0;     ///< inside the perimeter, covered by no pavement, internal block or water
  double tilingExcessArea = 0.0;  ///< internal blocks and pavement outside the perimeter
  int outlineVertices = 0;
  int squareTurnVertices = 0;
  double squareTurnShare = 0.0;
  int truthBlocks = 0;  ///< counted truth blocks (-1 when no truth was given)
  int truthBlocksMatched = 0;
  double truthMatchShare = 0.0;
  double failsafeShare = 0.0;  ///< -1 when unknown
};

BlocksCheckReport checkBlocks(const BlocksCheckInput& input, const BlocksQualityTargets& targets = {});

/// One sentence per target the report misses; empty when all are met.
std::vector<std::string> qualityFailures(const BlocksCheckReport& report,
                                         const BlocksQualityTargets& targets = {});

}  // namespace urbanvec::vectorize
