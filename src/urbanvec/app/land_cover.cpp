// A land-cover raster on gridify's grid (issue 20): see land_cover.hpp.
#include "urbanvec/app/land_cover.hpp"

#include <cmath>
#include <map>

#include "urbanvec/app/command.hpp"
#include "urbanvec/app/grid_input.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/landuse.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"

namespace urbanvec::app {

Grid<std::uint8_t> readLandCover(const LandCoverSource& source, const GridSpec& grid) {
  const std::string role = "-landcover raster";
  std::map<double, LandUse> classes;
  for (const auto& [value, use] : readClassTable(source.table, "-landcover-table")) classes[value] = use;
  io::RasterInfo info;
  const Grid<double> values = io::warpRasterBand(source.raster, role, grid, source.resampling, &info);
  Grid<std::uint8_t> out(grid.width, grid.height, static_cast<std::uint8_t>(LandUse::Unused));
  std::size_t covered = 0;
  for (std::size_t i = 0; i < values.cells.size(); ++i) {
    const double v = values.cells[i];
    if (std::isnan(v)) continue;
    ++covered;
    const auto it = classes.find(v);
    if (it == classes.end())
      throw invalidInput(role + " '" + source.raster + "' holds value " + numberText(v) +
                         " (on the grid at column " + std::to_string(i % values.width) + ", row " +
                         std::to_string(i / values.width) + "), which -landcover-table '" + source.table +
                         "' does not map (add a line '" + numberText(v) + ",<class name>')");
    out.cells[i] = static_cast<std::uint8_t>(it->second);
  }
  if (covered == 0) {
    const auto& s = info.spec.transform.c;
    const auto& g = grid.transform.c;
    throw invalidInput(role + " '" + source.raster + "' covers no cell of the grid (the raster spans " +
                       numberText(s[0]) + " " + numberText(s[3] + info.spec.height * s[5]) + " " +
                       numberText(s[0] + info.spec.width * s[1]) + " " + numberText(s[3]) + " in " +
                       io::crsShortName(info.spec.crsWkt) + "; the grid " + numberText(g[0]) + " " +
                       numberText(g[3] + grid.height * g[5]) + " " + numberText(g[0] + grid.width * g[1]) +
                       " " + numberText(g[3]) + " in " + io::crsShortName(grid.crsWkt) +
                       "), or only nodata there");
  }
  return out;
}

}  // namespace urbanvec::app
