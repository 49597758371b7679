// The generator pipeline, spec wijgerse-boundary.md §1 (steps), §4 (method 4 regeneration) and §9.6
// (validate and regenerate, as the thesis recommends for production use).
#include "urbanvec/boundary/generate_boundary.hpp"

#include <cmath>
#include <string>

#include "urbanvec/boundary/cell_outline.hpp"
#include "urbanvec/boundary/islands.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/random.hpp"

namespace urbanvec::boundary {

Ring ringThroughCentres(const std::vector<Pixel>& chain) {
  Ring ring;
  const size_t n = chain.size();
  ring.reserve(n + 1);
  for (size_t i = 0; i < n; ++i) {
    const Pixel& before = chain[(i + n - 1) % n];
    const Pixel& here = chain[i];
    const Pixel& after = chain[(i + 1) % n];
    const bool straight =
        n > 2 && here.x - before.x == after.x - here.x && here.y - before.y == after.y - here.y;
    if (!straight) ring.emplace_back(here.x + 0.5, here.y + 0.5);
  }
  if (!ring.empty()) ring.push_back(ring.front());
  return ring;
}

PerlinSeed trySeed(PerlinSeed runSeed, int index) {
  if (index == 0) return runSeed;
  return static_cast<PerlinSeed>(deriveSeed(runSeed, static_cast<std::uint64_t>(index)) >> 32);
}

BoundaryAttempt attemptBoundary(const BoundaryOptions& options, PerlinSeed seed) {
  BoundaryAttempt attempt;
  attempt.seed = seed;
  {
    // The float images are freed as soon as the mask exists. Held to the end, they left megabytes
    // free at the top of the heap after every bitmap, which the allocator returned to the system and
    // faulted in again for the next one (75 page faults per bitmap, 2 % system time in the bench).
    const Grid<float> image = radialTransform(perlinNoise(options.noise, seed), options.transform);
    attempt.threshold = fillThreshold(image, options.threshold);
    attempt.mask = applyThreshold(image, attempt.threshold.threshold);
  }
  size_t filled = 0;
  for (std::uint8_t v : attempt.mask.cells) filled += v;
  attempt.fillRatio = static_cast<double>(filled) / static_cast<double>(attempt.mask.size());
  // Method 4: a threshold at or below the highest rim value fails, and the thesis starts over.
  if (!attempt.threshold.aboveRim) return attempt;
  attempt.chain = traceLongestContour(attempt.mask, options.trace);
  if (attempt.chain.size() < 3) return attempt;
  try {
    attempt.metrics = shape::measureShape(ringThroughCentres(attempt.chain), options.realism);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::InvalidInput) throw;
  }
  return attempt;
}

BoundaryResult generateBoundary(const BoundaryOptions& options, const Progress& progress) {
  if (options.maxTries < 1)
    throw invalidOption("-max-tries must be at least 1, got " + std::to_string(options.maxTries));
  if (!(options.suburbMinimumPixels >= 0.0) || !std::isfinite(options.suburbMinimumPixels))
    throw invalidOption("the minimum suburb area (-suburbs) must be a finite number >= 0, got " +
                        std::to_string(options.suburbMinimumPixels) + " pixels");
  BoundaryResult result;
  bool kept = false;
  for (int t = 0; t < options.maxTries; ++t) {
    reportProgress(progress, 0.9 * t / options.maxTries, "generating");
    BoundaryAttempt attempt = attemptBoundary(options, trySeed(options.seed, t));
    ++result.tries;
    if (attempt.hasHull() && attempt.metrics) {
      result.attempt = std::move(attempt);
      kept = true;
      if (!options.validate || result.attempt.realistic()) break;
    }
  }
  if (!kept)
    throw invalidInput(
        "no boundary in " + std::to_string(result.tries) + " tr" + (result.tries == 1 ? "y" : "ies") +
        ": the fill-ratio threshold always fell below the highest rim value (threshold method 4); "
        "lower -fill or -c2, use coarser -layers, or raise -max-tries");
  reportProgress(progress, 0.9, "tracing");
  result.ring = ringThroughCentres(result.attempt.chain);
  const Grid<std::uint8_t>& mask = result.attempt.mask;
  result.city.outer = cellOutline(mask, result.attempt.chain.front());
  if (options.suburbMinimumPixels > 0.0)
    for (const std::vector<Pixel>& island :
         traceIslands(mask, result.attempt.chain, options.suburbMinimumPixels))
      result.suburbs.push_back(Polygon{cellOutline(mask, island.front()), {}});
  reportProgress(progress, 1.0, "done");
  return result;
}

}  // namespace urbanvec::boundary
