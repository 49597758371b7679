// The thesis's importance file, `.osmi` XML version 0.1 (spec pueyo-urban-data.md §B.1.2): places with
// an id, a role, node/way members and free tags (appearW, name, function=bounding|boundary, ...).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace urbanvec::io {

struct OsmiMember {
  char type = 'n';  ///< 'n' node, 'w' way, 'r' relation (an extension: its way members)
  std::int64_t ref = 0;
};

struct OsmiPlace {
  std::string id;
  std::string role;
  std::vector<OsmiMember> members;
  std::vector<std::pair<std::string, std::string>> tags;
  int line = 0;  ///< of its <place> element
  /// Value of tag k, or nullptr.
  const std::string* tag(const std::string& k) const;
};

struct OsmiFile {
  std::string version;
  std::string osm;  ///< the `osm` attribute: the map file it was written for
  std::vector<OsmiPlace> places;
};

/// Parses an .osmi file with expat. Throws an InvalidInput error naming the file for a missing file,
/// malformed XML (with line and column), a root other than <osmi>, or a <member> without a valid
/// type/ref (with its line).
OsmiFile readOsmiFile(const std::string& path);

/// True when the file looks like an .osmi document (extension .osmi, or XML whose root is <osmi>).
bool looksLikeOsmi(const std::string& path);

}  // namespace urbanvec::io
