#pragma once
// A solid's velocity extended across its smoothing zone's fluid half (kernels/surface_velocity.hpp):
// what its level set moves with (level_set.surface_velocity: solid). The elastic stress still
// deforms with the grid's velocity: its outermost cells taking this one instead made the falling
// block's impact an energy source (cases/falling_block/NOTEBOOK.md, "A smooth surface").
// Scratch fields "surface_velocity", "surface_velocity_tmp" (node vectors) and "psi_node" (node
// scalar), declared by declareSurfaceVelocity.
#include <string>

#include "core/field.hpp"
#include "core/index_space.hpp"
#include "core/state.hpp"

namespace voigt {

void declareSurfaceVelocity(FieldStore& f, const std::string& owner);

// The grid's velocity with the nodes lo < psi_n <= 0, lo = -(kappa + h), replaced by the
// solid's, extended (Jacobi sweeps, ghosts exchanged before each); fixed components keep
// theirs. psi needs fresh ghosts; layer holds one entry per array point.
VecField solidSurfaceVelocity(State& st, const Field& psi, double kappa, const IntList& layer);

} // namespace voigt
