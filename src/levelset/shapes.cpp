#include "levelset/shapes.hpp"

namespace voigt {

void evaluateShape(const Grid& g, const ShapeProgram& p, const Field& f) { evaluateShapeOps(g, p.ops, p.spheres, f); }

} // namespace voigt
