// The tensor field of Chen et al. 2008 (spec chen-streets.md §3-§6): symmetric traceless tensors
// t = R [cos 2θ, sin 2θ; sin 2θ, −cos 2θ] stored as (a, b) = (R cos 2θ, R sin 2θ) on a regular grid
// D in world units (metres) and interpolated bilinearly; basis fields from grid and radial design
// elements and from polylines (each segment a regular element, §4.3) blended with Eq. 3; an optional
// height-field term (§4.4) and Laplacian (Jacobi) smoothing (§6.1).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::streets {

struct Tensor {
  double a = 0.0;  ///< R cos 2θ
  double b = 0.0;  ///< R sin 2θ
  /// Tensor whose major eigenvector is u (|u| = magnitude): a = (ux² − uy²)/l, b = 2 ux uy / l (§3.2).
  static Tensor fromDirection(const Vec2& u);
  /// Tensor with major direction θ (radians, counter-clockwise from +x) and magnitude r.
  static Tensor fromAngle(double theta, double r);
  double magnitude() const;
  /// Major direction θ = ½ atan2(b, a), in (−π/2, π/2].
  double angle() const;
  Vec2 major() const;  ///< unit major eigenvector (cos θ, sin θ)
  Vec2 minor() const;  ///< unit minor eigenvector (−sin θ, cos θ)
  Tensor operator+(const Tensor& o) const { return {a + o.a, b + o.b}; }
  Tensor operator*(double s) const { return {a * s, b * s}; }
};

enum class ElementKind { Grid, Radial };

/// A design element (§4.1, §4.2), or one segment of a polyline (§4.3, a regular element at A).
struct DesignElement {
  ElementKind kind = ElementKind::Grid;
  Vec2 position;
  /// Grid: major direction, radians counter-clockwise from east.
  double angle = 0.0;
  /// Grid: magnitude l (Eq. 1). Radial: the radius (m) at which its magnitude r² / size² is 1.
  double size = 1.0;
  /// Decay constant d of Eq. 3 (1/m²); <= 0 = the field's default decay.
  double decay = 0.0;
};

/// The basis tensor of one element at p, without the Eq. 3 weight.
Tensor basisTensor(const DesignElement& e, const Vec2& p);

struct FieldOptions {
  /// Cell size of grid D (m). The spec: about a quarter of the minor d_sep.
  double cellSize = 20.0;
  /// Default decay d of Eq. 3 is 1/σ² with σ this share of the domain width (spec §5, §16: 0.25).
  double decayRadiusShare = 0.25;
  /// Decay radius σ (m) of polyline segments (d = 1/σ²): the spec leaves it open; 0 = half the major
  /// d_sep given by the caller through polylineDecayRadius.
  double polylineDecayRadius = 0.0;
  /// Weight of the height-field term per unit slope (m/m) added to the normalised element blend
  /// (spec §4.4: a global additive term w_H) [INFERENCE].
  double heightWeight = 10.0;
  /// Jacobi smoothing iterations, λ = 1, 4-neighbourhood (spec §6.1, §16: 20).
  int smoothingIterations = 20;
  /// Perlin-noise rotation θ ← θ + N(p) of the whole field after smoothing (spec §7, §16: amplitude
  /// 0.1 to 0.3 rad, wavelength about 2 major d_sep): streets curve a little and stop lining up.
  double noiseAmplitude = 0.2;   ///< radians, at most π/2; 0 = no noise
  double noiseWavelength = 0.0;  ///< metres; 0 = set by the caller (2 × major d_sep)
  int noiseOctaves = 2;
  /// Seed of the noise (generateStreets sets it from StreetsOptions::seed).
  std::uint64_t seed = 1;
  /// Worker threads for the per-vertex evaluation (results do not depend on it).
  int threads = 1;
};

/// 2-D Perlin gradient noise at p (in wavelengths), octaves halving in size and amplitude, roughly in
/// [−1, 1]; gradients come from the seed and the lattice point only.
double perlin(const Vec2& p, int octaves, std::uint64_t seed);

/// A height map on its own frame (metres), for the height-field term.
struct HeightMap {
  GridSpec spec;
  Grid<float> heights;
  std::vector<std::uint8_t> valid;  ///< per cell; empty = all valid
};

class TensorField {
 public:
  TensorField() = default;
  /// Grid D over [minCorner, maxCorner] with the given cell size.
  TensorField(const Vec2& minCorner, const Vec2& maxCorner, double cellSize);

  int width() const { return nx_; }
  int height() const { return ny_; }
  double cellSize() const { return cell_; }
  const Vec2& origin() const { return origin_; }
  Tensor& at(int i, int j) { return t_[static_cast<std::size_t>(j) * nx_ + i]; }
  const Tensor& at(int i, int j) const { return t_[static_cast<std::size_t>(j) * nx_ + i]; }
  Vec2 vertex(int i, int j) const { return {origin_.x + i * cell_, origin_.y + j * cell_}; }
  /// Bilinear interpolation of a and b (§3.2); clamped at the grid's edge.
  Tensor sample(const Vec2& p) const;
  /// Median magnitude over the vertices (the reference of the degeneracy test).
  double medianMagnitude() const;
  /// `iterations` Jacobi sweeps T ← mean of 4-neighbours (§6.1, λ = 1).
  void smooth(int iterations);

 private:
  Vec2 origin_;
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<Tensor> t_;
};

/// Builds the field on grid D: Eq. 3 over `elements` (weights taken relative to the nearest element,
/// which keeps directions exact, spec §5 "Numerics"), normalised by the weight sum, plus the height
/// term, then smoothing. Elements with decay <= 0 get 1/σ² with σ = decayRadiusShare × domain width.
/// Throws InvalidInput when there is no element and no height map.
TensorField buildField(const Vec2& minCorner, const Vec2& maxCorner,
                       const std::vector<DesignElement>& elements, const HeightMap* heights,
                       const FieldOptions& options, const Progress& progress = {});

/// Each segment AB of each polyline as a regular element at A with major direction AB and unit
/// magnitude (§4.3, l normalised); segments longer than `spacing` are cut into pieces of about it.
std::vector<DesignElement> polylineElements(const std::vector<LineString>& lines, double spacing,
                                            double decay);

}  // namespace urbanvec::streets
