// `urbanvec cadastre`: messy CAD/DXF linework -> blocks, sub-blocks, courtyards, parcels and building
// elements with heights, OBJ and CityJSON LoD1 (issue 17; spec pueyo-urban-data.md part A).
#include <ogr_spatialref.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "urbanvec/app/command.hpp"
#include "urbanvec/cadastre/cadastre.hpp"
#include "urbanvec/cadastre/extrusion.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/layer_styles.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

const char* const kLayers[] = {"blocks",  "sub_blocks", "courtyards",
                               "parcels", "buildings",  "cadastre_report"};

app::CommandSpec spec() {
  const cadastre::CadastreOptions d;
  app::CommandSpec s;
  s.name = "cadastre";
  s.summary =
      "Structures messy cadastral CAD linework (DXF) into blocks, parcels and buildings with heights, and a "
      "3D LoD1 model.";
  s.description =
      "Reads the named layers of a CAD drawing (DXF: its 'Layer' field; or GeoPackage/Shapefile layers of "
      "lines or "
      "polygons) and rebuilds the structure the drawing only shows (Pueyo's cadastre pipeline): vertices "
      "closer "
      "than the Collapsing Threshold are collapsed with the anti-drift rule, repeated and overlapping "
      "segments "
      "are removed, ends that stop short are joined within the Block Threshold, fringe paths are cut, and "
      "the "
      "minimal circuits give blocks (outline first), sub-blocks, courtyards, parcels (block + lot lines) and "
      "building elements (block + lot + building lines). Number-of-floors labels (Roman numerals such as III "
      "or "
      "-I+III, or Arabic numbers) give each element its floors and height 3 + 2.5 (floors - 1) m; elements "
      "without a label are courtyards with height 0. Writes the layers blocks, sub_blocks, courtyards, "
      "parcels, buildings and cadastre_report (the thesis's Table 1), and optionally a Wavefront OBJ and a "
      "CityJSON 1.1 LoD1 model. See docs/cadastre.md.";
  s.group = "Cadastre";
  s.positionals = {
      {"input", "CAD drawing (DXF) or vector dataset with the linework layers.", Role::InputVector},
      {"output", "Vector file to create (GeoPackage by default).", Role::OutputVector}};
  s.outputLayers = {std::begin(kLayers), std::end(kLayers)};
  auto& o = s.options;
  o.push_back(
      option("-block-layer", ValueType::String, "<name>", "Layer drawing the blocks (repeatable).").many());
  o.push_back(
      option("-lot-layer", ValueType::String, "<name>", "Layer drawing the lots / parcels (repeatable).")
          .many());
  o.push_back(
      option("-building-layer", ValueType::String, "<name>", "Layer drawing the buildings (repeatable).")
          .many());
  o.push_back(option("-label-layer", ValueType::String, "<name>", "Layer of number-of-floors text labels."));
  o.push_back(
      option("-label-field", ValueType::String, "<field>", "Field holding the label text (DXF: Text).")
          .byDefault("Text")
          .isAdvanced());
  o.push_back(option("-a_srs", ValueType::String, "<crs>",
                     "CRS of the drawing when it has none (a DXF never has one).")
                  .withRole(Role::Crs));
  o.push_back(option("-collapse", ValueType::Real, "<metres>",
                     "Collapsing Threshold: vertices and parallel segments closer than this are one (the "
                     "thesis used 1 m).")
                  .byDefault(app::numberText(d.collapsingThreshold))
                  .withUnit("m"));
  o.push_back(option("-block-threshold", ValueType::Real, "<metres>",
                     "Block Threshold, slightly smaller than the narrowest street (the thesis used 3 m).")
                  .byDefault(app::numberText(d.blockThreshold))
                  .withUnit("m"));
  o.push_back(option("-thesis-thresholds", ValueType::Flag, "",
                     "Use the thesis's thresholds (Collapsing 1 m, Block 3 m)."));
  o.push_back(
      option("-thesis-revert", ValueType::Flag, "",
             "On a failed collapse, revert it as the thesis does (split off the farthest vertex) instead of "
             "keeping the new vertex apart; implies -drawing-order.")
          .isAdvanced());
  o.push_back(option("-collapse-all", ValueType::Flag, "",
                     "Collapse every vertex as the thesis does, also two where lines already meet exactly "
                     "(default: only free ends collapse).")
                  .isAdvanced());
  o.push_back(option("-drawing-order", ValueType::Flag, "",
                     "Collapse vertices in drawing order as the thesis does (default: closest pairs first, "
                     "whatever the order of the drawing).")
                  .isAdvanced());
  o.push_back(
      option("-straighten", ValueType::Real, "<share>",
             "Drop degree-2 vertices closer than this share of -collapse to the line of their neighbours "
             "(split and jittered straight lines); 0 keeps every vertex.")
          .byDefault(app::numberText(d.straightenShare))
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-merge-split", ValueType::Real, "<noise units>",
                     "Merge two vertices closer than this many times the drawing's estimated noise when no "
                     "drawn segment joins them, no face but a sliver collapses and no crossing is created "
                     "(copies of one drawn vertex split over several); clean drawings are left alone; 0 "
                     "disables.")
                  .byDefault(app::numberText(d.mergeSplit))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-snap-joined", ValueType::Flag, "",
                     "Segment cleaning moves every vertex within -collapse of a segment onto it, also "
                     "corners of lot and building lines where two or more segments per layer already meet "
                     "(default: only free ends and block-layer vertices move).")
                  .isAdvanced());
  o.push_back(option("-drop-labelled-thin", ValueType::Flag, "",
                     "Drop every building face thinner than the sliver width (" +
                         app::numberText(d.sliverWidth) +
                         " m mean width), also one holding a number-of-floors label on a drawing whose "
                         "copies coincide (default: kept there as a building part).")
                  .isAdvanced());
  o.push_back(option("-no-adjust", ValueType::Flag, "",
                     "Place each vertex at the mean of its drawn copies, without the least-squares "
                     "adjustment (straight lines, right angles, ends off along their line).")
                  .isAdvanced());
  o.push_back(option("-straight-angle", ValueType::Real, "<degrees>",
                     "Adjustment: vertices whose two segments are within this of 180 degrees are kept on "
                     "the line of their neighbours; 0 disables.")
                  .byDefault(app::numberText(d.straightAngle))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-right-angle", ValueType::Real, "<degrees>",
                     "Adjustment: angles within this of 90 degrees are held square; other angles are left "
                     "alone; 0 disables.")
                  .byDefault(app::numberText(d.rightAngle))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-min-area", ValueType::Real, "<m2>", "Circuits smaller than this are slivers and dropped.")
          .byDefault(app::numberText(d.minFaceArea))
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-label-distance", ValueType::Real, "<metres>",
                     "A label outside every element goes to the nearest one within this distance.")
                  .byDefault(app::numberText(d.labelSearchDistance))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-ground-floor", ValueType::Real, "<metres>", "Height of the ground floor.")
                  .byDefault(app::numberText(d.groundFloorHeight))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-upper-floor", ValueType::Real, "<metres>", "Height of each upper floor.")
                  .byDefault(app::numberText(d.upperFloorHeight))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-height-offset", ValueType::Real, "<metres>",
             "Largest seeded random offset added to each height (the thesis's 'small random offset'); "
             "0 keeps heights exact.")
          .byDefault("0")
          .atLeast(0));
  o.push_back(
      option("-seed", ValueType::Integer, "<n>", "Seed of the height offsets.").byDefault("0").atLeast(0));
  o.push_back(option("-threads", ValueType::Integer, "<n>",
                     "Worker threads (0 = all cores): the parcel and building graphs are built side by side; "
                     "the output does not depend on it.")
                  .byDefault("0")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-obj", ValueType::String, "<file.obj>", "Also write the LoD1 prisms as Wavefront OBJ.")
                  .withRole(Role::OutputFile));
  o.push_back(
      option("-cityjson", ValueType::String, "<file.city.json>", "Also write a CityJSON 1.1 LoD1 model.")
          .withRole(Role::OutputFile));
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  s.examples = {
      "urbanvec cadastre -block-layer BLOCKS -lot-layer PARCELS -building-layer BUILDINGS -label-layer "
      "FLOORS "
      "-a_srs EPSG:32628 drawing.dxf cadastre.gpkg -obj city.obj -cityjson city.city.json"};
  return s;
}

/// A DXF must end with the EOF group; a binary DXF must be one GDAL reads.
void checkDxf(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.size() < 4 || lower.substr(lower.size() - 4) != ".dxf") return;
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // the reader names a missing file
  std::string head(22, '\0');
  in.read(&head[0], 22);
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.rfind("AutoCAD Binary DXF", 0) == 0) return;  // GDAL's DXF driver reads binary DXF
  in.clear();
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  std::string end(static_cast<size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(&end[0], tail);
  while (!end.empty() && std::isspace(static_cast<unsigned char>(end.back()))) end.pop_back();
  if (end.size() < 3 || end.substr(end.size() - 3) != "EOF")
    throw invalidInput("input '" + path +
                       "' is not a complete DXF file (it does not end with the EOF group): truncated?");
}

void addGeometry(const Geometry& g, std::uint8_t layer, std::vector<cadastre::CadLine>& out) {
  auto addLine = [&](const LineString& l) {
    if (l.size() >= 2) out.push_back({l, layer});
  };
  auto addPolygon = [&](const Polygon& p) {
    addLine(p.outer);
    for (const Ring& h : p.holes) addLine(h);
  };
  if (const auto* l = std::get_if<LineString>(&g)) addLine(*l);
  if (const auto* ml = std::get_if<MultiLineString>(&g))
    for (const LineString& l : *ml) addLine(l);
  if (const auto* p = std::get_if<Polygon>(&g)) addPolygon(*p);
  if (const auto* mp = std::get_if<MultiPolygon>(&g))
    for (const Polygon& p : *mp) addPolygon(p);
}

std::string joinNames(const std::set<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

Layer polygonLayer(const std::string& name, std::vector<FieldDef> fields) {
  Layer l;
  l.name = name;
  l.geometryType = GeometryType::MultiPolygon;
  l.fields = std::move(fields);
  return l;
}

int epsgOf(const std::string& wkt) {
  if (wkt.empty()) return 0;
  OGRSpatialReference srs;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return 0;
  srs.AutoIdentifyEPSG();
  const char* code = srs.GetAuthorityCode(nullptr);
  const char* auth = srs.GetAuthorityName(nullptr);
  return code && auth && std::string(auth) == "EPSG" ? std::atoi(code) : 0;
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string input = args.positionals()[0];
  const std::string outputPath = args.positionals()[1];
  cadastre::CadastreOptions options;
  if (args.flag("-thesis-thresholds")) {
    options.collapsingThreshold = cadastre::CadastreOptions::thesisCollapsingThreshold;
    options.blockThreshold = cadastre::CadastreOptions::thesisBlockThreshold;
  }
  if (args.given("-collapse")) options.collapsingThreshold = args.real("-collapse");
  if (args.given("-block-threshold")) options.blockThreshold = args.real("-block-threshold");
  if (!(options.collapsingThreshold > 0.0))
    throw invalidOption("-collapse " + args.str("-collapse") + " must be > 0");
  if (!(options.blockThreshold > 0.0))
    throw invalidOption("-block-threshold " + args.str("-block-threshold") + " must be > 0");
  if (options.collapsingThreshold > options.blockThreshold)
    throw invalidOption("-collapse " + app::numberText(options.collapsingThreshold) +
                        " is larger than -block-threshold " + app::numberText(options.blockThreshold) +
                        "; the Collapsing Threshold must not exceed the Block Threshold");
  options.thesisRevert = args.flag("-thesis-revert");
  options.freeEndsOnly = !args.flag("-collapse-all");
  options.closestFirst = !args.flag("-drawing-order") && !options.thesisRevert;
  options.straightenShare = args.real("-straighten");
  options.mergeSplit = args.real("-merge-split");
  options.adjust = !args.flag("-no-adjust");
  options.snapJoined = args.flag("-snap-joined");
  options.keepLabelledThin = !args.flag("-drop-labelled-thin");
  options.straightAngle = args.real("-straight-angle");
  options.rightAngle = args.real("-right-angle");
  options.minFaceArea = args.real("-min-area");
  options.labelSearchDistance = args.real("-label-distance");
  options.groundFloorHeight = args.real("-ground-floor");
  options.upperFloorHeight = args.real("-upper-floor");
  options.heightOffset = args.real("-height-offset");
  options.seed = static_cast<std::uint64_t>(args.integer("-seed"));
  options.threads = static_cast<int>(args.integer("-threads"));
  const std::vector<std::string> blockNames = args.values("-block-layer");
  if (blockNames.empty())
    throw invalidOption("-block-layer is required: name the layer(s) drawing the blocks");
  const std::vector<std::string> lotNames = args.values("-lot-layer");
  const std::vector<std::string> buildingNames = args.values("-building-layer");
  const std::string labelName = args.given("-label-layer") ? args.str("-label-layer") : std::string();
  const std::string labelField = args.str("-label-field");

  // Outputs are taken before any work (name checks, lock, -of/-lco).
  io::VectorWriteOptions write;
  if (args.has("-of")) write.format = args.str("-of");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  write.defaultStyles = false;
  std::vector<io::StyleRange> heights = {
      {0, 0.01, "0 m (courtyard)", "240,240,240,255"}, {0.01, 3.5, "ground floor", "254,229,217,255"},
      {3.5, 6, "2 floors", "252,174,145,255"},         {6, 8.5, "3 floors", "251,106,74,255"},
      {8.5, 11, "4 floors", "222,45,38,255"},          {11, 1e9, "5+ floors", "165,15,21,255"}};
  write.layerStylesQml["buildings"] = io::graduatedQml("height", heights, 0.1);
  write.layerStylesQml["blocks"] = io::singleSymbolQml(io::SymbolKind::Fill, "225,220,205,255", 0.4);
  write.layerStylesQml["sub_blocks"] =
      io::singleSymbolQml(io::SymbolKind::Fill, "0,0,0,0", 0.2, "120,120,120,255");
  write.layerStylesQml["courtyards"] = io::singleSymbolQml(io::SymbolKind::Fill, "170,210,150,255", 0.1);
  write.layerStylesQml["parcels"] =
      io::singleSymbolQml(io::SymbolKind::Fill, "0,0,0,0", 0.15, "200,60,60,255");
  io::VectorOutput output(outputPath, write, {std::begin(kLayers), std::end(kLayers)},
                          io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  std::optional<io::AtomicOutput> objOut, jsonOut;
  if (args.given("-obj"))
    objOut.emplace(args.str("-obj"), io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});
  if (args.given("-cityjson"))
    jsonOut.emplace(args.str("-cityjson"), io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});

  checkDxf(input);
  std::string crs;
  if (args.given("-a_srs")) crs = io::crsToWkt(args.str("-a_srs"), "-a_srs");
  reportProgress(ctx.progress, 0.0, "reading");
  // Each wanted layer name: a dataset layer of that name, or the features whose 'Layer' field has it.
  std::map<std::string, std::uint8_t> role;
  for (const auto& n : blockNames) role[n] |= cadastre::kBlockLayer;
  for (const auto& n : lotNames) role[n] |= cadastre::kLotLayer;
  for (const auto& n : buildingNames) role[n] |= cadastre::kBuildingLayer;
  std::vector<cadastre::CadLine> lines;
  std::vector<cadastre::CadLabel> labels;
  std::map<std::string, std::size_t> found;  // features per wanted name
  std::set<std::string> available;
  std::size_t labelsWithoutText = 0;
  std::string fileCrs;
  // Lines are gathered per role in the order block, lot, building (§A.4: layer by layer).
  std::vector<std::vector<cadastre::CadLine>> perRole(3);
  auto take = [&](const std::string& name, const Feature& f, const Layer& layer) {
    if (name == labelName && !labelName.empty()) {
      const Vec2* p = std::get_if<Vec2>(&f.geometry);
      const int fi = layer.fieldIndex(labelField);
      ++found[name];
      if (!p) return;
      const std::string* text =
          fi >= 0 ? std::get_if<std::string>(&f.values[static_cast<size_t>(fi)]) : nullptr;
      if (!text) {
        if (fi >= 0 && std::holds_alternative<std::int64_t>(f.values[static_cast<size_t>(fi)]))
          labels.push_back({*p, std::to_string(std::get<std::int64_t>(f.values[static_cast<size_t>(fi)]))});
        else
          ++labelsWithoutText;
        return;
      }
      labels.push_back({*p, *text});
    }
    auto it = role.find(name);
    if (it == role.end()) return;
    ++found[name];
    const int slot = (it->second & cadastre::kBlockLayer) ? 0 : (it->second & cadastre::kLotLayer) ? 1 : 2;
    std::vector<cadastre::CadLine> got;
    addGeometry(f.geometry, it->second, got);
    for (auto& g : got) perRole[static_cast<size_t>(slot)].push_back(std::move(g));
  };
  for (const std::string& dsLayer : io::listVectorLayers(input, "input")) {
    available.insert(dsLayer);
    std::optional<io::LayerRead> read = io::readVectorLayer(input, dsLayer, "input");
    if (!read) continue;
    if (fileCrs.empty()) fileCrs = read->crsWkt;
    const Layer& layer = read->layer;
    const int layerField = layer.fieldIndex("Layer");
    const bool whole = role.count(dsLayer) || dsLayer == labelName;
    for (const Feature& f : layer.features) {
      if (whole) {
        take(dsLayer, f, layer);
      } else if (layerField >= 0) {
        const auto* v = std::get_if<std::string>(&f.values[static_cast<size_t>(layerField)]);
        if (!v) continue;
        available.insert(*v);
        take(*v, f, layer);
      }
    }
  }
  std::vector<std::string> wanted(blockNames);
  wanted.insert(wanted.end(), lotNames.begin(), lotNames.end());
  wanted.insert(wanted.end(), buildingNames.begin(), buildingNames.end());
  if (!labelName.empty()) wanted.push_back(labelName);
  std::vector<std::string> missing;
  for (const std::string& n : wanted)
    if (!available.count(n)) missing.push_back(n);
  if (!missing.empty()) {
    std::string m;
    for (const auto& n : missing) m += (m.empty() ? "'" : ", '") + n + "'";
    throw invalidInput("input '" + input + "' has no layer " + m +
                       "; its layers are: " + joinNames(available));
  }
  for (auto& v : perRole)
    for (auto& l : v) lines.push_back(std::move(l));
  std::size_t blockLines = perRole[0].size();
  if (blockLines == 0)
    throw invalidInput("the block layer" + std::string(blockNames.size() > 1 ? "s" : "") + " of '" + input +
                       "' hold no lines or polygons");
  for (const std::string& n : wanted)
    if (!found[n]) ctx.warn("layer '" + n + "' of '" + input + "' is empty");
  if (labelsWithoutText)
    ctx.warn(std::to_string(labelsWithoutText) + " label(s) have no '" + labelField + "' text");

  if (crs.empty()) crs = fileCrs;
  if (!crs.empty() && io::crsShortName(crs).rfind("Undefined", 0) == 0) crs.clear();
  if (!crs.empty() && io::isGeographic(crs))
    throw invalidInput("input '" + input + "' is in a geographic CRS (" + io::crsShortName(crs) +
                       "); thresholds are in metres: reproject it (ogr2ogr -t_srs) to a projected CRS");
  if (crs.empty())
    ctx.warn("input '" + input +
             "' has no CRS (give -a_srs): outputs carry none, thresholds are in its units");

  cadastre::CadastreResult r =
      cadastre::structureCadastre(lines, labels, options, subProgress(ctx.progress, 0.05, 0.85));
  const cadastre::CadastreReport& rep = r.report;
  if (rep.labelsNotNumbers)
    ctx.warn(std::to_string(rep.labelsNotNumbers) + " label(s) are not numbers of floors and were ignored");

  // Layers.
  Layer blocks = polygonLayer("blocks", {{"block_id", FieldType::Integer},
                                         {"pre_block", FieldType::Integer},
                                         {"sub_blocks", FieldType::Integer},
                                         {"courtyards", FieldType::Integer},
                                         {"area", FieldType::Real}});
  for (size_t i = 0; i < r.blocks.size(); ++i) {
    const auto& b = r.blocks[i];
    blocks.features.push_back({b.shape,
                               {std::int64_t(i), std::int64_t(b.preBlock), std::int64_t(b.subBlocks),
                                std::int64_t(b.courtyards), area(b.shape)}});
  }
  auto areaLayer = [&](const std::string& name, const std::vector<cadastre::AreaOut>& items,
                       const char* idName) {
    Layer l = polygonLayer(
        name, {{idName, FieldType::Integer}, {"block_id", FieldType::Integer}, {"area", FieldType::Real}});
    for (size_t i = 0; i < items.size(); ++i)
      l.features.push_back(
          {items[i].shape, {std::int64_t(i), std::int64_t(items[i].block), area(items[i].shape)}});
    return l;
  };
  Layer subBlocks = areaLayer("sub_blocks", r.subBlocks, "sub_block_id");
  Layer courtyards = areaLayer("courtyards", r.courtyards, "courtyard_id");
  Layer parcels = areaLayer("parcels", r.parcels, "parcel_id");
  Layer buildings = polygonLayer("buildings", {{"building_id", FieldType::Integer},
                                               {"block_id", FieldType::Integer},
                                               {"floors", FieldType::Integer},
                                               {"floors_below", FieldType::Integer},
                                               {"height", FieldType::Real},
                                               {"label", FieldType::String},
                                               {"area", FieldType::Real}});
  for (size_t i = 0; i < r.buildings.size(); ++i) {
    const auto& b = r.buildings[i];
    FieldValue label, block;
    if (!b.label.empty()) label = b.label;
    if (b.block >= 0) block = std::int64_t(b.block);
    buildings.features.push_back({b.shape,
                                  {std::int64_t(i), block, std::int64_t(b.floors),
                                   std::int64_t(b.floorsBelow), b.height, label, area(b.shape)}});
  }
  Layer report;
  report.name = "cadastre_report";
  report.geometryType = GeometryType::None;
  report.fields = {{"statistic", FieldType::String}, {"value", FieldType::Real}, {"note", FieldType::String}};
  auto row = [&](const std::string& name, double v, const std::string& note) {
    report.features.push_back({std::monostate{}, {name, v, note}});
  };
  auto n = [](std::size_t v) { return static_cast<double>(v); };
  row("block_layer_entities", n(rep.blockEntities), "Table 1: input entities, block layer");
  row("lot_layer_entities", n(rep.lotEntities), "input entities, lot layer");
  row("building_layer_entities", n(rep.buildingEntities), "Table 1: input entities, building layer");
  row("label_entities", n(rep.labelEntities), "input number-of-floors labels");
  row("total_entities", n(rep.totalEntities()), "Table 1: Total");
  row("pre_blocks", n(rep.preBlocks), "pre-block graphs (Block Threshold clustering)");
  row("blocks", n(rep.blocks), "Table 1: processed elements, block layer");
  row("sub_blocks", n(rep.subBlocks), "");
  row("courtyards", n(rep.courtyards), "closed rings inside a block");
  row("parcels", n(rep.parcels), "circuits of block + lot lines");
  row("buildings", n(rep.buildings),
      "Table 1: processed elements, building layer (building elements + courtyards)");
  row("buildings_with_floors", n(rep.buildingsWithFloors), "elements with floors >= 1");
  row("collapsed_vertices", rep.collapsedShare, "Table 1: share of vertex occurrences merged");
  row("entities_per_building", rep.entitiesPerBuildingTable(), "Table 1 as printed: 2 Total / buildings");
  row("entities_per_building_formula", rep.entitiesPerBuildingFormula(),
      "thesis formula (Be + 2 be) / buildings");
  row("buildings_per_block", rep.buildingsPerBlock(), "Table 1");
  row("input_vertices", n(rep.inputVertices), "");
  row("output_vertices", n(rep.outputVertices), "");
  row("reverted_collapses", n(rep.revertedCollapses), "anti-drift rule");
  row("zero_length_segments", n(rep.zeroLengthSegments), "segments collapsed to a point");
  row("duplicate_segments", n(rep.duplicateSegments), "redundant segments removed");
  row("vertices_on_segments", n(rep.verticesOnSegments),
      "segments split at a vertex on them: T-vertices, partial overlaps");
  row("corners_kept_off_segments", n(rep.cornersKeptOff),
      "lot/building corners within -collapse of a segment left in place (their lines already meet)");
  row("corners_closed", n(rep.cornersClosed),
      "pairs of dangling ends extended or trimmed to where their lines cross");
  row("undershoots_to_segment", n(rep.undershootsToSegment),
      "dangling ends extended onto a segment (also its middle)");
  row("undershoots_to_vertex", n(rep.undershootsToVertex), "dangling ends joined to the nearest vertex");
  row("overshoots_cut", n(rep.overshootsCut), "ends running past a crossing");
  row("hooks_cut", n(rep.hooksCut),
      "short last edges folding back on their line, the line ended at the fold");
  row("fringe_edges_removed", n(rep.fringeEdgesRemoved), "removed fringe paths (edges)");
  row("vertices_straightened", n(rep.verticesStraightened), "degree-2 vertices dropped on straight lines");
  row("split_vertices_merged", n(rep.splitVerticesMerged),
      "vertices closer than -merge-split noise units merged (copies of one drawn vertex)");
  row("merges_refused_drawn", n(rep.mergesRefusedDrawn),
      "close vertices kept apart: a drawn segment joins them");
  row("merges_refused_face", n(rep.mergesRefusedFace),
      "close vertices kept apart: a real face would collapse");
  row("merges_refused_crossing", n(rep.mergesRefusedCrossing),
      "close vertices kept apart: the merge would make segments cross");
  row("adjustment_noise", rep.adjustmentNoise,
      "estimated spread (m) of the drawn copies across their segments (adjustment weights)");
  row("straight_constraints", n(rep.straightConstraints), "adjustment: vertices kept on a straight line");
  row("right_angle_constraints", n(rep.rightAngleConstraints), "adjustment: near-right angles held square");
  row("vertices_adjusted", n(rep.verticesAdjusted), "vertices moved by the adjustment (> 1 mm)");
  row("slivers_dropped", n(rep.slivers), "circuits under -min-area");
  row("labelled_thin_faces_kept", n(rep.labelledThinKept),
      "building faces thinner than the sliver width kept: a floor label inside, copies coinciding");
  row("faces_outside_blocks", n(rep.facesOutsideBlocks), "building circuits outside every block");
  row("buildings_outside_blocks", n(rep.buildingsOutsideBlocks),
      "of those, kept as buildings: a label gives them floors");
  row("enclosed_blocks", n(rep.enclosedBlocks),
      "rings inside a block holding lot/building lines: blocks, not courtyards");
  row("labels_used", n(rep.labelsUsed), "");
  row("labels_outside_polygons", n(rep.labelsSnapped), "labels outside every element, given to the nearest");
  row("labels_unmatched", n(rep.labelsUnmatched), "labels too far from every element");
  row("labels_not_numbers", n(rep.labelsNotNumbers), "labels without a number of floors");
  row("label_suffixes_ignored", n(rep.labelSuffixesIgnored), "labels with a use suffix (e.g. +TZA) ignored");
  row("polygons_with_several_labels", n(rep.polygonsWithSeveralLabels),
      "the label nearest the inside is kept");

  output.write({blocks, subBlocks, courtyards, parcels, buildings, report}, crs);

  if (objOut || jsonOut) {
    reportProgress(ctx.progress, 0.9, "3D");
    if (objOut) {
      const cadastre::Mesh mesh = cadastre::extrudeBuildings(r.buildings);
      double ox = 1e300, oy = 1e300;
      for (const auto& v : mesh.vertices) ox = std::min(ox, v[0]), oy = std::min(oy, v[1]);
      if (mesh.vertices.empty()) ox = oy = 0;
      std::ofstream f(objOut->tempPath(), std::ios::binary);
      f << cadastre::objText(mesh, {std::floor(ox), std::floor(oy)},
                             crs.empty() ? "" : io::crsShortName(crs));
      if (!f) throw ioError("cannot write '" + args.str("-obj") + "'");
    }
    if (jsonOut) {
      std::ofstream f(jsonOut->tempPath(), std::ios::binary);
      f << cadastre::cityJsonText(r.buildings, epsgOf(crs));
      if (!f) throw ioError("cannot write '" + args.str("-cityjson") + "'");
    }
  }
  output.commit(ctx.progress);
  if (objOut) objOut->commit(ctx.progress);
  if (jsonOut) jsonOut->commit(ctx.progress);
  if (!ctx.quiet && ctx.out)
    *ctx.out << "cadastre: " << rep.blocks << " blocks (" << rep.subBlocks << " sub-blocks, "
             << rep.courtyards << " courtyards), " << rep.parcels << " parcels, " << rep.buildings
             << " building elements (" << rep.buildingsWithFloors << " with floors); " << rep.labelsUsed
             << " of " << rep.labelEntities << " labels used\n";
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
