// Street tracing along hyperstreamlines (spec chen-streets.md §8 integration and stopping, §9
// interleaved seeding, §11 density, §12 minor roads): major roads first, then minor roads that end
// on them, both levels interleaving the major and minor eigenvector families; RK4 with sign
// alignment at every stage, d_sep / d_test separation within a family, look-ahead joins that turn
// dangling ends into T-junctions. All lengths in metres.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/streets/tensor_field.hpp"

namespace urbanvec::streets {

struct TraceOptions {
  /// d_sep of major roads (m). The spec's domain/8 suits its unit-square scenes, not real cities of
  /// any size [INFERENCE]: 4 × the minor d_sep, the spec's major/minor ratio (§16).
  double majorDsep = 360.0;
  /// d_sep of minor roads (m): the spec's major / 4 (§16), a typical urban block side.
  double minorDsep = 90.0;
  /// d_test = ratio × d_sep (Jobard & Lefer, spec §8.3 and §16: 0.5).
  double dtestRatio = 0.5;
  /// Look-ahead d_lookahead = ratio × d_sep (spec §16: 1.0).
  double lookaheadRatio = 1.0;
  /// Integration step (m); 0 = half a field cell (spec §8.2: h_max about 0.5 cell).
  double step = 0.0;
  /// Lines shorter than ratio × d_sep are dropped (spec §8.3 "Minimum length": 0.5 d_sep).
  double minLengthRatio = 0.5;
  /// Loop closing: after 2 d_sep of travel, passing within ratio × d_test of its seed. The spec's
  /// min(0.5 h, 0.1 d_sep) (§16) misses loops of a smoothed, interpolated field, which spiral by more
  /// than half a step per turn and then wind round until the maximum length [ADAPTED].
  double loopRatio = 0.25;
  /// Degenerate point: |T| < epsilon × median |T| (spec §16: 1e-6).
  double degenerateEpsilon = 1e-6;
  /// Maximum length of one street (m); 0 = the domain's diagonal (spec §8.3).
  double maxLength = 0.0;
  /// Density mapping d_sep(p) = d_sep + (maxFactor − 1) d_sep (1 − P(p))^gamma (spec §11: 3, 1).
  double densityMaxFactor = 3.0;
  double densityGamma = 1.0;
  /// d_sep is multiplied by this inside parks (spec §11: 2).
  double parkFactor = 2.0;
  /// Seed priority ω = e^(−d_b / λ) with λ = this × d_sep (spec §9.3: λ_ω = d_sep).
  double priorityScaleRatio = 1.0;
  /// Seeds closer than ratio × the integration step to the boundary or the water's edge are not
  /// used: a street seeded on the edge (at the end of a street clipped there) leaves it at a right
  /// angle, and the two meet at a corner on the edge that no junction explains [INFERENCE; 0 = off].
  double edgeSeedRatio = 1.0;
  /// Share of the ends of minor roads that would join a street (a T-junction on a major road or a
  /// look-ahead join, §8.3, §12) which stop d_test short of it instead and stay dangling: cul-de-sacs
  /// and streets that do not reach the next one (spec §8.3 "the line ends as a dangling end",
  /// §13.6 "streets that stop"). Each end draws its own chance from the run seed; only a road that
  /// joins streets at both ends stops short, at one end at most, so none is cut off. A traced network
  /// without it ends almost every minor road on the next street, so its dead-end share stays under
  /// the 5th percentile of the world's cities (0.05, Boeing 2020) [INFERENCE: no value in the spec;
  /// the default puts the generated networks near the middle of Boeing's 0.05-0.30: medians 0.065-
  /// 0.206 over bench/streets/compare.sh's generated areas, seeds 1-8, where 0.25 and 0.35 lower
  /// the 3-way share more than they add (docs/streets.md); 0 = off].
  double stopShortShare = 0.15;
  /// A minor-road seed keeps ratio × d_sep_minor from the major roads of its family (it keeps the full
  /// d_sep from the minor ones). The major roads bound the regions minor roads are traced in (§12), and
  /// at the default d_sep_minor = d_sep_major / 2 the one minor road a region between two parallel
  /// major roads can hold lies exactly d_sep_minor from both: with the full d_sep (1) the field's noise
  /// leaves most such regions empty, so a grid design's nodes are mostly major crossings (4-way share
  /// 0.46-0.54 on bench/streets/speed.sh's cities, over Boeing's 0.42). d_test (0.5), the distance a
  /// traced street stops at, fills them (4-way 0.32) but makes the sample cities' kept networks 1.3-2.3 ×
  /// as dense as before (kept matches 17.9 -> 13.3 of 28, seeds 1-8); so the default stays 1
  /// [INFERENCE: the spec traces each region on its own; docs/streets.md].
  double majorClearanceRatio = 1.0;
  /// Seed of the per-end draws (the run seed; generateStreets sets it from StreetsOptions::seed).
  std::uint64_t seed = 1;
  /// Trace minor roads (the second level).
  bool minorRoads = true;
  /// Minor-road seeds lie this far (m) beside the major road they start from, so that they begin in
  /// one region and end on the road (well above the noding tolerance).
  double sideOffset = 0.5;
};

/// Where streets may grow.
struct TraceDomain {
  MultiPolygon land;   ///< the boundary: streets stay inside
  MultiPolygon water;  ///< no street inside
  MultiPolygon parks;  ///< d_sep × parkFactor inside
  /// Population density normalised to [0, 1] on its frame (empty = P ≡ 1, d_sep everywhere).
  std::optional<GridSpec> densitySpec;
  Grid<float> density;
  /// Existing roads kept in the network (spec §14 local editing, the old network outside the traced
  /// region): traced roads keep their d_sep from them, minor roads end on them in T-junctions, and
  /// minor-road seeds are placed along them like along a traced major road.
  std::vector<LineString> existing;
};

/// Outline marks the boundary and water outlines noded with the streets (for the blocks).
enum class StreetLevel : std::uint8_t { Major = 0, Minor = 1, Outline = 2, Existing = 3 };

struct Street {
  LineString line;
  StreetLevel level = StreetLevel::Major;
  int family = 0;  ///< 0 = major eigenvector, 1 = minor eigenvector (an existing road: either)
};

struct TraceStats {
  std::size_t seedsTried = 0;
  std::size_t lookaheadJoins = 0;
  std::size_t droppedShort = 0;
};

/// Traces the network. `seeds` are tried first (design-element positions), in order.
std::vector<Street> traceStreets(const TensorField& field, const TraceDomain& domain,
                                 const std::vector<Vec2>& seeds, const TraceOptions& options,
                                 TraceStats* stats = nullptr, const Progress& progress = {});

}  // namespace urbanvec::streets
