#pragma once
// Level-set geometry shared by the level_set and reinit effects: the smoothing
// half-width kappa of Eq. (4) and the narrow band, both given in cells in the
// scene's `level_set` section and turned into lengths with the smallest h.
#include <algorithm>

#include "core/grid.hpp"
#include "scene/scene.hpp"

namespace voigt {

struct LevelSetGeometry {
  double kappaCells = 2; // paper: kappa = 2 cells
  double bandCells = 6;  // re-initialisation works where |psi| < band
  static double hMin(const Grid& g) { return std::min({g.h[0], g.h[1], g.h[2]}); }
  double kappa(const Grid& g) const { return kappaCells * hMin(g); }
  double band(const Grid& g) const { return bandCells * hMin(g); }
};

// Reads level_set.smoothing and level_set.band (validated; the level_set effect
// owns the rest of the section and rejects unknown keys).
LevelSetGeometry levelSetGeometry(const Scene& s);

} // namespace voigt
