#pragma once
// Boundary conditions on the node velocity.
// fixmask bit d set = velocity component d is prescribed at that node (walls,
// inflow, obstacles); fixval holds the prescribed value. Prescribed components
// get no pressure correction (NUMERICS.md) and are re-imposed after each update.
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/boundary.hpp"
#include "scene/scene.hpp"

namespace voigt {

// Face masks from the scene's boundary conditions, over owned and ghost nodes;
// wall values at time t (oscillating walls: velocity * sin(omega t + phase)).
void buildFaceMask(const Grid& g, const Scene& s, const IntField& mask, const VecField& val, double t = 0);
bool hasOscillatingWalls(const Scene& s);
// Rewrites the face values at time t where the scene has oscillating walls (a
// no-op otherwise). Overwrites obstacle values on wall nodes: re-add obstacles
// afterwards if any touch the walls.
void refreshWallValues(const Grid& g, const Scene& s, const IntField& mask, const VecField& val, double t);
// Adds the obstacles (all components, their velocity) to the mask.
void addObstacleMask(const Grid& g, const std::vector<Obstacle>& obs, const IntField& mask,
                     const VecField& val);
// applyFixed (u = val where prescribed): kernels/boundary.hpp.
// Ghost nodes beyond physical faces, for the MUSCL stencil: odd reflection about
// the boundary value for prescribed components, even for free ones (outflow,
// slip tangential). Call after the halo exchange.
void fillVelocityGhosts(const Grid& g, const Scene& s, const VecField& u);
// Ghost nodes of a scalar node field beyond physical faces by even reflection
// about the boundary node (the node density of the momentum advection).
void fillNodeGhostsEven(const Grid& g, const Field& f);
// Ghost cells beyond physical faces by even reflection (zero normal gradient).
void fillCellGhostsEven(const Grid& g, const Field& f);
// The same, only where the cells in `reads` (local indices, ghosts included) need it.
void fillCellGhostsEven(const Grid& g, const Field& f, const Range3& reads);

} // namespace voigt
