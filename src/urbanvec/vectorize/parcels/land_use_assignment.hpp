// Stage E4 of the vectorizer: land-use assignment (spec §3 E4, §4.1-4.2 Eq. 3.1-3.9, Q22-Q23; thesis
// §3.4.3 "Use Assignment", paper §3.4.2). The trivial case gives every parcel the block's single use;
// otherwise each parcel (in random order) is first made undeveloped or not from the proportion term,
// then gets a developed use drawn from p_i = pd_i·pu_i·ps_i normalized.
#pragma once

#include <vector>

#include "urbanvec/core/random.hpp"
#include "urbanvec/vectorize/parcels/parcel_input.hpp"

namespace urbanvec::vectorize::parcels {

struct LandUseOptions {
  /// Trivial case: a single simulated use and at least this developed share (spec §5.4: 75%).
  double trivialDevelopedShare = 0.75;
  /// Undeveloped share at which Eq. 3.3 switches denominators and undeveloped becomes a candidate
  /// use (spec §5.4: 0.25; "≥" per the spec's edge-case note), unitless.
  double undevelopedSwitch = 0.25;
  /// σ of the size likelihood for a use with one simulated parcel, as a share of its mean size
  /// [INFERENCE, §6: 0.5].
  double minSigmaFraction = 0.5;
  /// Distance used instead of 0 in 1/d_i [INFERENCE, §6: 1e-6 pw], cells.
  double distanceEpsilon = 1e-6;
};

/// A parcel as E4/E5 see it.
struct UseParcel {
  double area = 0.0;  ///< cells²
  Vec2 centre;        ///< area centroid, cells
};

/// The assigned use of one parcel.
struct UseChoice {
  bool undeveloped = false;
  LandUse use = LandUse::Unused;
};

/// What the simulated block says about uses: candidate developed uses (in enum order), their
/// simulated shares us_i (Eq. 3.3), the undeveloped share, and the per-use size statistics.
struct UseModel {
  std::vector<LandUse> uses;                ///< developed uses present among the simulated parcels
  std::vector<double> simShare;             ///< us_i, same order
  double simUndevelopedShare = 0.0;         ///< us_undev (only meaningful when undevelopedActive)
  bool undevelopedActive = false;           ///< undeveloped share ≥ the switch: undeveloped is a candidate
  bool trivial = false;                     ///< single use and developed enough: everything gets uses[0]
  std::vector<double> meanSize, sizeSigma;  ///< as_i, ds_i (σ_min applied), cells²
  std::vector<std::vector<const SimParcel*>> parcelsOfUse;  ///< simulated parcels per candidate use
  int indexOf(LandUse use) const;
};
UseModel buildUseModel(const SimBlockSummary& sim, const LandUseOptions& options);

/// Eq. 3.1: distance from `centre` to the nearest simulated parcel of each candidate use (cells).
std::vector<double> useDistances(const UseModel& model, const Vec2& centre);
/// Eq. 3.2 (reconstructed; the OCR lost the body): pd_i = (1/d_i) / Σ_j 1/d_j, with d = 0 → ε.
std::vector<double> distanceProbabilities(const std::vector<double>& distances, double epsilon);
/// Eq. 3.5-3.6: puu_i = max(0, us_i − u_i) (OCR dropped the minus), pu_i = puu_i / Σ_j puu_j; all zero
/// when every use has reached its share.
std::vector<double> proportionProbabilities(const std::vector<double>& simShare,
                                            const std::vector<double>& share);
/// Eq. 3.7: ps_i = normal(a; as_i, ds_i) / Σ_j normal(a; as_j, ds_j); uniform when every likelihood
/// underflows.
std::vector<double> sizeProbabilities(double area, const std::vector<double>& mean,
                                      const std::vector<double>& sigma);
/// Eq. 3.8: up_i = pd_i·pu_i·ps_i (product: the OCR lost the operators, UNCERTAIN), p_i = up_i / Σ up_j;
/// falls back to pd·ps, then pd, when the product vanishes (spec E4 degenerate cases).
std::vector<double> combinedProbabilities(const std::vector<double>& pd, const std::vector<double>& pu,
                                          const std::vector<double>& ps);
/// Eq. 3.9: c_i = Σ_{j≤i} p_j, with the last forced to exactly 1.
std::vector<double> cumulativeProbabilities(const std::vector<double>& p);
/// The index whose interval [c_{i-1}, c_i) holds r.
size_t pickInterval(const std::vector<double>& cumulative, double r);

/// Assigns a use to every parcel (spec E4). `blockArea` is the vector block's area (Eq. 3.4).
std::vector<UseChoice> assignLandUse(const std::vector<UseParcel>& parcels, double blockArea,
                                     const UseModel& model, const LandUseOptions& options, Rng& rng);

}  // namespace urbanvec::vectorize::parcels
