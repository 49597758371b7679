#pragma once

namespace urbanvec::io {
/// Registers GDAL/OGR drivers once and routes GDAL's own messages away from stderr (the app reports
/// errors itself, as one line). Safe to call many times.
void ensureGdal();
/// The last message GDAL reported (empty when none), for inclusion in an error sentence.
const char* lastGdalMessage();
}  // namespace urbanvec::io
