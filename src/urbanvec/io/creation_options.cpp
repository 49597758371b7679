#include "urbanvec/io/creation_options.hpp"

#include <cpl_minixml.h>
#include <cpl_string.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <memory>

#include "urbanvec/core/error.hpp"

namespace urbanvec::io {

bool equalsIgnoringCase(const std::string& a, const std::string& b) {
  return EQUAL(a.c_str(), b.c_str());
}

void checkCreationOptions(const char* optionListXml, const std::vector<std::string>& given,
                          const std::string& flag, const std::string& kind, const std::string& format) {
  if (given.empty()) return;
  std::unique_ptr<CPLXMLNode, decltype(&CPLDestroyXMLNode)> root(
      optionListXml ? CPLParseXMLString(optionListXml) : nullptr, &CPLDestroyXMLNode);
  std::vector<std::string> known;
  if (root)
    for (const CPLXMLNode* o = root->psChild; o; o = o->psNext)
      if (o->eType == CXT_Element && EQUAL(o->pszValue, "Option"))
        known.push_back(CPLGetXMLValue(o, "name", ""));
  for (const std::string& kv : given) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw invalidOption(flag + " expects NAME=VALUE, got '" + kv + "'");
    const std::string name = kv.substr(0, eq);
    const std::string value = kv.substr(eq + 1);
    const CPLXMLNode* option = nullptr;
    if (root)
      for (const CPLXMLNode* o = root->psChild; o && !option; o = o->psNext)
        if (o->eType == CXT_Element && EQUAL(o->pszValue, "Option") &&
            (equalsIgnoringCase(CPLGetXMLValue(o, "name", ""), name) ||
             equalsIgnoringCase(CPLGetXMLValue(o, "alias", ""), name)))
          option = o;
    if (!option) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw invalidOption(flag + " " + kv + ": " + format + " has no " + kind + " creation option '" + name +
                          "'" + (list.empty() ? " (it takes none)" : " (it takes " + list + ")"));
    }
    const std::string type = CPLGetXMLValue(option, "type", "string");
    auto refuse = [&](const std::string& expected) {
      throw invalidOption(flag + " " + kv + ": " + name + " of " + format + " takes " + expected + ", got '" +
                          value + "'");
    };
    if (equalsIgnoringCase(type, "boolean")) {
      static const char* const kBooleans[] = {"YES", "NO", "TRUE", "FALSE", "ON", "OFF", "1", "0"};
      if (std::none_of(std::begin(kBooleans), std::end(kBooleans),
                       [&](const char* b) { return equalsIgnoringCase(b, value); }))
        refuse("YES or NO");
    } else if (equalsIgnoringCase(type, "int") || equalsIgnoringCase(type, "integer")) {
      char* end = nullptr;
      std::strtoll(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0') refuse("an integer");
    } else if (equalsIgnoringCase(type, "string-select")) {
      std::vector<std::string> choices;
      for (const CPLXMLNode* v = option->psChild; v; v = v->psNext)
        if (v->eType == CXT_Element && EQUAL(v->pszValue, "Value") && v->psChild)
          choices.push_back(v->psChild->pszValue);
      if (!choices.empty() && std::none_of(choices.begin(), choices.end(), [&](const std::string& c) {
            return equalsIgnoringCase(c, value);
          })) {
        std::string list;
        for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
        refuse("one of " + list);
      }
    }
  }
}

}  // namespace urbanvec::io
