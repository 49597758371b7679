// .osmi importance files (spec §B.1.2), parsed with expat so malformed XML reports its line and column.
#include "urbanvec/io/osmi_reader.hpp"

#include <expat.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "urbanvec/core/error.hpp"

namespace urbanvec::io {
namespace {

struct ParseState {
  std::string path;
  OsmiFile file;
  XML_Parser parser = nullptr;
  int depth = 0;
  bool inPlace = false;
  std::string error;  ///< first semantic error
};

const char* attribute(const XML_Char** attrs, const char* name) {
  for (int i = 0; attrs[i]; i += 2)
    if (std::strcmp(attrs[i], name) == 0) return attrs[i + 1];
  return nullptr;
}

void fail(ParseState& s, const std::string& message) {
  if (s.error.empty())
    s.error = "importance file '" + s.path + "' line " + std::to_string(XML_GetCurrentLineNumber(s.parser)) +
              ": " + message;
  XML_StopParser(s.parser, XML_FALSE);
}

void XMLCALL startElement(void* data, const XML_Char* name, const XML_Char** attrs) {
  ParseState& s = *static_cast<ParseState*>(data);
  ++s.depth;
  const std::string element = name;
  if (s.depth == 1) {
    if (element != "osmi") return fail(s, "the root element is <" + element + ">, not <osmi>");
    if (const char* v = attribute(attrs, "version")) s.file.version = v;
    if (const char* v = attribute(attrs, "osm")) s.file.osm = v;
    return;
  }
  if (s.depth == 2 && element == "place") {
    OsmiPlace place;
    if (const char* v = attribute(attrs, "id")) place.id = v;
    if (const char* v = attribute(attrs, "role")) place.role = v;
    place.line = static_cast<int>(XML_GetCurrentLineNumber(s.parser));
    s.file.places.push_back(std::move(place));
    s.inPlace = true;
    return;
  }
  if (s.depth == 3 && s.inPlace) {
    OsmiPlace& place = s.file.places.back();
    if (element == "member") {
      const char* type = attribute(attrs, "type");
      const char* ref = attribute(attrs, "ref");
      if (!type || !ref) return fail(s, "<member> of place '" + place.id + "' needs both type and ref");
      const std::string t = type;
      if (t != "node" && t != "way" && t != "relation")
        return fail(
            s, "<member> of place '" + place.id + "' has type '" + t + "'; expected node, way or relation");
      char* end = nullptr;
      errno = 0;
      const long long id = std::strtoll(ref, &end, 10);
      if (errno != 0 || end == ref || *end != '\0')
        return fail(s,
                    "<member> of place '" + place.id + "' has ref '" + std::string(ref) + "', not an OSM id");
      place.members.push_back({t[0], static_cast<std::int64_t>(id)});
    } else if (element == "tag") {
      const char* k = attribute(attrs, "k");
      const char* v = attribute(attrs, "v");
      if (!k || !v) return fail(s, "<tag> of place '" + place.id + "' needs both k and v");
      place.tags.emplace_back(k, v);
    }
  }
}

void XMLCALL endElement(void* data, const XML_Char*) {
  ParseState& s = *static_cast<ParseState*>(data);
  if (s.depth == 2) s.inPlace = false;
  --s.depth;
}

}  // namespace

const std::string* OsmiPlace::tag(const std::string& k) const {
  for (const auto& [key, value] : tags)
    if (key == k) return &value;
  return nullptr;
}

bool looksLikeOsmi(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".osmi") return true;
  std::ifstream in(path, std::ios::binary);
  std::string head(512, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find("<osmi") != std::string::npos;
}

OsmiFile readOsmiFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw invalidInput("importance file '" + path + "' does not exist");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw invalidInput("importance file '" + path + "' cannot be opened");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  ParseState state;
  state.path = path;
  state.parser = XML_ParserCreate(nullptr);
  XML_SetUserData(state.parser, &state);
  XML_SetElementHandler(state.parser, startElement, endElement);
  const XML_Status status = XML_Parse(state.parser, text.data(), static_cast<int>(text.size()), XML_TRUE);
  std::string message;
  if (!state.error.empty()) {
    message = state.error;
  } else if (status != XML_STATUS_OK) {
    message = "importance file '" + path + "' is not well-formed XML at line " +
              std::to_string(XML_GetCurrentLineNumber(state.parser)) + ", column " +
              std::to_string(XML_GetCurrentColumnNumber(state.parser) + 1) + ": " +
              XML_ErrorString(XML_GetErrorCode(state.parser));
  }
  XML_ParserFree(state.parser);
  if (!message.empty()) throw invalidInput(message);
  if (state.depth != 0 ||
      (state.file.version.empty() && state.file.places.empty() && text.find("<osmi") == std::string::npos))
    throw invalidInput("importance file '" + path + "' has no <osmi> root element");
  return std::move(state.file);
}

}  // namespace urbanvec::io
