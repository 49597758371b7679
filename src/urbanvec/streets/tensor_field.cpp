// Tensor field design (spec chen-streets.md §3 representation, §4 basis fields, §5 Eq. 3 blending,
// §4.4 height field, §6.1 smoothing).
#include "urbanvec/streets/tensor_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <thread>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/core/uniform_grid.hpp"

namespace urbanvec::streets {

Tensor Tensor::fromDirection(const Vec2& u) {
  const double l = length(u);
  if (l == 0.0) return {};
  return {(u.x * u.x - u.y * u.y) / l, 2.0 * u.x * u.y / l};
}

Tensor Tensor::fromAngle(double theta, double r) {
  return {r * std::cos(2.0 * theta), r * std::sin(2.0 * theta)};
}

double Tensor::magnitude() const {
  return std::sqrt(a * a + b * b);
}
double Tensor::angle() const {
  return 0.5 * std::atan2(b, a);
}
Vec2 Tensor::major() const {
  const double t = angle();
  return {std::cos(t), std::sin(t)};
}
Vec2 Tensor::minor() const {
  const double t = angle();
  return {-std::sin(t), std::cos(t)};
}

Tensor basisTensor(const DesignElement& e, const Vec2& p) {
  if (e.kind == ElementKind::Grid) return Tensor::fromAngle(e.angle, e.size);
  // Eq. 2: a = y² − x², b = −2xy around the centre; magnitude r² / size².
  const double x = p.x - e.position.x, y = p.y - e.position.y;
  const double s2 = e.size > 0.0 ? e.size * e.size : 1.0;
  return {(y * y - x * x) / s2, -2.0 * x * y / s2};
}

TensorField::TensorField(const Vec2& minCorner, const Vec2& maxCorner, double cellSize)
    : origin_(minCorner), cell_(cellSize) {
  nx_ = std::max(2, static_cast<int>(std::ceil((maxCorner.x - minCorner.x) / cellSize)) + 1);
  ny_ = std::max(2, static_cast<int>(std::ceil((maxCorner.y - minCorner.y) / cellSize)) + 1);
  t_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
}

Tensor TensorField::sample(const Vec2& p) const {
  double fx = std::clamp((p.x - origin_.x) / cell_, 0.0, nx_ - 1.0);
  double fy = std::clamp((p.y - origin_.y) / cell_, 0.0, ny_ - 1.0);
  const int i = std::min(static_cast<int>(fx), nx_ - 2), j = std::min(static_cast<int>(fy), ny_ - 2);
  fx -= i, fy -= j;
  const Tensor &t00 = at(i, j), &t10 = at(i + 1, j), &t01 = at(i, j + 1), &t11 = at(i + 1, j + 1);
  const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  return {t00.a * w00 + t10.a * w10 + t01.a * w01 + t11.a * w11,
          t00.b * w00 + t10.b * w10 + t01.b * w01 + t11.b * w11};
}

double TensorField::medianMagnitude() const {
  std::vector<double> m;
  m.reserve(t_.size());
  for (const Tensor& t : t_) m.push_back(t.magnitude());
  if (m.empty()) return 0.0;
  std::nth_element(m.begin(), m.begin() + static_cast<std::ptrdiff_t>(m.size() / 2), m.end());
  return m[m.size() / 2];
}

void TensorField::smooth(int iterations) {
  std::vector<Tensor> next(t_.size());
  for (int it = 0; it < iterations; ++it) {
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        Tensor sum;
        int n = 0;
        if (i > 0) sum = sum + at(i - 1, j), ++n;
        if (i + 1 < nx_) sum = sum + at(i + 1, j), ++n;
        if (j > 0) sum = sum + at(i, j - 1), ++n;
        if (j + 1 < ny_) sum = sum + at(i, j + 1), ++n;
        next[static_cast<std::size_t>(j) * nx_ + i] = sum * (1.0 / n);
      }
    t_.swap(next);
  }
}

std::vector<DesignElement> polylineElements(const std::vector<LineString>& lines, double spacing,
                                            double decay) {
  std::vector<DesignElement> out;
  for (const LineString& line : lines)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec2 a = line[i], b = line[i + 1];
      const double len = distance(a, b);
      if (len <= 0.0) continue;
      const int pieces = std::max(1, static_cast<int>(std::ceil(len / spacing)));
      const double theta = std::atan2(b.y - a.y, b.x - a.x);
      for (int k = 0; k < pieces; ++k) {
        DesignElement e;
        e.kind = ElementKind::Grid;
        e.position = a + (b - a) * (static_cast<double>(k) / pieces);
        e.angle = theta;
        e.size = 1.0;
        e.decay = decay;
        out.push_back(e);
      }
    }
  return out;
}

double perlin(const Vec2& p, int octaves, std::uint64_t seed) {
  double sum = 0.0, norm = 0.0, scale = 1.0, weight = 1.0;
  for (int o = 0; o < std::max(1, octaves); ++o) {
    const double x = p.x * scale, y = p.y * scale;
    const long i0 = static_cast<long>(std::floor(x)), j0 = static_cast<long>(std::floor(y));
    auto grad = [&](long i, long j, double dx, double dy) {
      const std::uint64_t h =
          deriveSeed(seed + static_cast<std::uint64_t>(o) * 0x51ED27ULL,
                     (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint32_t>(j));
      const double a = static_cast<double>(h >> 11) * (2.0 * M_PI / 9007199254740992.0);
      return std::cos(a) * dx + std::sin(a) * dy;
    };
    auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
    const double fx = x - i0, fy = y - j0, u = fade(fx), v = fade(fy);
    const double n00 = grad(i0, j0, fx, fy), n10 = grad(i0 + 1, j0, fx - 1, fy);
    const double n01 = grad(i0, j0 + 1, fx, fy - 1), n11 = grad(i0 + 1, j0 + 1, fx - 1, fy - 1);
    const double n = (n00 * (1 - u) + n10 * u) * (1 - v) + (n01 * (1 - u) + n11 * u) * v;
    sum += weight * n * std::sqrt(2.0);
    norm += weight;
    scale *= 2.0, weight *= 0.5;
  }
  return std::clamp(sum / norm, -1.0, 1.0);
}

namespace {

/// Elements sharing one decay in buckets, for the nearest element and the elements within a radius.
class ElementBuckets {
 public:
  ElementBuckets(const std::vector<const DesignElement*>& elements, double cell) {
    if (elements.empty()) return;
    double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
    for (const DesignElement* e : elements) {
      minX = std::min(minX, e->position.x), maxX = std::max(maxX, e->position.x);
      minY = std::min(minY, e->position.y), maxY = std::max(maxY, e->position.y);
    }
    grid_.init({minX, minY}, {maxX, maxY}, cell);
    for (const DesignElement* e : elements) grid_.insert(e->position, e);
  }
  bool empty() const { return grid_.empty(); }
  /// Squared distance to the nearest element. A point outside the buckets starts from the nearest
  /// bucket: its distance to any element is at least that of its projection onto the grid's box.
  double nearest2(const Vec2& p) const {
    const int ci = grid_.column(p.x), cj = grid_.row(p.y);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0;; ++ring) {
      // Buckets at Chebyshev distance `ring` are at least (ring - 1) buckets away.
      const double reach = std::max(0, ring - 1) * grid_.cell();
      if (reach * reach > best) break;
      const bool any = grid_.forRing(ci, cj, ring, [&](const std::vector<const DesignElement*>& bucket) {
        for (const DesignElement* e : bucket) {
          const Vec2 d = e->position - p;
          best = std::min(best, dot(d, d));
        }
      });
      if (!any) break;
    }
    return best;
  }
  template <class Fn>
  void within(const Vec2& p, double radius, Fn fn) const {
    grid_.forBox(p - Vec2{radius, radius}, p + Vec2{radius, radius},
                 [&](const std::vector<const DesignElement*>& bucket) {
                   for (const DesignElement* e : bucket) fn(*e);
                 });
  }

 private:
  UniformGrid<const DesignElement*> grid_;
};

/// Height H at a world point by bilinear interpolation of the map (NaN outside or on invalid cells).
double heightAt(const HeightMap& map, const Vec2& p) {
  const Vec2 px = map.spec.transform.worldToPixel(p);
  const double fx = px.x - 0.5, fy = px.y - 0.5;
  const int i = static_cast<int>(std::floor(fx)), j = static_cast<int>(std::floor(fy));
  if (i < 0 || j < 0 || i + 1 >= map.heights.width || j + 1 >= map.heights.height) return std::nan("");
  auto h = [&](int x, int y) -> double {
    const std::size_t k = static_cast<std::size_t>(y) * map.heights.width + x;
    if (!map.valid.empty() && !map.valid[k]) return std::nan("");
    return map.heights.cells[k];
  };
  const double u = fx - i, v = fy - j;
  return h(i, j) * (1 - u) * (1 - v) + h(i + 1, j) * u * (1 - v) + h(i, j + 1) * (1 - u) * v +
         h(i + 1, j + 1) * u * v;
}

/// §4.4: the minor eigenvector follows ∇H: a = −(gx² − gy²)/|g|, b = −2 gx gy / |g|.
Tensor heightTensor(const HeightMap& map, const Vec2& p) {
  const double d = map.spec.transform.cellSize();
  const double hx1 = heightAt(map, p + Vec2{d, 0}), hx0 = heightAt(map, p - Vec2{d, 0});
  const double hy1 = heightAt(map, p + Vec2{0, d}), hy0 = heightAt(map, p - Vec2{0, d});
  if (!std::isfinite(hx1 + hx0 + hy1 + hy0)) return {};
  const double gx = (hx1 - hx0) / (2 * d), gy = (hy1 - hy0) / (2 * d);
  const double g = std::sqrt(gx * gx + gy * gy);
  if (g == 0.0) return {};
  return {-(gx * gx - gy * gy) / g, -2.0 * gx * gy / g};
}

}  // namespace

TensorField buildField(const Vec2& minCorner, const Vec2& maxCorner,
                       const std::vector<DesignElement>& elements, const HeightMap* heights,
                       const FieldOptions& options, const Progress& progress) {
  if (elements.empty() && !heights)
    throw invalidInput(
        "the street design is empty: give design elements, roads or lines for the field, or a DEM");
  if (!(options.cellSize > 0.0)) throw invalidOption("the field cell size must be > 0");
  TensorField field(minCorner, maxCorner, options.cellSize);
  const double width = std::max(maxCorner.x - minCorner.x, maxCorner.y - minCorner.y);
  const double sigma = options.decayRadiusShare * width;
  const double defaultDecay = 1.0 / (sigma * sigma);
  // Elements by decay: the few of their own (design points) are summed directly; the many sharing the
  // most common decay (polyline segments) go into buckets.
  std::vector<const DesignElement*> bucketed, direct;
  double bucketDecay = 0.0;
  std::map<double, std::size_t> decayCount;
  for (const DesignElement& e : elements) ++decayCount[e.decay > 0.0 ? e.decay : defaultDecay];
  std::size_t most = 0;
  for (const auto& [d, n] : decayCount)
    if (n > most) most = n, bucketDecay = d;
  for (const DesignElement& e : elements) {
    const double d = e.decay > 0.0 ? e.decay : defaultDecay;
    if (most > 64 && d == bucketDecay)
      bucketed.push_back(&e);
    else
      direct.push_back(&e);
  }
  const ElementBuckets buckets(bucketed, bucketDecay > 0 ? 2.0 / std::sqrt(bucketDecay) : 1.0);
  const double cutoff = 30.0;  // weights below e^-30 of the largest are dropped
  auto evaluate = [&](const Vec2& p) {
    double m = std::numeric_limits<double>::infinity();
    for (const DesignElement* e : direct) {
      const Vec2 d = e->position - p;
      m = std::min(m, (e->decay > 0.0 ? e->decay : defaultDecay) * dot(d, d));
    }
    if (!buckets.empty()) m = std::min(m, bucketDecay * buckets.nearest2(p));
    Tensor sum;
    double wsum = 0.0;
    auto add = [&](const DesignElement& e, double d) {
      const Vec2 v = e.position - p;
      const double x = d * dot(v, v) - m;
      if (x > cutoff) return;
      const double w = std::exp(-x);
      sum = sum + basisTensor(e, p) * w;
      wsum += w;
    };
    for (const DesignElement* e : direct) add(*e, e->decay > 0.0 ? e->decay : defaultDecay);
    if (!buckets.empty())
      buckets.within(p, std::sqrt((m + cutoff) / bucketDecay),
                     [&](const DesignElement& e) { add(e, bucketDecay); });
    Tensor t = wsum > 0.0 ? sum * (1.0 / wsum) : Tensor{};
    if (heights) t = t + heightTensor(*heights, p) * options.heightWeight;
    return t;
  };
  const int threads = std::max(1, options.threads);
  const int rows = field.height();
  std::vector<std::thread> pool;
  auto work = [&](int first) {
    for (int j = first; j < rows; j += threads)
      for (int i = 0; i < field.width(); ++i) field.at(i, j) = evaluate(field.vertex(i, j));
  };
  reportProgress(progress, 0.0, "tensor field");
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();
  reportProgress(progress, 0.8, "smoothing");
  field.smooth(options.smoothingIterations);
  if (options.noiseAmplitude > 0.0 && options.noiseWavelength > 0.0)
    for (int j = 0; j < field.height(); ++j)
      for (int i = 0; i < field.width(); ++i) {
        // θ ← θ + N: (a, b) = R (cos 2θ, sin 2θ) turns by 2N.
        const double n =
            2.0 * options.noiseAmplitude *
            perlin(field.vertex(i, j) / options.noiseWavelength, options.noiseOctaves, options.seed);
        Tensor& t = field.at(i, j);
        const double c = std::cos(n), s = std::sin(n);
        t = {t.a * c - t.b * s, t.a * s + t.b * c};
      }
  reportProgress(progress, 1.0, "smoothing");
  return field;
}

}  // namespace urbanvec::streets
