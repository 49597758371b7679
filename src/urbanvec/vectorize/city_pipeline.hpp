// Stages C-E of shared/specs/sexton-vectorizer.md §1 joined to the road network of part 1: pavement
// and blocks (part 2, blocks_pipeline), then spines, parcels, land use and population (part 3,
// parcels_pipeline). This file adapts one part's output to the next part's input and writes the
// `pavement`, `blocks`, `water`, `spines`, `parcels` and `vectorize_report` layers of CONVENTIONS.md.
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/blocks/blocks_pipeline.hpp"
#include "urbanvec/vectorize/parcels/parcels_pipeline.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

struct CityOptions {
  BlocksOptions blocks;             ///< stages C, D1-D5
  parcels::ParcelsOptions parcels;  ///< stages D6, E1-E6
  /// Width of the band around the pavement within which a block edge counts as road-facing (E2
  /// constraint 2), in cells. [INFERENCE] Only absorbs floating-point noise between the block outline
  /// and the pavement it was cut from.
  double roadFacingTolerance = 1e-3;
  /// [INFERENCE, beyond the documents] A block with no road-facing edge at all (an island of developed
  /// land that meets no road: a grid without roads, an estate in the fields) takes its whole outline
  /// as its frontage, so E2 can still split it into its simulated parcels, which then face the open
  /// land around it. false = such a block stays one parcel (E2 constraint 2 read literally; its
  /// report says "block has no road-facing boundary").
  bool islandFrontage = true;
  /// Column and row of the grid's first cell in the whole raster (VectorizeInput::originCol/Row, set by
  /// the pipeline, not a user option): each block's seed stream is its first simulated cell there.
  std::int64_t originCol = 0;
  std::int64_t originRow = 0;
};

struct CityResult {
  /// Stages C-D5; its `pavement`, `blocks` and `water` layers are moved into `layers` (left empty here).
  BlocksResult blocks;
  /// Stages D6-E6, aligned with blocks.blockInfo; each block's spine and parcel polygons are moved into
  /// `layers` (left empty here: the reports, populations and areas stay).
  parcels::ParcelsResult parcels;
  /// pavement, blocks, water, spines, parcels, vectorize_report (world coordinates); empty when
  /// vectorizeCity was given a sink.
  std::vector<Layer> layers;
  std::size_t blockFeatures = 0;  ///< features of the blocks layer
};

/// The simulated side of one vector block: its matched simulated blocks merged (spec D5).
parcels::SimBlockSummary summarizeSimulatedBlocks(const std::vector<int>& simBlockIndices,
                                                  const std::vector<SimBlock>& blocks,
                                                  const std::vector<SimParcel>& parcels,
                                                  const Grid<std::uint8_t>& cells);

/// Runs C -> D5 then D6 -> E6 on part 1's output. `cells`, `blocks` and `simParcels` are
/// VectorizeResult's A2-A5 data; `network` its road network; `grid` the input frame. With a `sink`,
/// the layers go to it in order as soon as each is final (pavement before D6, the rest at the end)
/// instead of into `layers`.
CityResult vectorizeCity(const RoadNetwork& network, const Grid<std::uint8_t>& cells,
                         const std::vector<SimBlock>& blocks, const std::vector<SimParcel>& simParcels,
                         const GridSpec& grid, const CityOptions& options, const Progress& progress = {},
                         const LayerSink& sink = {});

}  // namespace urbanvec::vectorize
