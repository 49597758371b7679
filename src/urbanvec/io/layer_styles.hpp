// QGIS layer styles (QML) stored in a GeoPackage's `layer_styles` table, so layers open in QGIS in
// their usual colours (CONVENTIONS.md "Vector output": residential yellow, commercial red,
// industrial blue, park green, undeveloped white).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace urbanvec::io {

struct StyleCategory {
  std::string value;  ///< field value
  std::string label;
  std::string rgba;  ///< "r,g,b,a"
};

enum class SymbolKind { Fill, Line, Marker };

/// A categorized renderer on `field`, one simple symbol per category.
std::string categorizedQml(const std::string& field, SymbolKind kind,
                           const std::vector<StyleCategory>& categories, double lineWidthMm = 0.26);
struct StyleRange {
  double lower = 0.0;
  double upper = 0.0;
  std::string label;
  std::string rgba;  ///< "r,g,b,a"
};

/// A graduated-colour renderer on `field`, one fill symbol per range.
std::string graduatedQml(const std::string& field, const std::vector<StyleRange>& ranges,
                         double lineWidthMm = 0.1);

/// A single simple symbol.
std::string singleSymbolQml(SymbolKind kind, const std::string& rgba, double lineWidthMm = 0.26,
                            const std::string& outlineRgba = "60,60,60,255");

/// Land-use colours by class name (the land_use field of parcels), including "undeveloped".
std::vector<StyleCategory> landUseCategories();
/// The default style of each standard layer name (parcels, blocks, roads, pavement, water, spines,
/// road_nodes); empty for other names.
std::string defaultStyleFor(const std::string& layerName);
/// Further named styles a user can pick in QGIS's layer properties (name, QML): parcels get
/// "parcels density", a ramp on people per m².
std::vector<std::pair<std::string, std::string>> alternativeStylesFor(const std::string& layerName);

}  // namespace urbanvec::io
