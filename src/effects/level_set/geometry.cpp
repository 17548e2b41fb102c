#include "effects/level_set/geometry.hpp"

#include "scene/reader.hpp"

namespace voigt {

LevelSetGeometry levelSetGeometry(const Scene& s) { return levelSetGeometry(topSection(s, "level_set")); }

LevelSetGeometry levelSetGeometry(const Section& ls) {
  LevelSetGeometry geo;
  geo.kappaCells = ls.number("smoothing", geo.kappaCells, {0.5, 20, false, false});
  geo.bandCells = ls.number("band", geo.bandCells, {1, 1000, false, false});
  if (geo.bandCells < geo.kappaCells + 1)
    ls.fail("band", "must be at least smoothing + 1 cells (the band must hold the smoothed interface)");
  return geo;
}

} // namespace voigt
