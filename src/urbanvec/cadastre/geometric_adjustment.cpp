// Geometric adjustment of the cleaned linework (issue 17). See geometric_adjustment.hpp.
#include "urbanvec/cadastre/geometric_adjustment.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace urbanvec::cadastre {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Vertices with more neighbours than this get no constraint (a pile of lines on one spot).
constexpr std::size_t kMaxConstrainedDegree = 8;

Vec2 perpendicular(const Vec2& t) {
  return {-t.y, t.x};
}

/// A linearised constraint row over three vertices (u, w, v): g · (P_u, P_w, P_v) = rhs.
struct Row {
  std::array<int, 3> v;
  std::array<Vec2, 3> g;
  double rhs = 0.0;
};

/// The normal equations as a symmetric matrix of 2 x 2 blocks, one block row per vertex, with a
/// pattern fixed once (the diagonal and every pair of vertices sharing a constraint).
class BlockMatrix {
 public:
  BlockMatrix(std::size_t n, const std::vector<std::array<int, 3>>& triples) : start_(n + 1, 0) {
    std::vector<std::vector<int>> cols(n);
    for (std::size_t i = 0; i < n; ++i) cols[i].push_back(static_cast<int>(i));
    for (const auto& t : triples)
      for (int a : t)
        for (int b : t) cols[static_cast<std::size_t>(a)].push_back(b);
    for (std::size_t i = 0; i < n; ++i) {
      auto& c = cols[i];
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end()), c.end());
      start_[i + 1] = start_[i] + c.size();
      col_.insert(col_.end(), c.begin(), c.end());
    }
    val_.assign(col_.size(), {0, 0, 0, 0});
  }
  void clear() { std::fill(val_.begin(), val_.end(), std::array<double, 4>{0, 0, 0, 0}); }
  /// Position of block (i, j) in the pattern.
  std::size_t slot(int i, int j) const {
    const auto b = col_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(i)]);
    const auto e = col_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(i) + 1]);
    return static_cast<std::size_t>(std::lower_bound(b, e, j) - col_.begin());
  }
  /// Adds w a bᵀ to block (i, j).
  void add(std::size_t s, const Vec2& a, const Vec2& b, double w) {
    auto& m = val_[s];
    m[0] += w * a.x * b.x, m[1] += w * a.x * b.y, m[2] += w * a.y * b.x, m[3] += w * a.y * b.y;
  }
  void multiply(const std::vector<Vec2>& x, std::vector<Vec2>& y) const {
    for (std::size_t i = 0; i + 1 < start_.size(); ++i) {
      Vec2 s{0, 0};
      for (std::size_t k = start_[i]; k < start_[i + 1]; ++k) {
        const auto& m = val_[k];
        const Vec2& v = x[static_cast<std::size_t>(col_[k])];
        s.x += m[0] * v.x + m[1] * v.y;
        s.y += m[2] * v.x + m[3] * v.y;
      }
      y[i] = s;
    }
  }
  const std::array<double, 4>& diagonal(std::size_t i) const {
    return val_[slot(static_cast<int>(i), static_cast<int>(i))];
  }

  /// z = (D + L)⁻¹ D (D + U)⁻¹ r, symmetric block Gauss-Seidel (the CG preconditioner); `inverse`
  /// holds the inverted diagonal blocks.
  void symmetricGaussSeidel(const std::vector<std::array<double, 4>>& inverse, const std::vector<Vec2>& r,
                            std::vector<Vec2>& z) const {
    const std::size_t n = r.size();
    auto apply = [](const std::array<double, 4>& m, const Vec2& v) {
      return Vec2{m[0] * v.x + m[1] * v.y, m[2] * v.x + m[3] * v.y};
    };
    // Forward: (D + L) y = r.
    for (std::size_t i = 0; i < n; ++i) {
      Vec2 s = r[i];
      for (std::size_t k = start_[i]; k < start_[i + 1] && static_cast<std::size_t>(col_[k]) < i; ++k)
        s -= apply(val_[k], z[static_cast<std::size_t>(col_[k])]);
      z[i] = apply(inverse[i], s);
    }
    // Backward: (D + U) z = D y.
    for (std::size_t i = n; i-- > 0;) {
      Vec2 s{0, 0};
      for (std::size_t k = start_[i + 1]; k-- > start_[i] && static_cast<std::size_t>(col_[k]) > i;)
        s += apply(val_[k], z[static_cast<std::size_t>(col_[k])]);
      z[i] -= apply(inverse[i], s);
    }
  }

 private:
  std::vector<std::size_t> start_;
  std::vector<int> col_;
  std::vector<std::array<double, 4>> val_;
};

/// Solves A x = b by conjugate gradients preconditioned with symmetric block Gauss-Seidel, to a
/// residual 10⁻³ of |b| (b is the correction's right-hand side: millimetres on decimetre moves).
std::vector<Vec2> solve(const BlockMatrix& a, const std::vector<Vec2>& b) {
  const std::size_t n = b.size();
  std::vector<std::array<double, 4>> inv(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& m = a.diagonal(i);
    const double det = m[0] * m[3] - m[1] * m[2];
    inv[i] = det > 0 ? std::array<double, 4>{m[3] / det, -m[1] / det, -m[2] / det, m[0] / det}
                     : std::array<double, 4>{0, 0, 0, 0};
  }
  auto precondition = [&](const std::vector<Vec2>& r, std::vector<Vec2>& z) {
    a.symmetricGaussSeidel(inv, r, z);
  };
  auto dotAll = [&](const std::vector<Vec2>& x, const std::vector<Vec2>& y) {
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i) s += dot(x[i], y[i]);
    return s;
  };
  std::vector<Vec2> x(n, {0, 0}), r = b, z(n), p(n), q(n);
  precondition(r, z);
  p = z;
  double rz = dotAll(r, z);
  const double stop = 1e-6 * dotAll(b, b);
  for (std::size_t it = 0; it < 4 * n + 10 && dotAll(r, r) > stop; ++it) {
    a.multiply(p, q);
    const double pq = dotAll(p, q);
    if (!(pq > 0)) break;
    const double alpha = rz / pq;
    for (std::size_t i = 0; i < n; ++i) x[i] += p[i] * alpha, r[i] -= q[i] * alpha;
    precondition(r, z);
    const double rz2 = dotAll(r, z);
    const double beta = rz2 / rz;
    rz = rz2;
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + p[i] * beta;
  }
  return x;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

double copyNoise(const Linework& lw) {
  // Spread of the copies across their own segments around their vertex's position (robust: 1.4826
  // times the median, each residual scaled up by sqrt(k / (k - 1)) for the k copies that made the mean).
  std::vector<int> copiesOf(lw.vertices.size(), 0);
  for (const EndCopy& c : lw.copies)
    if (c.vertex != c.other && c.vertex >= 0 && c.other >= 0) ++copiesOf[static_cast<std::size_t>(c.vertex)];
  std::vector<double> across;
  for (const EndCopy& c : lw.copies) {
    if (c.vertex == c.other || c.vertex < 0 || c.other < 0) continue;
    const int k = copiesOf[static_cast<std::size_t>(c.vertex)];
    const Vec2 v = lw.vertices[static_cast<std::size_t>(c.vertex)];
    const Vec2 d = lw.vertices[static_cast<std::size_t>(c.other)] - v;
    const double len = length(d);
    if (k < 2 || !(len > 0)) continue;
    across.push_back(std::abs(dot(perpendicular(d / len), c.p - v)) * std::sqrt(k / (k - 1.0)));
  }
  return 1.4826 * median(std::move(across));
}

std::vector<Vec2> adjustedVertices(const Linework& lw, const AdjustmentOptions& o, AdjustmentStats& stats) {
  stats = {};
  std::vector<Vec2> result = lw.vertices;
  const std::size_t n = lw.vertices.size();
  if (n == 0 || lw.copies.empty()) return result;
  // Local coordinates: the normal equations stay well scaled far from the CRS origin.
  const Vec2 origin = lw.vertices[0];
  std::vector<Vec2> pos(n);
  for (std::size_t i = 0; i < n; ++i) pos[i] = lw.vertices[i] - origin;
  const std::vector<Vec2> start = pos;
  std::vector<EndCopy> copies;
  copies.reserve(lw.copies.size());
  std::vector<int> copiesOf(n, 0);
  for (const EndCopy& c : lw.copies)
    if (c.vertex != c.other && c.vertex >= 0 && c.other >= 0) {
      copies.push_back({c.vertex, c.other, c.p - origin});
      ++copiesOf[static_cast<std::size_t>(c.vertex)];
    }
  auto frame = [&](const EndCopy& c, Vec2& t) {
    const Vec2 d = pos[static_cast<std::size_t>(c.other)] - pos[static_cast<std::size_t>(c.vertex)];
    const double len = length(d);
    if (!(len > 0)) return false;
    t = d / len;
    return true;
  };
  stats.noise = copyNoise(lw);
  // A clean drawing (most copies coincide) keeps its vertices: the fit could only undo the cleaning's
  // repairs (an undershot end moved onto the segment it stops short of).
  if (!(stats.noise > kCleanNoise)) return result;
  // Constraints, chosen once on the initial positions.
  std::vector<std::vector<int>> neighbours(n);
  for (const Segment& s : lw.segments) {
    neighbours[static_cast<std::size_t>(s.a)].push_back(s.b);
    neighbours[static_cast<std::size_t>(s.b)].push_back(s.a);
  }
  std::vector<std::array<int, 3>> straight, square;
  const double cosStraight = -std::cos(o.straightAngle * kPi / 180.0);
  const double reach = o.reach * stats.noise;
  const double sinRight = std::sin(o.rightAngle * kPi / 180.0);
  for (std::size_t w = 0; w < n; ++w) {
    auto& nb = neighbours[w];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    if (nb.size() > kMaxConstrainedDegree) continue;
    for (std::size_t i = 0; i < nb.size(); ++i)
      for (std::size_t j = i + 1; j < nb.size(); ++j) {
        const Vec2 a = pos[static_cast<std::size_t>(nb[i])] - pos[w];
        const Vec2 b = pos[static_cast<std::size_t>(nb[j])] - pos[w];
        const double la = length(a), lb = length(b);
        if (!(la > 0) || !(lb > 0)) continue;
        const double c = dot(a, b) / (la * lb);
        const std::array<int, 3> t{nb[i], static_cast<int>(w), nb[j]};
        // Only where the noise explains the departure from the ideal shape: w within reach of the line
        // of its neighbours, or the shorter arm's end within reach of square.
        const Vec2 d = pos[static_cast<std::size_t>(nb[j])] - pos[static_cast<std::size_t>(nb[i])];
        const double ld = length(d);
        const double offLine =
            ld > 0 ? std::abs(cross(d, pos[w] - pos[static_cast<std::size_t>(nb[i])])) / ld : la;
        const double offSquare = std::abs(c) * std::min(la, lb);
        if (o.straightAngle > 0 && c <= cosStraight && offLine <= reach) straight.push_back(t);
        if (o.rightAngle > 0 && std::abs(c) <= sinRight && offSquare <= reach) square.push_back(t);
      }
  }
  stats.straightConstraints = straight.size();
  stats.rightConstraints = square.size();
  std::vector<std::array<int, 3>> triples = straight;
  triples.insert(triples.end(), square.begin(), square.end());
  BlockMatrix normal(n, triples);
  std::vector<std::size_t> diagonal(n);
  for (std::size_t i = 0; i < n; ++i) diagonal[i] = normal.slot(static_cast<int>(i), static_cast<int>(i));
  std::vector<std::array<std::size_t, 9>> slots(triples.size());
  for (std::size_t k = 0; k < triples.size(); ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        slots[k][static_cast<std::size_t>(3 * i + j)] = normal.slot(triples[k][i], triples[k][j]);

  const double wCopy = 1.0 / (stats.noise * stats.noise);
  const double wStraight = 1.0 / (o.straightSigma * o.straightSigma);
  const double wRight = 1.0 / (o.rightSigma * o.rightSigma);
  std::vector<Vec2> rhs(n), current(n);
  for (int round = 0; round < o.iterations; ++round) {
    normal.clear();
    std::fill(rhs.begin(), rhs.end(), Vec2{0, 0});
    for (const EndCopy& c : copies) {
      Vec2 t;
      const std::size_t v = static_cast<std::size_t>(c.vertex);
      if (!frame(c, t)) continue;
      const Vec2 nn = perpendicular(t);
      const double along = std::abs(dot(t, c.p - pos[v])) / stats.noise;
      const double wa = wCopy * (along > o.huber ? o.huber / along : 1.0);
      normal.add(diagonal[v], nn, nn, wCopy);
      normal.add(diagonal[v], t, t, wa);
      rhs[v] += nn * (wCopy * dot(nn, c.p)) + t * (wa * dot(t, c.p));
    }
    // A vertex without copies (none in a drawing read from a file) stays where it is.
    for (std::size_t v = 0; v < n; ++v)
      if (copiesOf[v] == 0) {
        normal.add(diagonal[v], {1, 0}, {1, 0}, wCopy);
        normal.add(diagonal[v], {0, 1}, {0, 1}, wCopy);
        rhs[v] += pos[v] * wCopy;
      }
    auto addRow = [&](std::size_t k, const Row& row, double w) {
      for (int i = 0; i < 3; ++i) {
        rhs[static_cast<std::size_t>(row.v[static_cast<std::size_t>(i)])] +=
            row.g[static_cast<std::size_t>(i)] * (w * row.rhs);
        for (int j = 0; j < 3; ++j)
          normal.add(slots[k][static_cast<std::size_t>(3 * i + j)], row.g[static_cast<std::size_t>(i)],
                     row.g[static_cast<std::size_t>(j)], w);
      }
    };
    for (std::size_t k = 0; k < triples.size(); ++k) {
      const auto& t = triples[k];
      const Vec2 pu = pos[static_cast<std::size_t>(t[0])], pw = pos[static_cast<std::size_t>(t[1])],
                 pv = pos[static_cast<std::size_t>(t[2])];
      Row row{t, {}, 0.0};
      if (k < straight.size()) {
        // The middle vertex on the line of its neighbours: n · ((1 - λ) P_u + λ P_v - P_w) = 0.
        const Vec2 d = pv - pu;
        const double len = length(d);
        if (!(len > 0)) continue;
        const Vec2 nn = perpendicular(d / len);
        const double lambda = dot(d, pw - pu) / (len * len);
        row.g = {nn * (1.0 - lambda), nn * -1.0, nn * lambda};
        addRow(k, row, wStraight);
      } else {
        // The end of the shorter arm is square: m cos(angle at w) = 0 (m the shorter arm's length,
        // held at its current value), linearised at the current positions.
        const Vec2 a0 = pu - pw, b0 = pv - pw;
        const double la = length(a0), lb = length(b0);
        if (!(la > 0) || !(lb > 0)) continue;
        const double m = std::min(la, lb);
        const Vec2 a = a0 / la, b = b0 / lb;
        const double f = dot(a, b);
        const Vec2 gu = (b - a * f) * (m / la), gv = (a - b * f) * (m / lb);
        row.g = {gu, (gu + gv) * -1.0, gv};
        row.rhs = dot(gu, pu) + dot(row.g[1], pw) + dot(gv, pv) - m * f;
        addRow(k, row, wRight);
      }
    }
    // Solve for the correction: normal (pos + delta) = rhs.
    normal.multiply(pos, current);
    for (std::size_t i = 0; i < n; ++i) current[i] = rhs[i] - current[i];
    const std::vector<Vec2> delta = solve(normal, current);
    for (std::size_t i = 0; i < n; ++i) pos[i] += delta[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double shift = distance(pos[i], start[i]);
    if (!(shift <= o.maxShift)) {
      ++stats.shiftsRefused;
      continue;
    }
    if (shift > 1e-3) ++stats.verticesMoved;
    result[i] = pos[i] + origin;
  }
  return result;
}

}  // namespace urbanvec::cadastre
