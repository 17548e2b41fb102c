#pragma once
// Sussman re-initialisation of psi with the local volume constraint, paper
// Eq. (17)-(21), on a narrow band. Numerics in kernels/reinit.hpp; this is the
// host driver. One call (run):
//   psi0 = psi (ghosts refreshed); band = owned cells with |psi0| < band;
//   per band cell, fixed for the call: S(psi0), subcell distance D, constraint coef;
//   `iterations` pseudo steps of dtau = dtauCells * hmin, each
//     psi1 = psi^m + dtau R(psi^m)                       (RK2 stage 1, Heun/SSP)
//     psi~ = (psi^m + psi1 + dtau R(psi1)) / 2           (RK2 stage 2)
//     psi^{m+1} = psi~ + dtau lambda f   (Eq. 19-21, once per full step, not per stage)
//   then psi's ghosts are refreshed again, so the caller gets a consistent field.
// Cells outside the band are never written. The per-call setup sweeps the whole
// array (copies, band scan); the pseudo steps touch band cells only (plus halos).
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/halo.hpp"
#include "kernels/reinit.hpp"

namespace voigt {

struct ReinitParams {
  int iterations = 2;      // pseudo-time steps per call
  double dtauCells = 0.5;  // dtau = dtauCells * hmin (Eikonal CFL, NUMERICS.md); in (0, 1]
  double kappa = 0;        // smoothing half-width (length) of H' in Eq. (18)-(21); > 0 with the constraint
  double band = 0;         // work only where |psi0| < band (length); must be >= kappa
  bool volumeConstraint = true;
  bool subcellFix = false; // Russo & Smereka (2000) next to the interface (kernels/reinit.hpp: off, measured)
  double zoneTolerance = 0; // leave smoothing-zone cells with ||grad psi| - 1| below it as advected (settledCell)
  bool boundFarField = false; // bound |psi| outside the zone by its neighbours' + h first (boundFarField)
  bool zoneCurvature = false; // ... below it plus the central differences' error on a curved distance
};

struct ReinitStats {
  long long bandCells = 0; // global count of cells re-initialised: |psi0| < band, not settled
  double seconds = 0;      // wall time of the call (this rank, after a fence)
  // Global max ||grad psi| - 1| at the end (central differences) over band cells
  // not next to the interface (psi0 keeps its sign across every face), whose 6
  // face neighbours are in the band (no frozen cell in the difference) and with
  // |psi| <= band - 2 hmin (frozen cells feed only values >= band into the band).
  double maxGradError = 0;
};

class Reinitializer {
 public:
  // Allocates the scratch once: 3 cell fields and 5 band arrays sized for all owned cells.
  Reinitializer(const Grid& g, ReinitParams p);
  // Re-initialises the owned band cells of psi in place (needs nothing fresh on entry).
  // box: the owned cells where psi can lie in the band (several level sets, one Reinitializer
  // for all: the passes and copies run there only; the scratch outside it is not read).
  ReinitStats run(Halo& halo, const Field& psi, const Range3* box = nullptr);
  // Another level set's smoothing half-width and band (lengths), for the next run().
  void setBand(double kappa, double band);
  const ReinitParams& params() const { return p_; }

 private:
  // Halo exchange and wall ghosts; with `reads`, wall ghosts only where those cells lie.
  void refresh(Halo& halo, const Field& f, const Range3* reads = nullptr, int depth = 0) const;

  const Grid* g_;
  ReinitParams p_;
  Field psi1_, psiT_, dH_;  // RK stage, Eikonal result psi~, H'(psi0)
  Field gm_;                 // |grad psi0| where H' > 0 (the constraint's scratch)
  reinit::BandViews band_;
};

} // namespace voigt
