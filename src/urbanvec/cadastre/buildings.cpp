// Localisation of faces in blocks and building elements (spec pueyo-urban-data.md §A.7, §A.8 labels).
#include "urbanvec/cadastre/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanvec/cadastre/circuits.hpp"
#include "urbanvec/cadastre/linework.hpp"

namespace urbanvec::cadastre {
BlockLocator::BlockLocator(std::vector<Polygon> areas, std::vector<int> owners)
    : areas_(std::move(areas)), owners_(std::move(owners)) {
  double total = 0;
  for (const Polygon& p : areas_) total += std::abs(signedArea(p.outer));
  if (!areas_.empty()) cell_ = std::max(1.0, std::sqrt(total / static_cast<double>(areas_.size())));
  for (size_t i = 0; i < areas_.size(); ++i) {
    const Box b = boxOf(areas_[i].outer);
    for (auto x = static_cast<std::int64_t>(std::floor(b.x0 / cell_));
         x <= static_cast<std::int64_t>(std::floor(b.x1 / cell_)); ++x)
      for (auto y = static_cast<std::int64_t>(std::floor(b.y0 / cell_));
           y <= static_cast<std::int64_t>(std::floor(b.y1 / cell_)); ++y)
        index_.emplace_back(key(x, y), static_cast<int>(i));
  }
  std::sort(index_.begin(), index_.end());
}

int BlockLocator::locate(const Vec2& p) const {
  const std::int64_t k = key(static_cast<std::int64_t>(std::floor(p.x / cell_)),
                             static_cast<std::int64_t>(std::floor(p.y / cell_)));
  auto it = std::lower_bound(index_.begin(), index_.end(), std::make_pair(k, -1));
  for (; it != index_.end() && it->first == k; ++it)
    if (pointInPolygon(p, areas_[static_cast<size_t>(it->second)]))
      return owners_[static_cast<size_t>(it->second)];
  return -1;
}

std::vector<Localised> localise(const std::vector<Polygon>& faces, const BlockLocator& blocks, double minArea,
                                std::size_t& outside, std::vector<Localised>* outsideFaces) {
  std::vector<Localised> out;
  for (const Polygon& f : faces) {
    MultiPolygon parts = validParts(f, minArea);
    if (parts.empty()) continue;
    // The interior point of the largest part locates the face.
    size_t largest = 0;
    for (size_t i = 1; i < parts.size(); ++i)
      if (area(parts[i]) > area(parts[largest])) largest = i;
    const Vec2 inside = interiorPoint(parts[largest]);
    const int block = blocks.locate(inside);
    if (block < 0) {
      ++outside;
      if (outsideFaces) outsideFaces->push_back({std::move(parts), -1, inside});
      continue;
    }
    out.push_back({std::move(parts), block, inside});
  }
  return out;
}

std::vector<int> assignLabels(const std::vector<Localised>& polys, const std::vector<Vec2>& labels,
                              double searchDistance, std::size_t& snapped, std::size_t& unmatched,
                              std::size_t& crowded) {
  CellGrid grid(8.0);
  for (size_t i = 0; i < polys.size(); ++i) {
    Box b;
    for (const Polygon& p : polys[i].shape)
      for (const Vec2& q : p.outer) b.add(q);
    grid.insertBox(b, static_cast<int>(i));
  }
  std::vector<std::vector<int>> held(polys.size());
  for (size_t l = 0; l < labels.size(); ++l) {
    const Vec2 p = labels[l];
    int inside = -1;
    grid.query(p.x, p.y, p.x, p.y, [&](int i) {
      if (inside >= 0 && inside <= i) return;
      for (const Polygon& part : polys[static_cast<size_t>(i)].shape)
        if (pointInPolygon(p, part)) inside = i;
    });
    if (inside < 0) {
      double best = searchDistance;
      grid.query(p.x - searchDistance, p.y - searchDistance, p.x + searchDistance, p.y + searchDistance,
                 [&](int i) {
                   for (const Polygon& part : polys[static_cast<size_t>(i)].shape) {
                     const double d = distanceToBoundary(p, part);
                     if (d < best || (d == best && inside >= 0 && i < inside)) best = d, inside = i;
                   }
                 });
      if (inside < 0) {
        ++unmatched;
        continue;
      }
      ++snapped;
    }
    held[static_cast<size_t>(inside)].push_back(static_cast<int>(l));
  }
  std::vector<int> chosen(polys.size(), -1);
  for (size_t i = 0; i < polys.size(); ++i) {
    if (held[i].empty()) continue;
    if (held[i].size() > 1) ++crowded;
    double best = std::numeric_limits<double>::infinity();
    for (int l : held[i]) {
      const double d = distance(labels[static_cast<size_t>(l)], polys[i].inside);
      if (d < best) best = d, chosen[i] = l;
    }
  }
  return chosen;
}

}  // namespace urbanvec::cadastre
