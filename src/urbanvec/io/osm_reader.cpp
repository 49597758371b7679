// OSM input through libosmium (docs/shrink.md "Why libosmium"): node ids per way, bounds, relations.
#include "urbanvec/io/osm_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <osmium/handler.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include "urbanvec/core/error.hpp"

namespace urbanvec::io {
namespace {

template <class T>
const T* findById(const std::vector<T>& items, std::int64_t id) {
  auto it =
      std::lower_bound(items.begin(), items.end(), id, [](const T& t, std::int64_t v) { return t.id < v; });
  return it != items.end() && it->id == id ? &*it : nullptr;
}

struct Collector : osmium::handler::Handler {
  OsmData& data;
  explicit Collector(OsmData& d) : data(d) {}
  void node(const osmium::Node& n) {
    if (!n.location().valid()) return;
    data.nodes.push_back({n.id(), n.location().lon(), n.location().lat()});
  }
  void way(const osmium::Way& w) {
    OsmWay way;
    way.id = w.id();
    for (const osmium::NodeRef& r : w.nodes()) way.refs.push_back(r.ref());
    if (const char* h = w.tags()["highway"]) way.highway = h;
    if (const char* name = w.tags()["name"]) way.name = name;
    data.ways.push_back(std::move(way));
  }
  void relation(const osmium::Relation& r) {
    OsmRelation rel;
    rel.id = r.id();
    if (const char* name = r.tags()["name"]) rel.name = name;
    for (const osmium::RelationMember& m : r.members()) {
      const char t = m.type() == osmium::item_type::node  ? 'n'
                     : m.type() == osmium::item_type::way ? 'w'
                                                          : 'r';
      rel.members.push_back({t, m.ref(), m.role()});
    }
    data.relations.push_back(std::move(rel));
  }
};

/// "pbf" or "osm" from the first bytes, for names without a known suffix; empty when neither.
std::string sniffFormat(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.find("OSMHeader") != std::string::npos) return "pbf";
  const size_t first = head.find_first_not_of(" \t\r\n\xef\xbb\xbf");
  if (first != std::string::npos && head[first] == '<') return "osm";
  return {};
}

}  // namespace

const OsmNode* OsmData::node(std::int64_t id) const {
  return findById(nodes, id);
}
const OsmWay* OsmData::way(std::int64_t id) const {
  return findById(ways, id);
}
const OsmRelation* OsmData::relation(std::int64_t id) const {
  return findById(relations, id);
}

OsmData readOsmFile(const std::string& path, const std::string& role) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw invalidInput(role + " '" + path + "' does not exist");
  OsmData data;
  try {
    std::string format;
    const std::string lower = [&] {
      std::string s = path;
      std::transform(s.begin(), s.end(), s.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      return s;
    }();
    auto endsWith = [&](const char* suffix) {
      const std::string s(suffix);
      return lower.size() >= s.size() && lower.compare(lower.size() - s.size(), s.size(), s) == 0;
    };
    if (!(endsWith(".pbf") || endsWith(".osm") || endsWith(".osm.bz2") || endsWith(".osm.gz") ||
          endsWith(".o5m"))) {
      format = sniffFormat(path);
      if (format.empty())
        throw invalidInput(role + " '" + path + "' is not an OpenStreetMap file (.osm XML or .osm.pbf)");
    }
    osmium::io::File file(path, format);
    osmium::io::Reader reader(file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way |
                                        osmium::osm_entity_bits::relation);
    const osmium::io::Header header = reader.header();
    for (const osmium::Box& box : header.boxes()) {
      if (!box.valid()) continue;
      if (!data.hasBounds) {
        data.hasBounds = true;
        data.minLon = box.bottom_left().lon(), data.minLat = box.bottom_left().lat();
        data.maxLon = box.top_right().lon(), data.maxLat = box.top_right().lat();
      } else {
        data.minLon = std::min(data.minLon, box.bottom_left().lon());
        data.minLat = std::min(data.minLat, box.bottom_left().lat());
        data.maxLon = std::max(data.maxLon, box.top_right().lon());
        data.maxLat = std::max(data.maxLat, box.top_right().lat());
      }
    }
    Collector collector(data);
    osmium::apply(reader, collector);
    reader.close();
  } catch (const Error&) {
    throw;
  } catch (const osmium::xml_error& e) {
    throw invalidInput(role + " '" + path + "' is not well-formed OSM XML at line " + std::to_string(e.line) +
                       ", column " + std::to_string(e.column) + ": " + e.error_string);
  } catch (const std::exception& e) {
    throw invalidInput(role + " '" + path + "' cannot be read as OpenStreetMap: " + e.what());
  }
  auto byId = [](const auto& a, const auto& b) { return a.id < b.id; };
  if (!std::is_sorted(data.nodes.begin(), data.nodes.end(), byId))
    std::stable_sort(data.nodes.begin(), data.nodes.end(), byId);
  if (!std::is_sorted(data.ways.begin(), data.ways.end(), byId))
    std::stable_sort(data.ways.begin(), data.ways.end(), byId);
  if (!std::is_sorted(data.relations.begin(), data.relations.end(), byId))
    std::stable_sort(data.relations.begin(), data.relations.end(), byId);
  return data;
}

}  // namespace urbanvec::io
