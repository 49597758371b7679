// From structured-walk averages to a comparable fractal dimension: per-scale dimensions, their
// regression line and its scatter (spec wijgerse-boundary.md §6.3-§6.5, thesis Eqs. 4.1-4.13).
#pragma once

#include <optional>
#include <vector>

namespace urbanvec::shape {

struct FractalRegression {
  std::vector<double> logChord;      ///< ln r_n of the points used, n = 1..
  std::vector<double> dimensions;    ///< D_n = (ln N_0 - ln N_n) / ln(r_n / r_0)  (Eq. 4.1)
  double slope = 0.0;                ///< a of D = a ln r + b (Eq. 4.9)
  double intercept = 0.0;            ///< b
  double sigma = 0.0;                ///< sqrt(mean squared residual)  (Eqs. 4.12-4.13)
  double evaluationLogChord = 0.0;   ///< R where the line is read
  double comparableDimension = 0.0;  ///< D_R = a R + b  (Eq. 4.10)
  double logChordSpan = 0.0;         ///< max ln r_n - min ln r_n over the points (denominator of Eq. 4.11)
};

/// Regresses the dimensions of scales 1..W-1 against scale 0. `chordCounts` are N_n, `meanChords` r_n.
/// `evaluationLogChord` is R; without it, the line is read at the mean ln r_n of the points (where D_R
/// equals the mean D_n), which is how the thesis derived R = 2.5696 for its own pixel hulls.
/// Scales whose ln(r_n / r_0) is not positive are skipped. Throws InvalidInput with fewer than 2 points.
FractalRegression fractalRegression(const std::vector<double>& chordCounts,
                                    const std::vector<double>& meanChords,
                                    std::optional<double> evaluationLogChord);

}  // namespace urbanvec::shape
