// The .osmi importance format (spec §B.1.2) and the OSM reader that keeps way node ids.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/osm_reader.hpp"
#include "urbanvec/io/osmi_reader.hpp"

namespace urbanvec::io {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& path) {
  try {
    readOsmiFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Osmi, ReadsTheThesisExampleWithBothBoundingSpellings) {
  const std::string path = writeTemp("firenze.osmi", R"(<osmi version="0.1" osm="firenze.osm">
  <place id="112" role="interesting">
    <member ref="23396102" type="way"/>
    <tag k="appearW" v="1."/>
    <tag k="modifyW" v="o."/>
    <tag k="name" v="Battistero di San Giovanni"/>
  </place>
  <place id="100" role="important">
    <member ref="270928894" type="node"/>
    <member ref="27648129"  type="way"/>
    <member ref="270928894" type="node"/>
    <tag k="appearW" v="0.5"/> <tag k="function" v="boundary"/>
  </place>
</osmi>)");
  const OsmiFile f = readOsmiFile(path);
  EXPECT_EQ(f.version, "0.1");
  EXPECT_EQ(f.osm, "firenze.osm");
  ASSERT_EQ(f.places.size(), 2u);
  EXPECT_EQ(f.places[0].id, "112");
  EXPECT_EQ(f.places[0].role, "interesting");
  ASSERT_EQ(f.places[0].members.size(), 1u);
  EXPECT_EQ(f.places[0].members[0].type, 'w');
  EXPECT_EQ(f.places[0].members[0].ref, 23396102);
  EXPECT_EQ(*f.places[0].tag("appearW"), "1.");
  EXPECT_EQ(*f.places[0].tag("name"), "Battistero di San Giovanni");
  EXPECT_EQ(f.places[0].line, 2);
  EXPECT_EQ(f.places[1].members.size(), 3u);
  EXPECT_EQ(*f.places[1].tag("function"), "boundary");
  EXPECT_TRUE(looksLikeOsmi(path));
}

TEST(Osmi, MalformedXmlGivesLineAndColumn) {
  const std::string path = writeTemp("bad.osmi",
                                     "<osmi version=\"0.1\">\n  <place id=\"1\">\n    <member ref=\"1\" "
                                     "type=\"node\">\n  </place>\n</osmi>\n");
  EXPECT_EQ(errorOf(path),
            "importance file '" + path + "' is not well-formed XML at line 4, column 5: mismatched tag");
}

TEST(Osmi, RejectsOtherRootsAndBadMembers) {
  const std::string root = writeTemp("root.osmi", "<osm version=\"0.6\"/>\n");
  EXPECT_EQ(errorOf(root), "importance file '" + root + "' line 1: the root element is <osm>, not <osmi>");
  const std::string member = writeTemp(
      "member.osmi", "<osmi>\n<place id=\"7\">\n<member ref=\"x1\" type=\"way\"/>\n</place>\n</osmi>");
  EXPECT_EQ(errorOf(member),
            "importance file '" + member + "' line 3: <member> of place '7' has ref 'x1', not an OSM id");
  EXPECT_EQ(errorOf(::testing::TempDir() + "none.osmi"),
            "importance file '" + ::testing::TempDir() + "none.osmi' does not exist");
}

TEST(OsmReader, KeepsWayNodeIdsBoundsAndHighways) {
  const std::string path = writeTemp("tiny.osm", R"(<?xml version="1.0"?>
<osm version="0.6">
  <bounds minlat="43.70" minlon="7.40" maxlat="43.75" maxlon="7.45"/>
  <node id="3" lat="43.72" lon="7.41"/>
  <node id="1" lat="43.71" lon="7.42"/>
  <node id="2" lat="43.76" lon="7.42"/>
  <way id="10"><nd ref="1"/><nd ref="3"/><nd ref="2"/><tag k="highway" v="residential"/><tag k="name" v="Rue"/></way>
  <way id="11"><nd ref="1"/><nd ref="3"/><tag k="building" v="yes"/></way>
  <relation id="5"><member type="way" ref="11" role="outer"/><tag k="name" v="Palais"/></relation>
</osm>)");
  const OsmData d = readOsmFile(path, "OSM file");
  EXPECT_TRUE(d.hasBounds);
  EXPECT_DOUBLE_EQ(d.maxLat, 43.75);
  ASSERT_EQ(d.nodes.size(), 3u);
  EXPECT_EQ(d.nodes[0].id, 1);  // sorted
  ASSERT_NE(d.way(10), nullptr);
  EXPECT_EQ(d.way(10)->refs, (std::vector<std::int64_t>{1, 3, 2}));
  EXPECT_EQ(d.way(10)->highway, "residential");
  EXPECT_EQ(d.way(11)->highway, "");
  ASSERT_NE(d.relation(5), nullptr);
  EXPECT_EQ(d.relation(5)->members[0].ref, 11);
  EXPECT_EQ(d.node(4), nullptr);
  const std::string broken = writeTemp(
      "broken.osm",
      "<?xml version=\"1.0\"?>\n<osm version=\"0.6\">\n<node id=\"1\" lat=\"1\" lon=\"2\">\n</osm>\n");
  try {
    readOsmFile(broken, "OSM file");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace urbanvec::io
