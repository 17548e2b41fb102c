#pragma once
// Initial shapes as implicit functions, positive inside (phase 1, NOTES.md erratum 4): the
// postfix program a Kokkos kernel evaluates at every cell centre (kernels/shapes.hpp). The
// level_set effect compiles it from the scene (effects/level_set/shape_compiler.hpp, which
// lists the shapes); Fast Marching then turns the result into a signed distance, so
// primitives only need the right zero set (the cheap ones are exact distances anyway).
#include <string>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "kernels/shapes.hpp"

namespace voigt {

struct ShapeProgram {
  ShapeOps ops;
  ShapeSpheres spheres; // packing centres and radii
  std::string text;                             // one-line description for `voigt check`
  long long sphereCount = 0;
  // A single sphere, box, plane or cylinder (or its complement) is already an
  // exact signed distance: Fast Marching can only blur its edges.
  bool exactDistance = false;
};

// Fills f at every cell centre of the local array (owned + ghosts).
void evaluateShape(const Grid& g, const ShapeProgram& p, const Field& f);

} // namespace voigt
