// `cadastre`: messy CAD linework -> blocks, sub-blocks, courtyards, parcels and building elements with
// heights (issue 17; spec pueyo-urban-data.md part A, pipeline of §A.2 / Fig. 7).
#pragma once

#include <string>
#include <vector>

#include "urbanvec/cadastre/linework.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::cadastre {

struct BlockOut {
  MultiPolygon shape;  ///< outline minus courtyards
  int preBlock = -1;
  int subBlocks = 0;
  int courtyards = 0;
};
struct AreaOut {
  MultiPolygon shape;
  int block = -1;
};
struct BuildingOut {
  MultiPolygon shape;
  int block = -1;
  int floors = 0;
  int floorsBelow = 0;
  double height = 0.0;
  std::string label;  ///< the label text used, empty when none
};

/// Table 1 of the thesis (§A.10) plus the counts of every case the pipeline repaired.
struct CadastreReport {
  std::size_t blockEntities = 0, lotEntities = 0, buildingEntities = 0, labelEntities = 0;
  std::size_t inputVertices = 0, outputVertices = 0;
  double collapsedShare = 0.0;
  std::size_t revertedCollapses = 0, zeroLengthSegments = 0;
  std::size_t duplicateSegments = 0, verticesOnSegments = 0, cornersKeptOff = 0;
  std::size_t cornersClosed = 0, undershootsToSegment = 0, undershootsToVertex = 0, overshootsCut = 0,
              hooksCut = 0, fringeEdgesRemoved = 0, verticesStraightened = 0;
  /// Split vertices merged (vertex_merging.hpp), and the refusals: a drawn segment between them, a
  /// real face collapsing, a crossing created.
  std::size_t splitVerticesMerged = 0, mergesRefusedDrawn = 0, mergesRefusedFace = 0,
              mergesRefusedCrossing = 0;
  /// Geometric adjustment: the drawing's noise estimate (m), constraints, vertices moved.
  double adjustmentNoise = 0.0;
  std::size_t straightConstraints = 0, rightAngleConstraints = 0, verticesAdjusted = 0;
  std::size_t preBlocks = 0, blocks = 0, subBlocks = 0, courtyards = 0, parcels = 0, buildings = 0;
  std::size_t buildingsWithFloors = 0;
  /// Building faces thinner than the sliver width kept because a floor label lies inside.
  std::size_t labelledThinKept = 0;
  std::size_t slivers = 0, facesOutsideBlocks = 0, buildingsOutsideBlocks = 0, enclosedBlocks = 0;
  std::size_t labelsUsed = 0, labelsSnapped = 0, labelsUnmatched = 0, labelsNotNumbers = 0,
              labelSuffixesIgnored = 0, polygonsWithSeveralLabels = 0;
  std::size_t totalEntities() const { return blockEntities + lotEntities + buildingEntities + labelEntities; }
  /// Entities/Building as Table 1 prints it: 2 Total / bi (spec F.1).
  double entitiesPerBuildingTable() const {
    return buildings ? 2.0 * static_cast<double>(totalEntities()) / static_cast<double>(buildings) : 0.0;
  }
  /// Entities/Building by the thesis's formula (Be + 2 be) / bi, lot entities counted as building ones.
  double entitiesPerBuildingFormula() const {
    return buildings ? (static_cast<double>(blockEntities) +
                        2.0 * static_cast<double>(lotEntities + buildingEntities)) /
                           static_cast<double>(buildings)
                     : 0.0;
  }
  double buildingsPerBlock() const {
    return blocks ? static_cast<double>(buildings) / static_cast<double>(blocks) : 0.0;
  }
};

struct CadastreResult {
  std::vector<BlockOut> blocks;
  std::vector<AreaOut> subBlocks;
  std::vector<AreaOut> courtyards;
  std::vector<AreaOut> parcels;
  std::vector<BuildingOut> buildings;
  CadastreReport report;
};

/// Runs the whole pipeline. `lines` in drawing order (layer by layer, polyline by polyline). Throws
/// InvalidOption for thresholds <= 0 or a Collapsing Threshold above the Block Threshold, InvalidInput
/// when no block is found.
CadastreResult structureCadastre(const std::vector<CadLine>& lines, const std::vector<CadLabel>& labels,
                                 const CadastreOptions& options, const Progress& progress = {});

}  // namespace urbanvec::cadastre
