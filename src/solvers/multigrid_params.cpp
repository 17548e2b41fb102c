// MueLu's parameter list for the pressure solve (multigrid_params.hpp).
#include "solvers/multigrid_params.hpp"

#include "core/index_space.hpp" // kOnDevice

namespace voigt::tpetra {

Teuchos::ParameterList multigridParameters(const PoissonSettings& cfg, bool exact, const Teuchos::RCP<MV>& nearNull) {
  Teuchos::ParameterList p;
  p.set("verbosity", "none");
  p.set("coarse: type", "RELAXATION"); // KLU2 fails on the singular operator
  // On a threaded node (OpenMP, CUDA) MueLu aggregates with its Kokkos algorithms, whose
  // phases race unless told otherwise: the hierarchy, and so every iterate, would differ
  // from run to run (a restart not bit-identical). The Serial node ignores it.
  p.set("aggregation: deterministic", true);
  // Not enough: MueLu 13.2's Kokkos tentative prolongator (TentativePFactory_kokkos_def.hpp,
  // createAgg2RowMap) lists each aggregate's rows with atomic_fetch_add, so their order, and
  // the round-off of each aggregate's QR, follows the thread schedule. On host backends use
  // the classic factories, as MueLu does by itself on the Serial node (no change there).
  if (!kOnDevice) p.set("use kokkos refactor", false);
  auto& cp = p.sublist("coarse: params");
  cp.set("relaxation: type", "Symmetric Gauss-Seidel");
  cp.set("relaxation: sweeps", cfg.coarseSweeps);
  cp.set("relaxation: damping factor", cfg.damping);
  if (cfg.multigridReuse != "none") p.set("reuse: type", cfg.multigridReuse);
  if (exact) {
    // The 27-point D B G has low-energy modulated checkerboards (its null space holds
    // the checkerboards, null_space.hpp): aggregates that also carry (-1)^(i+j+k) can
    // represent them on the coarse levels. Dam break at density ratio 1000, 64^3,
    // tolerance 1e-8: 1000 (the cap) -> 160-200 iterations; 32^3: 340-430 -> 95-115.
    // A smaller coarsest level (MueLu's default is 2000 rows, solved here by one SGS
    // sweep) takes another 20 % off at 64^3 (perf/README.md, "Exact projection"). 200 rows a
    // rank: with fewer, a level of a few aggregates a rank (uncoupled aggregation stops at
    // the rank's edges) broke CG down at once on 8 ranks (dam break 24^3 and 48^3: p^T A p
    // <= 0 at iteration 2; 1,600 rows, 49 iterations like 1 rank's 41).
    p.sublist("user data").set("Nullspace", nearNull);
    p.set("coarse: max size", 200 * int(nearNull->getMap()->getComm()->getSize()));
  }
  if (cfg.multigridSmoother == "chebyshev") {
    p.set("smoother: type", "CHEBYSHEV");
    p.sublist("smoother: params").set("chebyshev: degree", cfg.chebyshevDegree);
  }
  return p;
}

} // namespace voigt::tpetra
