#pragma once
// Initial shapes as implicit functions, positive inside (phase 1, NOTES.md
// erratum 4), compiled from the scene into a small postfix program that a
// Kokkos kernel evaluates at every cell centre. Fast Marching then turns the
// result into a signed distance, so primitives only need the right zero set
// (the cheap ones are exact distances anyway).
//
//   shape: {type: sphere, center: [x,y,z], radius: r}
//          {type: box, lo: [...], hi: [...]}
//          {type: plane, point: [...], normal: [...]}        phase 1 behind the normal
//          {type: wave, point, normal, direction, amplitude, wavelength}
//                 a plane displaced by amplitude * cos(2 pi s / wavelength) along
//                 the normal, s = (x - point) . direction (Rayleigh-Taylor, sloshing)
//          {type: cylinder, center, radius, axis: x|y|z, length: L (optional, default infinite)}
//          {type: superquadric, center, semi_axes: [a,b,c], exponent: p}
//                 1 - sum |x_i/a_i|^p, the paper's Eq. (22) negated
//          {type: sphere_packing, file: spheres.csv, radius: r (if the CSV has 3 columns)}
//          {type: union | intersection, of: [shape, ...]}    max | min
//          {type: complement, of: shape}                     -f
#include <string>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "kernels/shapes.hpp"
#include "scene/reader.hpp"

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

// Reads `shape` from a section (the level_set section). CSV paths are relative
// to the scene file. Errors name the scene key, or the CSV file and line.
ShapeProgram compileShape(const Section& parent, const std::string& key, const Scene& scene);

// Fills f at every cell centre of the local array (owned + ghosts).
void evaluateShape(const Grid& g, const ShapeProgram& p, const Field& f);

} // namespace voigt
