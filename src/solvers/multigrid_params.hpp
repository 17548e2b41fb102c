#pragma once
// MueLu's parameter list for projection.preconditioner: multigrid (src/solvers/*.cpp only).
#include <Teuchos_ParameterList.hpp>

#include "solvers/solver_settings.hpp"
#include "solvers/trilinos_types.hpp"

namespace voigt::tpetra {

// exact: the 27-point operator, whose near-null space nearNull (the constant and the
// checkerboard) the aggregates carry.
Teuchos::ParameterList multigridParameters(const PoissonSettings& cfg, bool exact, const Teuchos::RCP<MV>& nearNull);

} // namespace voigt::tpetra
