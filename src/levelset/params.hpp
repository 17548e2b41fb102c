#pragma once
// Level-set geometry shared by the level_set and reinit effects: the smoothing
// half-width kappa of Eq. (4) and the narrow band, both given in cells in the
// scene's `level_set` section (read by effects/level_set/geometry.hpp) and turned into
// lengths with the smallest h.
#include <algorithm>

#include "core/grid.hpp"

namespace voigt {

struct LevelSetGeometry {
  double kappaCells = 2; // paper: kappa = 2 cells
  double bandCells = 6;  // re-initialisation works where |psi| < band
  static double hMin(const Grid& g) { return std::min({g.h[0], g.h[1], g.h[2]}); }
  double kappa(const Grid& g) const { return kappaCells * hMin(g); }
  double band(const Grid& g) const { return bandCells * hMin(g); }
};

} // namespace voigt
