// The `streets` pipeline (spec chen-streets.md §1): tensor field from design elements, polylines and
// a DEM (§4-§6) → major then minor roads (§8-§12) → the noded street graph (§10: every crossing a
// node, GEOS) → blocks, the faces inside the boundary and out of the water (§10.6), with a land use.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/gridify/untagged_land.hpp"
#include "urbanvec/streets/graph_noise.hpp"
#include "urbanvec/streets/hyperstreamlines.hpp"
#include "urbanvec/streets/tensor_field.hpp"

namespace urbanvec::streets {

struct StreetsInput {
  std::vector<DesignElement> design;   ///< grid and radial elements
  std::vector<LineString> fieldLines;  ///< roads, coastlines, rivers: each segment a regular element (§4.3)
  /// Roads kept in the network (spec §14): clipped to the boundary, traced roads grow around them.
  std::vector<LineString> existingRoads;
  std::optional<HeightMap> dem;  ///< height-field term (§4.4)
  MultiPolygon boundary;         ///< where streets grow (required)
  MultiPolygon water;
  MultiPolygon parks;
  std::optional<GridSpec> densitySpec;  ///< population density raster (any unit, normalised by its maximum)
  Grid<float> density;
};

struct StreetsOptions {
  /// The run seed. generateStreets hands it to every stage, over their own seed fields: the field's
  /// Perlin noise, the stop-short draws, the graph noise's Halton start (1 + seed mod 100000) and the
  /// bows; each stage salts its draws, so the streams stay independent.
  std::uint64_t seed = 1;
  FieldOptions field;
  TraceOptions trace;
  GraphNoiseOptions noise;
  /// Curved streets; its maxOffset is set from the minor d_sep (bowMaxOffsetRatio).
  BowOptions bow;
  /// Largest bow = ratio × minor d_sep: a quarter, so two facing bows never close the gap d_test
  /// (half a d_sep) between parallel streets.
  double bowMaxOffsetRatio = 0.25;
  /// Field cell = ratio × minor d_sep when field.cellSize is 0 (spec §16: cell ≈ d_sep_minor / 4).
  double fieldCellRatio = 0.25;
  /// Minor d_sep = ratio × major d_sep when the caller gives none. The spec's major / 4 (§16, "pure
  /// guess") puts the median edge of a city whose main roads are 150-200 m apart at 40-50 m, under
  /// the 5th percentile of the world's cities (52 m, Boeing 2020); half keeps it at 75-100 m, mid-range.
  double minorDsepRatio = 0.5;
  /// Least major d_sep (m) taken from the spacing of given roads (the CLI's -dsep-floor) [INFERENCE:
  /// the spec derives no d_sep from roads; 100 m keeps the derived minor d_sep at 50 m or more, near
  /// the narrowest common city blocks (Portland's 61 m), and keeps a full mapped network or a fine
  /// grid given as roads (a spacing of 20-60 m) from tracing tens of thousands of streets per km²;
  /// every derived d_sep of bench/streets/compare.sh is above it, 123-203 m].
  double derivedDsepFloor = 100.0;
  /// Noise wavelength = ratio × major d_sep when field.noiseWavelength is 0 (spec §16: 2).
  double noiseWavelengthRatio = 2.0;
  /// Polylines are resampled into elements about ratio × major d_sep apart (spec §4.3: d_sep / 2).
  double polylineSpacingRatio = 0.5;
  /// Decay radius σ of polyline elements = ratio × major d_sep (d = 1/σ²) [INFERENCE: the spec gives
  /// no value; one major spacing keeps a road's influence to its own neighbourhood].
  double polylineDecayRatio = 1.0;
  /// Snapping grid of the noding (m): pieces shorter than this vanish (no zero-length edges).
  double nodingTolerance = 0.01;
  /// Land use of blocks (a gridify class name) where the untagged-land rule finds no telling street
  /// (its defaultUse); the rule's other settings (street classes and their uses) are untaggedLand's.
  std::string defaultUse = "residential";
  gridify::UntaggedLandOptions untaggedLand;
  /// Land use of blocks where the density raster is zero (outside the urban extent).
  std::string emptyUse = "unused";
  /// Most design elements accepted (a larger design is refused as bad input).
  std::size_t maxDesignElements = 100000;
};

struct StreetEdge {
  LineString line;
  StreetLevel level = StreetLevel::Major;
};

struct StreetNode {
  Vec2 p;
  int degree = 0;
};

struct Block {
  Polygon shape;
  std::string landUse;
};

struct StreetNetwork {
  std::vector<StreetEdge> streets;  ///< between nodes (degree != 2 or a change of level)
  std::vector<StreetNode> nodes;
  std::vector<Block> blocks;
  TensorField field;
  TraceStats stats;
  std::size_t tracedLines = 0;
};

/// The spacing of the given roads over the land (the boundary minus the water): a grid of spacing s
/// has 2/s metres of road per m², so s = 2 A / L with A the land's area and L the roads' length on it
/// (m). The default major d_sep when roads shape the field, so that the network takes their scale;
/// 0 when no road lies on the land.
double roadSpacing(const std::vector<LineString>& roads, const MultiPolygon& boundary,
                   const MultiPolygon& water);

/// Runs the pipeline. Throws InvalidInput for an empty design, design points outside the boundary,
/// an empty boundary; InvalidOption for bad d_sep / d_test values. Water covering all land gives an
/// empty network (the caller warns).
StreetNetwork generateStreets(const StreetsInput& input, const StreetsOptions& options,
                              const Progress& progress = {});

}  // namespace urbanvec::streets
