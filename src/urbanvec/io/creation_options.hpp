// Checking GDAL creation options (-co, -lco, -dsco) before any work: GDAL itself only warns about
// unknown names and bad values, and only when the output is created, after the computation.
#pragma once

#include <string>
#include <vector>

namespace urbanvec::io {

/// Case-insensitive comparison, as GDAL compares option names and values.
bool equalsIgnoringCase(const std::string& a, const std::string& b);

/// Checks NAME=VALUE options against a driver's declared option list (XML, e.g. its
/// DMD_CREATIONOPTIONLIST): names, booleans, integers and fixed choices. `flag` ("-lco") and `kind`
/// ("layer") name the options in the message, `format` the driver. Throws invalidOption.
void checkCreationOptions(const char* optionListXml, const std::vector<std::string>& given,
                          const std::string& flag, const std::string& kind, const std::string& format);

}  // namespace urbanvec::io
