#pragma once
// The pressure Poisson solver's settings: what src/solvers/*.cpp reads, and nothing
// from the scene (the solver layer includes nothing from src/scene/; scripts/check-layout
// checks it). The scene's projection section (ProjectionCfg, src/scene/scene.hpp) is
// turned into these by poissonSettings() in src/effects/navier_stokes/. The defaults are
// ProjectionCfg's; what each knob means is documented there.
#include <string>

namespace voigt {

struct PoissonSettings {
  // Exact: D(1/rho)G, 27-point; Approximate: compact 7-point variable-coefficient Laplacian.
  enum class Op { Exact, Approximate } op = Op::Exact;
  double tolerance = 1e-8;            // Belos relative residual
  int maxIterations = 1000;
  std::string preconditioner = "sgs"; // sgs | jacobi | none | multigrid
  double damping = 1.0;               // Ifpack2 relaxation damping factor (also MueLu's smoother)
  int sweeps = 1;                     // relaxation sweeps (also MueLu's smoother)
  std::string multigridReuse = "tP";  // MueLu "reuse: type": none | S | tP | RP | RAP
  int multigridRefresh = 0;           // full multigrid rebuild every N coefficient updates (0: never)
  double multigridRebuildGrowth = 0.25; // ... and when the iterations grow by this fraction (0: never)
  std::string multigridSmoother = "sgs"; // fine-level smoother: sgs | chebyshev
  int chebyshevDegree = 2;
  int coarseSweeps = 10;                 // SGS sweeps on the coarsest multigrid level
  bool fdSingle = true;                  // fast diagonalization's passes in float
  bool matrixFree = true;                // exact operator: CG applies it without the CSR matrix
};

} // namespace voigt
