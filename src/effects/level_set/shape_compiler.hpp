#pragma once
// The scene's `shape` compiled into a ShapeProgram (levelset/shapes.hpp):
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

#include "levelset/shapes.hpp"
#include "scene/reader.hpp"

namespace voigt {

// Reads `shape` from a section (the level_set section). CSV paths are relative
// to the scene file. Errors name the scene key, or the CSV file and line.
ShapeProgram compileShape(const Section& parent, const std::string& key, const Scene& scene);

} // namespace voigt
