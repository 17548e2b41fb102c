#pragma once
// The level_set section's geometry keys, read once by the level_set effect and published to
// the others (Published::levelSet).
#include "levelset/params.hpp"
#include "scene/scene.hpp"

namespace voigt {

// Reads level_set.smoothing and level_set.band (validated; the level_set effect
// owns the rest of the section and rejects unknown keys).
LevelSetGeometry levelSetGeometry(const Scene& s);
class Section;
// The same keys from one map (`level_set:` or a `level_sets:` entry).
LevelSetGeometry levelSetGeometry(const Section& ls);

} // namespace voigt
