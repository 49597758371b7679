#include "urbanvec/io/layer_styles.hpp"

#include <sstream>

namespace urbanvec::io {

namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string symbolXml(SymbolKind kind, int index, const std::string& rgba, double widthMm,
                      const std::string& outlineRgba) {
  std::ostringstream s;
  const char* type = kind == SymbolKind::Fill ? "fill" : kind == SymbolKind::Line ? "line" : "marker";
  s << "      <symbol type=\"" << type << "\" name=\"" << index
    << "\" alpha=\"1\" clip_to_extent=\"1\" force_rhr=\"0\">\n";
  if (kind == SymbolKind::Fill) {
    s << "        <layer class=\"SimpleFill\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
      << "          <prop k=\"color\" v=\"" << rgba << "\"/>\n"
      << "          <prop k=\"style\" v=\"solid\"/>\n"
      << "          <prop k=\"outline_color\" v=\"" << outlineRgba << "\"/>\n"
      << "          <prop k=\"outline_style\" v=\"solid\"/>\n"
      << "          <prop k=\"outline_width\" v=\"" << widthMm << "\"/>\n"
      << "          <prop k=\"outline_width_unit\" v=\"MM\"/>\n";
  } else if (kind == SymbolKind::Line) {
    s << "        <layer class=\"SimpleLine\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
      << "          <prop k=\"line_color\" v=\"" << rgba << "\"/>\n"
      << "          <prop k=\"line_style\" v=\"solid\"/>\n"
      << "          <prop k=\"line_width\" v=\"" << widthMm << "\"/>\n"
      << "          <prop k=\"line_width_unit\" v=\"MM\"/>\n"
      << "          <prop k=\"capstyle\" v=\"round\"/>\n"
      << "          <prop k=\"joinstyle\" v=\"round\"/>\n";
  } else {
    s << "        <layer class=\"SimpleMarker\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
      << "          <prop k=\"color\" v=\"" << rgba << "\"/>\n"
      << "          <prop k=\"name\" v=\"circle\"/>\n"
      << "          <prop k=\"size\" v=\"" << widthMm << "\"/>\n"
      << "          <prop k=\"size_unit\" v=\"MM\"/>\n"
      << "          <prop k=\"outline_color\" v=\"" << outlineRgba << "\"/>\n";
  }
  s << "        </layer>\n      </symbol>\n";
  return s.str();
}

const char* kHeader =
    "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
    "<qgis version=\"3.22.0\" styleCategories=\"Symbology\">\n";

}  // namespace

std::string categorizedQml(const std::string& field, SymbolKind kind,
                           const std::vector<StyleCategory>& categories, double lineWidthMm) {
  std::ostringstream s;
  s << kHeader << "  <renderer-v2 type=\"categorizedSymbol\" attr=\"" << escape(field)
    << "\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n    <categories>\n";
  for (size_t i = 0; i < categories.size(); ++i)
    s << "      <category render=\"true\" symbol=\"" << i << "\" value=\"" << escape(categories[i].value)
      << "\" label=\"" << escape(categories[i].label) << "\"/>\n";
  s << "    </categories>\n    <symbols>\n";
  for (size_t i = 0; i < categories.size(); ++i)
    s << symbolXml(kind, static_cast<int>(i), categories[i].rgba, lineWidthMm, "80,80,80,255");
  s << "    </symbols>\n  </renderer-v2>\n</qgis>\n";
  return s.str();
}

std::string singleSymbolQml(SymbolKind kind, const std::string& rgba, double lineWidthMm,
                            const std::string& outlineRgba) {
  std::ostringstream s;
  s << kHeader
    << "  <renderer-v2 type=\"singleSymbol\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n"
    << "    <symbols>\n"
    << symbolXml(kind, 0, rgba, lineWidthMm, outlineRgba) << "    </symbols>\n  </renderer-v2>\n</qgis>\n";
  return s.str();
}

std::vector<StyleCategory> landUseCategories() {
  return {{"residential", "Residential", "246,224,94,255"},  {"commercial", "Commercial", "224,64,64,255"},
          {"industrial", "Industrial", "70,110,220,255"},    {"park", "Park", "90,180,90,255"},
          {"undeveloped", "Undeveloped", "255,255,255,255"}, {"unused", "Unused", "255,255,255,255"},
          {"reserved", "Reserved", "170,170,170,255"},       {"water", "Water", "120,180,230,255"}};
}

std::string graduatedQml(const std::string& field, const std::vector<StyleRange>& ranges,
                         double lineWidthMm) {
  std::ostringstream s;
  s << kHeader << "  <renderer-v2 type=\"graduatedSymbol\" attr=\"" << escape(field)
    << "\" graduatedMethod=\"GraduatedColor\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n"
    << "    <ranges>\n";
  for (size_t i = 0; i < ranges.size(); ++i)
    s << "      <range render=\"true\" symbol=\"" << i << "\" lower=\"" << ranges[i].lower << "\" upper=\""
      << ranges[i].upper << "\" label=\"" << escape(ranges[i].label) << "\"/>\n";
  s << "    </ranges>\n    <symbols>\n";
  for (size_t i = 0; i < ranges.size(); ++i)
    s << symbolXml(SymbolKind::Fill, static_cast<int>(i), ranges[i].rgba, lineWidthMm, "120,120,120,255");
  s << "    </symbols>\n  </renderer-v2>\n</qgis>\n";
  return s.str();
}

std::vector<std::pair<std::string, std::string>> alternativeStylesFor(const std::string& layerName) {
  if (layerName != "parcels") return {};
  // People per m² (10,000 × people per hectare); a light-to-dark yellow-orange-red ramp.
  const std::vector<StyleRange> density = {{0.0, 0.0, "0 (undeveloped, non-residential)", "255,255,255,255"},
                                           {0.0, 0.005, "up to 50 /ha", "255,255,178,255"},
                                           {0.005, 0.01, "50 - 100 /ha", "254,217,118,255"},
                                           {0.01, 0.02, "100 - 200 /ha", "254,178,76,255"},
                                           {0.02, 0.04, "200 - 400 /ha", "253,141,60,255"},
                                           {0.04, 0.08, "400 - 800 /ha", "240,59,32,255"},
                                           {0.08, 1e9, "over 800 /ha", "189,0,38,255"}};
  return {{"parcels density", graduatedQml("density", density, 0.1)}};
}

std::string defaultStyleFor(const std::string& layerName) {
  if (layerName == "parcels") return categorizedQml("land_use", SymbolKind::Fill, landUseCategories(), 0.1);
  if (layerName == "blocks")
    return categorizedQml("kind", SymbolKind::Fill,
                          {{"internal", "Internal block", "235,230,220,255"},
                           {"external", "External block", "210,205,195,255"}},
                          0.2);
  if (layerName == "roads")
    return categorizedQml("road_class", SymbolKind::Line,
                          {{"primary", "Primary road", "200,90,40,255"},
                           {"secondary", "Secondary road", "90,90,90,255"},
                           {"perimeter", "Perimeter", "150,150,150,255"}},
                          0.5);
  if (layerName == "pavement")
    return singleSymbolQml(SymbolKind::Fill, "190,190,190,255", 0.05, "150,150,150,255");
  if (layerName == "water")
    return singleSymbolQml(SymbolKind::Fill, "120,180,230,255", 0.1, "80,140,200,255");
  if (layerName == "spines") return singleSymbolQml(SymbolKind::Line, "150,60,150,255", 0.3);
  if (layerName == "road_nodes") return singleSymbolQml(SymbolKind::Marker, "40,40,40,255", 1.2);
  return {};
}

}  // namespace urbanvec::io
