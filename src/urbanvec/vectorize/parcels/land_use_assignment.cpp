// Spec §3 E4 and the Eq. 3.1-3.9 reconstruction of §4.2 (thesis §3.4.3 "Use Assignment"). OCR doubts
// are noted where each equation is implemented.
#include "urbanvec/vectorize/parcels/land_use_assignment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace urbanvec::vectorize::parcels {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::vector<double> normalized(std::vector<double> v) {
  const double sum = std::accumulate(v.begin(), v.end(), 0.0);
  if (sum <= 0.0 || !std::isfinite(sum)) return std::vector<double>(v.size(), 0.0);
  for (double& x : v) x /= sum;
  return v;
}
}  // namespace

int UseModel::indexOf(LandUse use) const {
  for (size_t i = 0; i < uses.size(); ++i)
    if (uses[i] == use) return static_cast<int>(i);
  return -1;
}

UseModel buildUseModel(const SimBlockSummary& sim, const LandUseOptions& options) {
  UseModel model;
  for (const SimParcel& p : sim.parcels)
    if (isDeveloped(p.use) && model.indexOf(p.use) < 0) model.uses.push_back(p.use);
  std::sort(model.uses.begin(), model.uses.end());
  const size_t n = model.uses.size();
  model.parcelsOfUse.resize(n);
  for (const SimParcel& p : sim.parcels) {
    const int i = model.indexOf(p.use);
    if (i >= 0) model.parcelsOfUse[i].push_back(&p);
  }
  const std::array<double, kLandUseClassCount> areas = simulatedUseAreas(sim);
  std::vector<double> useArea(n, 0.0);
  for (size_t i = 0; i < n; ++i) useArea[i] = areas[static_cast<size_t>(model.uses[i])];
  const double undevShare = sim.area > 0.0 ? sim.undevelopedArea / sim.area : 0.0;
  model.undevelopedActive = undevShare >= options.undevelopedSwitch;
  // Eq. 3.3: shares of developed land below the switch, of all land at or above it.
  const double developed =
      sim.developedArea > 0.0 ? sim.developedArea : std::accumulate(useArea.begin(), useArea.end(), 0.0);
  const double denominator = model.undevelopedActive ? sim.area : developed;
  for (size_t i = 0; i < n; ++i) model.simShare.push_back(denominator > 0.0 ? useArea[i] / denominator : 0.0);
  model.simUndevelopedShare = model.undevelopedActive ? undevShare : 0.0;
  const double developedShare = sim.area > 0.0 ? sim.developedArea / sim.area : 0.0;
  model.trivial = n == 1 && developedShare >= options.trivialDevelopedShare;
  for (size_t i = 0; i < n; ++i) {
    const auto& ps = model.parcelsOfUse[i];
    double mean = 0.0;
    for (const SimParcel* p : ps) mean += p->cells;
    mean /= static_cast<double>(ps.size());
    double var = 0.0;
    for (const SimParcel* p : ps) var += (p->cells - mean) * (p->cells - mean);
    double sigma = ps.size() > 1 ? std::sqrt(var / static_cast<double>(ps.size())) : 0.0;
    if (sigma <= 0.0) sigma = options.minSigmaFraction * mean;
    if (sigma <= 0.0) sigma = 1.0;
    model.meanSize.push_back(mean);
    model.sizeSigma.push_back(sigma);
  }
  return model;
}

std::vector<double> useDistances(const UseModel& model, const Vec2& centre) {
  std::vector<double> d(model.uses.size(), 0.0);
  for (size_t i = 0; i < model.uses.size(); ++i) {
    double best = 1e300;
    for (const SimParcel* p : model.parcelsOfUse[i]) best = std::min(best, distance(centre, p->centre));
    d[i] = best;
  }
  return d;
}

std::vector<double> distanceProbabilities(const std::vector<double>& distances, double epsilon) {
  std::vector<double> inv;
  for (double d : distances) inv.push_back(1.0 / std::max(d, epsilon));
  return normalized(std::move(inv));
}

std::vector<double> proportionProbabilities(const std::vector<double>& simShare,
                                            const std::vector<double>& share) {
  std::vector<double> puu;
  for (size_t i = 0; i < simShare.size(); ++i) puu.push_back(std::max(0.0, simShare[i] - share[i]));
  return normalized(std::move(puu));
}

std::vector<double> sizeProbabilities(double area, const std::vector<double>& mean,
                                      const std::vector<double>& sigma) {
  std::vector<double> likelihood;
  for (size_t i = 0; i < mean.size(); ++i) {
    const double z = (area - mean[i]) / sigma[i];
    likelihood.push_back(std::exp(-0.5 * z * z) / (sigma[i] * std::sqrt(2.0 * kPi)));
  }
  std::vector<double> p = normalized(likelihood);
  if (!p.empty() && std::accumulate(p.begin(), p.end(), 0.0) == 0.0) p.assign(p.size(), 1.0 / p.size());
  return p;
}

std::vector<double> combinedProbabilities(const std::vector<double>& pd, const std::vector<double>& pu,
                                          const std::vector<double>& ps) {
  std::vector<double> up(pd.size());
  for (size_t i = 0; i < pd.size(); ++i) up[i] = pd[i] * pu[i] * ps[i];
  std::vector<double> p = normalized(up);
  if (std::accumulate(p.begin(), p.end(), 0.0) > 0.0) return p;
  for (size_t i = 0; i < pd.size(); ++i) up[i] = pd[i] * ps[i];
  p = normalized(up);
  if (std::accumulate(p.begin(), p.end(), 0.0) > 0.0) return p;
  return normalized(pd);
}

std::vector<double> cumulativeProbabilities(const std::vector<double>& p) {
  std::vector<double> c(p.size());
  std::partial_sum(p.begin(), p.end(), c.begin());
  if (!c.empty()) c.back() = 1.0;
  return c;
}

size_t pickInterval(const std::vector<double>& cumulative, double r) {
  for (size_t i = 0; i < cumulative.size(); ++i)
    if (r < cumulative[i]) return i;
  return cumulative.empty() ? 0 : cumulative.size() - 1;
}

std::vector<UseChoice> assignLandUse(const std::vector<UseParcel>& parcels, double blockArea,
                                     const UseModel& model, const LandUseOptions& options, Rng& rng) {
  std::vector<UseChoice> choice(parcels.size());
  if (model.uses.empty()) {
    for (UseChoice& c : choice) c.undeveloped = true;
    return choice;
  }
  if (model.trivial) {
    for (UseChoice& c : choice) c.use = model.uses.front();
    return choice;
  }
  std::vector<size_t> order(parcels.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const size_t n = model.uses.size();
  std::vector<double> assignedArea(n, 0.0);
  double undevelopedArea = 0.0;
  for (size_t k : order) {
    std::vector<double> share(n);
    for (size_t i = 0; i < n; ++i) share[i] = blockArea > 0.0 ? assignedArea[i] / blockArea : 0.0;  // Eq. 3.4
    const double r1 = unit(rng);
    if (model.undevelopedActive) {
      // Decision 1: only the proportion term, over all uses including undeveloped.
      std::vector<double> simAll = model.simShare, shareAll = share;
      simAll.push_back(model.simUndevelopedShare);
      shareAll.push_back(blockArea > 0.0 ? undevelopedArea / blockArea : 0.0);
      const std::vector<double> pu = proportionProbabilities(simAll, shareAll);
      if (r1 < pu.back()) {
        choice[k].undeveloped = true;
        undevelopedArea += parcels[k].area;
        continue;
      }
    }
    // Decision 2: which developed use.
    const std::vector<double> pd =
        distanceProbabilities(useDistances(model, parcels[k].centre), options.distanceEpsilon);
    const std::vector<double> pu = proportionProbabilities(model.simShare, share);
    const std::vector<double> ps = sizeProbabilities(parcels[k].area, model.meanSize, model.sizeSigma);
    const std::vector<double> c = cumulativeProbabilities(combinedProbabilities(pd, pu, ps));
    const size_t i = pickInterval(c, unit(rng));
    choice[k].use = model.uses[i];
    assignedArea[i] += parcels[k].area;
  }
  return choice;
}

}  // namespace urbanvec::vectorize::parcels
