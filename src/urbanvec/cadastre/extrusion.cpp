// LoD1 extrusion, OBJ and CityJSON (spec pueyo-urban-data.md §A.8). See extrusion.hpp.
#include "urbanvec/cadastre/extrusion.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <cstdio>
#include <list>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace urbanvec::cadastre {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;
  bool inside() const { return nesting % 2 == 1; }
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

void markDomains(CDT& cdt, CDT::Face_handle start, int index, std::list<CDT::Edge>& border) {
  if (start->info().nesting != -1) return;
  std::list<CDT::Face_handle> queue{start};
  while (!queue.empty()) {
    CDT::Face_handle fh = queue.front();
    queue.pop_front();
    if (fh->info().nesting != -1) continue;
    fh->info().nesting = index;
    for (int i = 0; i < 3; ++i) {
      const CDT::Edge e(fh, i);
      CDT::Face_handle n = fh->neighbor(i);
      if (n->info().nesting == -1) {
        if (cdt.is_constrained(e))
          border.push_back(e);
        else
          queue.push_back(n);
      }
    }
  }
}

/// Ring points without the closing repeat and without consecutive duplicates.
std::vector<Vec2> openRing(const Ring& r) {
  std::vector<Vec2> out;
  for (const Vec2& p : r)
    if (out.empty() || p != out.back()) out.push_back(p);
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

/// The polygon with its outer ring counter-clockwise and holes clockwise, rings opened.
std::vector<std::vector<Vec2>> orientedRings(const Polygon& p) {
  std::vector<std::vector<Vec2>> rings;
  auto add = [&](const Ring& r, bool ccw) {
    std::vector<Vec2> o = openRing(r);
    if (o.size() < 3) return;
    Ring closed = o;
    closed.push_back(o.front());
    if ((signedArea(closed) > 0) != ccw) std::reverse(o.begin(), o.end());
    rings.push_back(std::move(o));
  };
  add(p.outer, true);
  if (rings.empty()) return rings;
  for (const Ring& h : p.holes) add(h, false);
  return rings;
}

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::vector<std::array<int, 3>> triangulatePolygon(const Polygon& polygon) {
  std::vector<std::array<int, 3>> tris;
  CDT cdt;
  int base = 0;
  std::vector<Vec2> pts;
  for (const Ring& r : {polygon.outer}) (void)r;
  std::vector<std::vector<Vec2>> rings{openRing(polygon.outer)};
  for (const Ring& h : polygon.holes) rings.push_back(openRing(h));
  for (const auto& ring : rings) {
    if (ring.size() < 3) {
      base += static_cast<int>(ring.size());
      continue;
    }
    std::vector<CDT::Vertex_handle> vh;
    for (size_t i = 0; i < ring.size(); ++i) {
      CDT::Vertex_handle v = cdt.insert(K::Point_2(ring[i].x, ring[i].y));
      v->info() = base + static_cast<int>(i);
      vh.push_back(v);
    }
    for (size_t i = 0; i < vh.size(); ++i)
      if (vh[i] != vh[(i + 1) % vh.size()]) cdt.insert_constraint(vh[i], vh[(i + 1) % vh.size()]);
    base += static_cast<int>(ring.size());
  }
  if (cdt.dimension() < 2) return tris;
  for (CDT::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
  std::list<CDT::Edge> border;
  markDomains(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const CDT::Edge e = border.front();
    border.pop_front();
    CDT::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) markDomains(cdt, n, e.first->info().nesting + 1, border);
  }
  for (CDT::Face_handle f : cdt.finite_face_handles())
    if (f->info().inside())
      tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return tris;
}

Mesh extrudeBuildings(const std::vector<BuildingOut>& buildings) {
  Mesh mesh;
  for (size_t b = 0; b < buildings.size(); ++b) {
    const double h = buildings[b].height;
    if (!(h > 0.0)) continue;
    for (const Polygon& part : buildings[b].shape) {
      const auto rings = orientedRings(part);
      if (rings.empty()) continue;
      Polygon oriented;
      std::vector<Vec2> flat;
      for (size_t r = 0; r < rings.size(); ++r) {
        Ring closed = rings[r];
        closed.push_back(rings[r].front());
        (r == 0 ? oriented.outer : oriented.holes.emplace_back()) = closed;
        flat.insert(flat.end(), rings[r].begin(), rings[r].end());
      }
      const auto tris = triangulatePolygon(oriented);
      if (tris.empty()) continue;
      const int bottom = static_cast<int>(mesh.vertices.size());
      const int n = static_cast<int>(flat.size());
      for (const Vec2& p : flat) mesh.vertices.push_back({p.x, p.y, 0.0});
      for (const Vec2& p : flat) mesh.vertices.push_back({p.x, p.y, h});
      auto tri = [&](int a, int c, int d) {
        mesh.triangles.push_back({a, c, d});
        mesh.triangleObject.push_back(static_cast<int>(b));
      };
      for (const auto& t : tris) {
        // The CDT's faces are counter-clockwise: the roof as is, the floor reversed (normal down).
        tri(bottom + n + t[0], bottom + n + t[1], bottom + n + t[2]);
        tri(bottom + t[0], bottom + t[2], bottom + t[1]);
      }
      int start = 0;
      for (const auto& ring : rings) {
        const int m = static_cast<int>(ring.size());
        for (int i = 0; i < m; ++i) {
          const int a = bottom + start + i, c = bottom + start + (i + 1) % m;
          // Outer ring counter-clockwise, holes clockwise: (a, c, c+n) faces away from the solid.
          tri(a, c, c + n);
          tri(a, c + n, a + n);
        }
        start += m;
      }
    }
  }
  return mesh;
}

std::string objText(const Mesh& mesh, const std::array<double, 2>& origin, const std::string& crsName) {
  std::ostringstream out;
  out << "# urbanvec cadastre: LoD1 building prisms\n";
  out << "# origin " << fmt(origin[0]) << " " << fmt(origin[1]) << " (add to x, y; CRS "
      << (crsName.empty() ? "unknown" : crsName) << "), z up in metres\n";
  for (const auto& v : mesh.vertices)
    out << "v " << fmt(v[0] - origin[0]) << " " << fmt(v[1] - origin[1]) << " " << fmt(v[2]) << "\n";
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.vertices[static_cast<size_t>(t[0])];
    const auto& b = mesh.vertices[static_cast<size_t>(t[1])];
    const auto& c = mesh.vertices[static_cast<size_t>(t[2])];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (len > 0) nx /= len, ny /= len, nz /= len;
    out << "vn " << fmt(nx) << " " << fmt(ny) << " " << fmt(nz) << "\n";
  }
  int last = -1;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.triangleObject[i] != last) {
      last = mesh.triangleObject[i];
      out << "o building_" << last << "\n";
    }
    const auto& t = mesh.triangles[i];
    out << "f " << t[0] + 1 << "//" << i + 1 << " " << t[1] + 1 << "//" << i + 1 << " " << t[2] + 1 << "//"
        << i + 1 << "\n";
  }
  return out.str();
}

std::string cityJsonText(const std::vector<BuildingOut>& buildings, int epsg) {
  using nlohmann::json;
  const double scale = 0.001;
  double minX = 1e300, minY = 1e300;
  for (const BuildingOut& b : buildings)
    for (const Polygon& p : b.shape)
      for (const Vec2& q : p.outer) minX = std::min(minX, q.x), minY = std::min(minY, q.y);
  if (minX > 1e299) minX = minY = 0.0;
  const double tx = std::floor(minX), ty = std::floor(minY);
  json vertices = json::array();
  std::map<std::array<long long, 3>, int> index;
  auto vid = [&](double x, double y, double z) {
    const std::array<long long, 3> k{std::llround((x - tx) / scale), std::llround((y - ty) / scale),
                                     std::llround(z / scale)};
    auto [it, fresh] = index.emplace(k, static_cast<int>(vertices.size()));
    if (fresh) vertices.push_back({k[0], k[1], k[2]});
    return it->second;
  };
  json objects = json::object();
  for (size_t b = 0; b < buildings.size(); ++b) {
    const BuildingOut& bo = buildings[b];
    if (!(bo.height > 0.0)) continue;
    json shell = json::array();
    for (const Polygon& part : bo.shape) {
      const auto rings = orientedRings(part);
      if (rings.empty()) continue;
      json floor = json::array(), roof = json::array();
      for (const auto& ring : rings) {
        json f = json::array(), r = json::array();
        for (const Vec2& p : ring) r.push_back(vid(p.x, p.y, bo.height));
        for (auto it = ring.rbegin(); it != ring.rend(); ++it) f.push_back(vid(it->x, it->y, 0.0));
        floor.push_back(f);
        roof.push_back(r);
        for (size_t i = 0; i < ring.size(); ++i) {
          const Vec2& a = ring[i];
          const Vec2& c = ring[(i + 1) % ring.size()];
          shell.push_back(json::array({json::array({vid(a.x, a.y, 0.0), vid(c.x, c.y, 0.0),
                                                    vid(c.x, c.y, bo.height), vid(a.x, a.y, bo.height)})}));
        }
      }
      shell.push_back(floor);
      shell.push_back(roof);
    }
    if (shell.empty()) continue;
    json attributes = {{"floors", bo.floors},
                       {"floors_below", bo.floorsBelow},
                       {"measuredHeight", bo.height},
                       {"block_id", bo.block}};
    if (!bo.label.empty()) attributes["label"] = bo.label;
    // One Solid per element; a multi-part element gives a MultiSurface-like shell set per part.
    json geometry = {{"type", bo.shape.size() == 1 ? "Solid" : "MultiSurface"}, {"lod", "1"}};
    if (bo.shape.size() == 1)
      geometry["boundaries"] = json::array({shell});
    else
      geometry["boundaries"] = shell;
    objects["building_" + std::to_string(b)] = {
        {"type", "Building"}, {"attributes", attributes}, {"geometry", json::array({geometry})}};
  }
  json doc = {{"type", "CityJSON"},
              {"version", "1.1"},
              {"transform", {{"scale", {scale, scale, scale}}, {"translate", {tx, ty, 0.0}}}},
              {"CityObjects", objects},
              {"vertices", vertices}};
  if (epsg > 0)
    doc["metadata"] = {{"referenceSystem", "https://www.opengis.net/def/crs/EPSG/0/" + std::to_string(epsg)}};
  return doc.dump() + "\n";
}

}  // namespace urbanvec::cadastre
