#pragma once
// A scene as the core understands it. Effects read their own sections from
// `root` through a voigt::Section (reader.hpp), so new physics needs no change here.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace voigt {

using Vec3 = std::array<double, 3>;
struct SourceInfo; // reader.hpp

enum class BcType { NoSlip, Slip, Periodic, Inflow, Outflow };
const char* toString(BcType t);

// Face order: x-, x+, y-, y+, z-, z+ (face = 2*axis + side).
struct FaceBc {
  BcType type = BcType::NoSlip;
  Vec3 velocity{0, 0, 0}; // wall velocity (no_slip: moving wall) or inflow velocity
  double pressure = 0;    // outflow pressure
  // no_slip `oscillation: {omega, phase}`: the wall moves as velocity * sin(omega t + phase).
  bool oscillating = false;
  double omega = 0, phase = 0;
  // Wall (or inflow) velocity at time t.
  Vec3 velocityAt(double t) const {
    if (!oscillating) return velocity;
    const double f = std::sin(omega * t + phase);
    return {velocity[0] * f, velocity[1] * f, velocity[2] * f};
  }
};

struct Material {
  std::string name;
  double density = 1;
  double viscosity = 0;     // fluid viscosity; on an elastic material the Kelvin-Voigt solid viscosity
  double shearModulus = 0;  // mu_S of Eq. (13); 0 = not elastic. Given directly (shear_modulus) or
                            // from youngs_modulus E and poisson_ratio nu: mu_S = E / (2 (1 + nu))
};

struct ProjectionCfg {
  enum class Op { Exact, Approximate } op = Op::Exact;
  // Belos relative residual. Not given: 1e-3 for the exact operator with two densities
  // (scene/load.cpp, why there), else this.
  double tolerance = 1e-8;
  static constexpr double kTwoPhaseExactTolerance = 1e-3;
  bool toleranceAuto = false;  // chosen by that rule, not written in the scene
  int maxIterations = 1000;
  // sgs | jacobi | none | multigrid | fast_diagonalization (exact operator only). Not given
  // (auto): fast_diagonalization with the exact operator; with the approximate one multigrid
  // from 32^3 cells or two densities, else sgs (scene/load.cpp, why there).
  std::string preconditioner = "sgs";
  bool preconditionerAuto = false; // chosen by that rule, not written in the scene
  double damping = 1.0;        // Ifpack2 relaxation damping factor
  int sweeps = 1;
  // Multigrid only: what set-up to keep when the coefficients change (MueLu "reuse: type",
  // MueLu_ParameterListInterpreter_def.hpp). none: rebuild all; S: smoother symbolic data;
  // tP: aggregates and tentative prolongators (smoothed P, R, RAP, smoothers recomputed);
  // RP: P and R (RAP and smoothers recomputed); RAP: every coarse level as built (only the
  // fine smoother recomputed). A change of the zero pattern rebuilds everything. tP (the
  // default) keeps only what does not depend on the values, so it gives the same
  // preconditioner as none, bit for bit, at about half the set-up cost; RP and RAP keep
  // value-dependent parts: cheaper, solutions agree to solver tolerance, and a restart is
  // no longer bit-identical (the restarted run rebuilds). MueLu's "full" is not offered:
  // its fine smoother keeps a stale diagonal and CG breaks down (test_multigrid_reuse.cpp).
  std::string multigridReuse = "tP";
  // Multigrid with reuse: a full rebuild every N coefficient updates (0: only when the
  // zero pattern changes). Useful with RAP, whose iterations grow as the density moves.
  int multigridRefresh = 0;
  // Multigrid with reuse: a full rebuild also when a solve takes more than (1 + growth)
  // times the iterations of the first solve after the last build, plus one (0: off). The
  // kept coarse levels age as the density moves; the iterations say when (perf/README.md).
  double multigridRebuildGrowth = 0.25;
  // Multigrid only: the fine-level smoother. sgs: MueLu's default relaxation (symmetric
  // Gauss-Seidel, sequential sweeps); chebyshev: Ifpack2 Chebyshev of this degree (matrix-
  // vector products only: runs on threads and GPUs; perf/README.md compares the two).
  std::string multigridSmoother = "sgs";
  // A solve that reaches max_iterations: warn (stderr, as it happens; counted in
  // summary.json and the end-of-run line) or stop (the run fails, exit code 3).
  std::string onCap = "warn";
  int chebyshevDegree = 2;
  // Multigrid only: SGS sweeps on the coarsest level (MueLu's RELAXATION coarse solver:
  // KLU2 fails on the singular operator). With the 7-point operator the coarsest level
  // holds up to 2000 rows, which one sweep hardly solves: 10 sweeps halve the CG
  // iterations at 64^3-75^3 (13.3 -> 6.6 on the falling block) for a negligible cost
  // (perf/README.md, "The coarsest level").
  int coarseSweeps = 10;
  // Fast diagonalization only: single (its passes in float between two conversions; CG stays
  // in double) or double. Single: 1.3-1.4x less time a pass, a few more iterations at tight
  // tolerances (perf/README.md, "The exact projection at a tolerance").
  std::string fdPrecision = "single";
  // The CG initial guess: previous (the last increment dp) or extrapolate (dt times the
  // pressure rate dp/dt extrapolated linearly from the last two steps). Default: extrapolate
  // with fast diagonalization (dam break 64^3 at tolerance 1e-3: 74.5 -> 49.9 iterations a
  // step), previous otherwise (multigrid on the same solve: 13.4 -> 22.9, its coarse levels
  // do not take the checkerboard part the extrapolation amplifies; perf/README.md, "The exact
  // projection at a tolerance").
  std::string initialGuess = "previous"; // scene/load.cpp applies the rule above
  bool initialGuessAuto = true;
  // Exact operator: CG multiplies by it without its matrix (kernels/poisson_apply.hpp, ~100
  // bytes a cell against ~330 for the 27-point CSR product), or by the CSR matrix (false).
  // The same operator up to round-off (perf/README.md, "The exact operator without its matrix").
  bool matrixFree = true;
  // balanced: with gravity, the stored pressure carries the discrete hydrostatic pressure of
  // the current density, so rest is a fixed point at any tolerance and the solve finds only
  // the departure from hydrostatics (effects/gravity.cpp); none: gravity as a plain body force.
  // Default: balanced with the exact operator, none with the approximate one (scene/load.cpp).
  std::string hydrostatic = "balanced";
  // An absolute floor beside the relative tolerance: no CG when the divergence the solve
  // could leave changes no cell's volume by more than this in the step (dt max|div| <=
  // volume_tolerance, Basilisk's TOLERANCE measure; with the exact operator D u = dt r, so
  // ||b|| <= volume_tolerance / dt^2 suffices). 0 (off) by default: at 1e-12 a resting
  // column's CG iterations fall 43 -> 17 a step, but a small-amplitude flow's solves are
  // skipped too (elastic Couette at V = 1e-4 m/s: the cross-stream velocity 1.2e-12 m/s where
  // it is 1e-13 with every solve), and the resting tank with a sphere grew from step ~2500
  // (tenfold every ~800 steps) where with every solve it stays at 2e-13 m/s; README.
  double volumeTolerance = 0;
  // How the variable 1/rho enters the pressure solve. solve (default): CG on D B G dp with
  // B = 1/rho. split (Dodd & Ferrante 2014, J. Comput. Phys. 273, 416): B G dp taken as
  // B0 G dp + (B - B0) G dp_hat with B0 = 1/rho_min and dp_hat = dt times the last pressure
  // rate, so the solve is the one-density operator D B0 G, which fast diagonalization inverts
  // (one CG iteration without obstacles); u^{n+1} is as divergence-free as before. The lagged
  // part is stable only below a time step of its own (navier_stokes dtLimit, "split"), and
  // not offered with elasticity (perf/README.md, "The one-density split").
  std::string variableDensity = "solve";
};

struct AdvectionCfg {
  std::string limiter = "minmod"; // minmod | van_leer | mc | none (unlimited, Fromm)
  // Momentum advection: conservative (rho and rho u with one flux), velocity
  // (-[div(u u) - u div_h u]), or auto: conservative when phases differ in density.
  std::string momentum = "auto";
};

struct TimeCfg {
  double endTime = 1;
  double dt = 0;        // > 0: fixed step; 0: adaptive
  double cfl = 0.5;     // adaptive: advective CFL number
  double viscousSafety = 0.5; // fraction of the explicit viscous limit
  double maxDt = std::numeric_limits<double>::infinity();
  double minDt = 1e-12; // a step below this is a collapse: stop
  long maxSteps = -1;   // -1: unlimited
};

struct Obstacle {
  enum class Kind { Cylinder, Box, Sphere } kind = Kind::Sphere;
  Vec3 center{0, 0, 0};
  double radius = 0;
  int axis = 2;          // cylinder axis
  Vec3 lo{0, 0, 0}, hi{0, 0, 0}; // box
  Vec3 velocity{0, 0, 0};
};

struct InitialCfg {
  // zero | uniform | taylor_green | couette | poiseuille
  std::string velocity = "zero";
  Vec3 uniform{0, 0, 0};
  double amplitude = 1; // taylor_green: U0; poiseuille: centre velocity
  double pressure = 0;  // uniform initial pressure
};

struct OutputCfg {
  double interval = 0;  // simulated time between outputs; 0: first and last only
  std::vector<std::string> fields{"velocity", "pressure"};
  bool enabled = true;
};

struct Probe {
  std::string name;
  enum class Kind { Point, Line } kind = Kind::Point;
  Vec3 a{0, 0, 0}, b{0, 0, 0};
  int points = 1;
  std::vector<std::string> fields{"velocity", "pressure"};
  double interval = 0; // 0: every step
};

struct Scene {
  std::string path;     // file it came from ("" for built-in)
  YAML::Node root;      // the validated tree, with --set overrides applied
  std::shared_ptr<const SourceInfo> source; // file name and --set list, for error locations
  std::string name;
  std::array<int, 3> cells{16, 16, 16};
  Vec3 lo{0, 0, 0}, hi{1, 1, 1};
  std::array<int, 3> ranks{0, 0, 0}; // requested decomposition, 0 = auto
  std::array<FaceBc, 6> bc{};
  TimeCfg time;
  std::map<std::string, Material> materials;
  std::string fluid;    // name of the fluid material
  std::vector<std::string> effects;
  Vec3 gravity{0, 0, 0};
  std::vector<Obstacle> obstacles;
  InitialCfg initial;
  OutputCfg output;
  std::vector<Probe> probes;
  ProjectionCfg projection;
  AdvectionCfg advection;
  std::string preset;                    // `preset:` fast | balanced | accurate, or "" (scene/presets.hpp)
  std::vector<std::string> presetNotes;  // the knobs it set, "time.cfl = 0.5", for `voigt check`

  const Material& fluidMaterial() const { return materials.at(fluid); }
  bool periodic(int axis) const { return bc[2 * axis].type == BcType::Periodic; }
};

} // namespace voigt
