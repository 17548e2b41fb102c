#pragma once
// Names of the fields that more than one effect (or the app) reads from the FieldStore.
// They are also the output's `fields:` names and the HDF5 datasets' names in outputs and
// checkpoints: renaming one changes files on disk.
namespace voigt::field {
inline constexpr const char* velocity = "velocity";   // nodes, 3 components (navier_stokes or prescribed_flow)
inline constexpr const char* pressure = "pressure";   // cells (navier_stokes)
inline constexpr const char* density = "density";     // cells (navier_stokes; level_set blends it)
inline constexpr const char* viscosity = "viscosity"; // cells (navier_stokes; level_set blends it)
inline constexpr const char* psi = "psi";             // cells, the level set (level_set)
inline constexpr const char* fixMask = "fix_mask";    // nodes, prescribed components (navier_stokes, obstacles)
inline constexpr const char* fixValue = "fix_value";  // nodes, their values (navier_stokes, obstacles)
} // namespace voigt::field
