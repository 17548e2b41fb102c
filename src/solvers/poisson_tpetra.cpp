// Pressure Poisson solver on Tpetra + Belos CG + Ifpack2/MueLu (poisson.hpp).
// The only translation unit that includes Trilinos (besides trilinos_types.hpp).
#include <BelosSolverFactory.hpp>
#include <BelosSolverFactory_Tpetra.hpp>
#include <Ifpack2_Factory.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_DefaultMpiComm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/poisson_assembly.hpp"
#include "kernels/poisson_rows.hpp"
#include "kernels/projection_ops.hpp"
#include "solvers/multigrid_params.hpp"
#include "solvers/null_space.hpp"
#include "solvers/operators.hpp"
#include "solvers/poisson.hpp"
#include "solvers/trilinos_types.hpp"

namespace voigt {
namespace {

using namespace tpetra;
constexpr double kRoundoff = 1e-14; // rhs below this times ||A|| ||x0||: nothing to solve

RowVector devView(Vector& v) {
  return Kokkos::subview(v.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), 0);
}

// Field owned cells -> vector; identity rows zeroed when `ident` is non-empty.
void fieldToVec(const Field& f, Vector& v, CellRows rw, Range3 cells, RowFlags ident) {
  fieldToRows(f, devView(v), rw, cells, ident);
}
void vecToField(Vector& v, const Field& f, CellRows rw, Range3 cells) { rowsToField(devView(v), f, rw, cells); }

class TpetraPoisson final : public PoissonSolver {
 public:
  TpetraPoisson(const Grid& g, const PoissonSettings& cfg)
      : geom_(g), rows_{g.ng, g.ln[0], g.ln[1]}, cells_(cellRange(g)), cfg_(cfg) {
    MPI_Comm dup;
    MPI_Comm_dup(g.comm, &dup); // owned by Teuchos, freed with the last Map
    comm_ = dup;
    tcomm_ = Teuchos::rcp(new Teuchos::MpiComm<int>(Teuchos::opaqueWrapper(dup, MPI_Comm_free)));
    exact_ = cfg.op == PoissonSettings::Op::Exact;
    nrows_ = (int)g.cellsOwned();
    // The CSR matrix: for the approximate operator, SGS, Jacobi and multigrid (which read its
    // entries), and projection.matrix_free: false. CG with fast diagonalization or none needs
    // only products, so the exact operator then has no matrix (~330 bytes a cell less).
    const bool matrixFree = exact_ && cfg.matrixFree;
    buildMap(g);
    if (!matrixFree || (cfg.preconditioner != "fast_diagonalization" && cfg.preconditioner != "none")) {
      buildGraph();
      A_ = Teuchos::rcp(new Matrix(graph_));
      A_->fillComplete();
    }
    b_ = Teuchos::rcp(new Vector(map_));
    x_ = Teuchos::rcp(new Vector(map_));
    x0_ = Teuchos::rcp(new Vector(map_));
    t_ = Teuchos::rcp(new Vector(map_));
    ident_ = RowFlags("poisson_identity_rows", nrows_);
    pattern_ = RowFlags("poisson_pattern", nrows_);
    Kokkos::deep_copy(pattern_, -1); // no pattern yet: the first setCoefficients finds the modes
    ns_ = std::make_unique<NullSpace>(geom_, rows_, nrows_, comm_);
    if (exact_ && cfg.preconditioner == "multigrid") buildNearNull();
    if (cfg.preconditioner == "fast_diagonalization") {
      if (!exact_)
        throw std::invalid_argument("projection.preconditioner: fast_diagonalization needs operator: exact");
      fd_ = std::make_unique<FastDiagonalization>(g, comm_, cfg.fdSingle);
    }
    if (matrixFree) mf_ = Teuchos::rcp(new MatrixFreeOperator(g, map_, ident_));
    op_ = mf_.is_null() ? Teuchos::RCP<const Operator>(A_) : Teuchos::RCP<const Operator>(mf_);
    buildSolver();
  }

  void setCoefficients(const VecField& coef) override {
    const double t0 = MPI_Wtime();
    if (!A_.is_null()) A_->resumeFill();
    const bool patternChanged = fillValues(coef);
    if (!A_.is_null()) A_->fillComplete();
    if (!mf_.is_null()) mf_->setCoefficients(coef);
    auto applyA = [this](const RowVector& in, const RowVector& out) {
      Kokkos::deep_copy(devView(*x_), in);
      op_->apply(*x_, *t_);
      Kokkos::deep_copy(out, devView(*t_));
    };
    if (patternChanged) ns_->rebuild(ident_, applyA, anorm_); // null(A) depends on the pattern only
    if (ifpack_) ifpack_->compute();
    if (fd_ && patternChanged) fd_->setup(coef); // which faces keep node rows
    if (cfg_.preconditioner == "multigrid") {
      // Reused set-up (projection.multigrid_reuse) was built for the old zero pattern,
      // whose identity rows and null space it may encode: rebuild when that changes, and
      // every multigrid_refresh updates.
      const bool refresh = (cfg_.multigridRefresh > 0 && sinceBuild_ + 1 >= cfg_.multigridRefresh) || rebuildDue_;
      if (muelu_.is_null() || (cfg_.multigridReuse != "none" && (patternChanged || refresh))) {
        Teuchos::ParameterList p = multigridParameters(cfg_, exact_, nearNull_);
        muelu_ = MueLu::CreateTpetraPreconditioner(Teuchos::RCP<Operator>(A_), p);
        problem_->setLeftPrec(Teuchos::rcp(new ProjectedPrec(muelu_, ns_.get())));
        sinceBuild_ = 0;
        baseIts_ = -1;
        rebuildDue_ = false;
      } else {
        MueLu::ReuseTpetraPreconditioner(A_, *muelu_);
        ++sinceBuild_;
      }
    }
    pendingSetup_ += MPI_Wtime() - t0;
    ready_ = true;
  }

  PoissonStats solve(const Field& rhs, const Field& x, double floor) override {
    if (!ready_) throw std::logic_error("PoissonSolver::solve before setCoefficients");
    const double t0 = MPI_Wtime();
    PoissonStats st;
    st.nullModes = ns_->dimension();
    fieldToVec(rhs, *b_, rows_, cells_, ident_);
    fieldToVec(x, *x_, rows_, cells_, ident_);
    const double b0 = b_->norm2();
    // Compatibility: rhs must lie in range(A) = null(A)^perp; say how far it was.
    st.incompatibility = b0 > 0 ? ns_->remove(devView(*b_)) / b0 : 0.0;
    double bn = b_->norm2();
    if (bn < 0.5 * b0) { // mostly null: the null part left by round-off, eps ||b0||, is not
      ns_->remove(devView(*b_)); // small against tol ||b||; CG would stagnate, then diverge
      bn = b_->norm2();
    }
    ns_->remove(devView(*x_));
    // Initial guess: x0 or 0, whichever has the smaller residual. x0 is usually
    // the previous increment; when it is worse than 0 (rest after a transient),
    // CG would have to reduce ||r0|| >> ||b|| below tol ||b||, beyond round-off.
    double rn = residual();
    if (!(rn <= bn)) {
      x_->putScalar(0);
      rn = bn;
    }
    if (bn <= kRoundoff * std::max(anorm_ * x_->norm2(), b0) || bn <= floor) {
      // b is at round-off relative to A x (or to its own null part): the
      // increment is below what double precision resolves; or below the caller's
      // absolute floor (a resting flow whose rhs is round-off of cancelled terms). Keep x.
      st.relResidual = bn > 0 ? rn / bn : 0.0;
      st.converged = true;
    } else {
      Tpetra::deep_copy(*x0_, *x_);
      problem_->setProblem(x_, b_);
      solver_->setProblem(problem_);
      bool belosConverged = false;
      const long applies0 = counted_->count;
      try {
        belosConverged = solver_->solve() == Belos::Converged;
        st.iterations = solver_->getNumIters();
      } catch (const std::exception&) {
        // CG breakdown (p^T A p <= 0, round-off): x holds the last iterate.
        st.breakdowns = 1;
        st.iterations = int(counted_->count - applies0); // getNumIters() is stale here
      }
      zeroIdentityRows(*x_);     // a multigrid correction may leak into them
      ns_->remove(devView(*x_)); // the preconditioner may feed null modes into x
      st.relResidual = residual() / bn;
      if (!belosConverged && !(st.relResidual * bn <= rn)) { // worse than the guess: keep it
        Tpetra::deep_copy(*x_, *x0_);
        st.relResidual = rn / bn;
      }
      st.converged = st.breakdowns ? st.relResidual <= 10 * cfg_.tolerance : belosConverged;
      // Aged reused multigrid levels (projection.multigrid_rebuild_growth): the first solve
      // after a full build sets the base; a solve that needs clearly more asks for a rebuild.
      if (!muelu_.is_null() && cfg_.multigridReuse != "none" && cfg_.multigridRebuildGrowth > 0) {
        if (baseIts_ < 0) baseIts_ = st.iterations;
        else if (st.iterations > baseIts_ * (1 + cfg_.multigridRebuildGrowth) + 1) rebuildDue_ = true;
      }
    }
    vecToField(*x_, x, rows_, cells_);
    st.seconds = MPI_Wtime() - t0;
    st.setupSeconds = pendingSetup_;
    pendingSetup_ = 0;
    return st;
  }

  void apply(const Field& x, const Field& y) override {
    fieldToVec(x, *x_, rows_, cells_, RowFlags());
    op_->apply(*x_, *t_);
    vecToField(*t_, y, rows_, cells_);
  }

  // 0 without a matrix (matrix-free exact operator with fast diagonalization or none).
  long long globalNonzeros() const override { return A_.is_null() ? 0 : (long long)A_->getGlobalNumEntries(); }
  std::array<int, 2> fdRankGrid() const override { return fd_ ? fd_->rankGrid() : std::array<int, 2>{0, 0}; }
  int nullModeCount() const override { return ns_->dimension(); }

 private:
  // Global column of cell (gi,gj,gk) + offset, wrapped on periodic axes; -1 outside.
  GO column(const int gc0[3], int o) const {
    const int off[3] = {o % 3 - 1, (o / 3) % 3 - 1, o / 9 - 1};
    long long c[3];
    for (int d = 0; d < 3; ++d) {
      int v = gc0[d] + off[d];
      if (geom_.per[d]) v = ((v % geom_.n[d]) + geom_.n[d]) % geom_.n[d];
      else if (v < 0 || v >= geom_.n[d]) return -1;
      c[d] = v;
    }
    return (GO)(c[0] + (long long)geom_.n[0] * (c[1] + (long long)geom_.n[1] * c[2]));
  }
  bool inStencil(int o) const {
    const int a = std::abs(o % 3 - 1) + std::abs((o / 3) % 3 - 1) + std::abs(o / 9 - 1);
    return exact_ || a <= 1;
  }

  // Row Map: one row per owned cell, the global cell index as its id.
  void buildMap(const Grid& g) {
    std::vector<GO> gids(nrows_);
    for (int r = 0; r < nrows_; ++r) {
      int i, j, k;
      rows_.cell(r, i, j, k);
      const int gc[3] = {geom_.glob(0, i), geom_.glob(1, j), geom_.glob(2, k)};
      gids[r] = column(gc, kCentre);
    }
    map_ = Teuchos::rcp(new Map((Tpetra::global_size_t)g.cellsGlobal(), Teuchos::ArrayView<const GO>(gids),
                                0, tcomm_));
  }

  // Graph (built once) and the slot table: slot(r, o) = index into the local values array
  // of row r's entry for offset o (-1 when absent).
  void buildGraph() {
    graph_ = Teuchos::rcp(new Graph(map_, exact_ ? 27 : 7));
    std::vector<GO> cols;
    for (int r = 0; r < nrows_; ++r) {
      int i, j, k;
      rows_.cell(r, i, j, k);
      const int gc[3] = {geom_.glob(0, i), geom_.glob(1, j), geom_.glob(2, k)};
      cols.clear();
      for (int o = 0; o < kStencil; ++o)
        if (inStencil(o) && column(gc, o) >= 0) cols.push_back(column(gc, o));
      std::sort(cols.begin(), cols.end()); // periodic n < 3: offsets alias
      cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
      graph_->insertGlobalIndices(map_->getGlobalElement(r), Teuchos::ArrayView<const GO>(cols));
    }
    graph_->fillComplete();
    slot_ = SlotView("poisson_slots", nrows_, kStencil);
    auto hs = hostMirror(slot_);
    auto lg = graph_->getLocalGraphHost();
    auto colMap = graph_->getColMap();
    for (int r = 0; r < nrows_; ++r) {
      int i, j, k;
      rows_.cell(r, i, j, k);
      const int gc[3] = {geom_.glob(0, i), geom_.glob(1, j), geom_.glob(2, k)};
      for (int o = 0; o < kStencil; ++o) {
        hs(r, o) = -1;
        const GO c = inStencil(o) ? column(gc, o) : -1;
        if (c < 0) continue;
        const LO lc = colMap->getLocalElement(c);
        for (auto p = lg.row_map(r); p < lg.row_map(r + 1); ++p)
          if (lg.entries(p) == lc) hs(r, o) = (int)p;
      }
    }
    toDevice(slot_, hs, "solver_setup");
  }

  // Values from coef (assemblePoisson); sets anorm_ = ||A||_inf and returns whether the
  // zero pattern changed, globally.
  // Without a matrix (A_ null) only the pattern, the identity rows and a bound on ||A||
  // within 8x (poissonRowPattern).
  bool fillValues(const VecField& coef) {
    Kokkos::View<int, MemSpace> changed("poisson_pattern_changed");
    double amax;
    if (!A_.is_null()) {
      auto lcl = A_->getLocalMatrixDevice();
      amax = assemblePoisson(lcl.values, lcl.graph.row_map, slot_, ident_, pattern_, geom_, rows_, exact_, coef,
                             nrows_, changed);
    } else {
      amax = poissonRowPattern(ident_, pattern_, geom_, rows_, coef, nrows_, changed);
    }
    Kokkos::fence();
    MPI_Allreduce(&amax, &anorm_, 1, MPI_DOUBLE, MPI_MAX, comm_);
    int any = 0;
    Kokkos::deep_copy(any, changed);
    MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, comm_);
    return any != 0;
  }

  // Multigrid near-null space of the exact operator: the constant and the checkerboard
  // (-1)^(i+j+k) in global cell indices (the same on any decomposition).
  void buildNearNull() {
    nearNull_ = Teuchos::rcp(new MV(map_, 2));
    auto h = nearNull_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int r = 0; r < nrows_; ++r) {
      int i, j, k;
      rows_.cell(r, i, j, k);
      h(r, 0) = 1.0;
      h(r, 1) = ((geom_.glob(0, i) + geom_.glob(1, j) + geom_.glob(2, k)) & 1) ? -1.0 : 1.0;
    }
  }

  void zeroIdentityRows(Vector& v) const { voigt::zeroIdentityRows(devView(v), ident_, nrows_); }

  double residual() { // ||b - A x||, t = b - A x
    op_->apply(*x_, *t_);
    t_->update(1.0, *b_, -1.0);
    return t_->norm2();
  }

  void buildSolver() {
    auto bp = Teuchos::parameterList();
    bp->set("Convergence Tolerance", cfg_.tolerance);
    bp->set("Maximum Iterations", cfg_.maxIterations);
    // Default scales by the initial residual, wrong when x starts from the previous pressure.
    bp->set("Implicit Residual Scaling", std::string("Norm of RHS"));
    bp->set("Verbosity", (int)Belos::Errors);
    bp->set("Output Frequency", -1);
    Belos::SolverFactory<Scalar, MV, Operator> factory;
    solver_ = factory.create("PSEUDOBLOCK CG", bp);
    counted_ = Teuchos::rcp(new CountedOperator(op_));
    problem_ = Teuchos::rcp(new Problem(counted_, x_, b_));
    const std::string& pc = cfg_.preconditioner;
    if (pc == "sgs" || pc == "jacobi") {
      using RowMatrix = Tpetra::RowMatrix<Scalar, LO, GO, Node>;
      ifpack_ = Ifpack2::Factory::create<RowMatrix>("RELAXATION", Teuchos::RCP<const RowMatrix>(A_));
      Teuchos::ParameterList p;
      p.set("relaxation: type", std::string(pc == "sgs" ? "Symmetric Gauss-Seidel" : "Jacobi"));
      p.set("relaxation: sweeps", cfg_.sweeps);
      p.set("relaxation: damping factor", cfg_.damping);
      ifpack_->setParameters(p);
      ifpack_->initialize(); // graph only; compute() per setCoefficients
      problem_->setLeftPrec(Teuchos::rcp(new ProjectedPrec(ifpack_, ns_.get())));
    } else if (pc == "fast_diagonalization") {
      problem_->setLeftPrec(
          Teuchos::rcp(new ProjectedPrec(Teuchos::rcp(new FastDiagPrec(map_, fd_.get(), ident_)), ns_.get())));
    } else if (pc != "none" && pc != "multigrid") {
      throw std::invalid_argument("projection.preconditioner: unknown '" + pc +
                                  "' (sgs | jacobi | none | multigrid | fast_diagonalization)");
    }
    // MueLu's "full" (and "emin", for the emin algorithm only) are left out: "full" keeps
    // the fine-level smoother, whose stored inverse diagonal goes stale while A changes
    // in place; with a moving density jump CG then breaks down at once.
    const std::string& mr = cfg_.multigridReuse;
    if (mr != "none" && mr != "S" && mr != "tP" && mr != "RP" && mr != "RAP")
      throw std::invalid_argument("projection.multigrid_reuse: unknown '" + mr + "' (none | S | tP | RP | RAP)");
    if (cfg_.multigridSmoother != "sgs" && cfg_.multigridSmoother != "chebyshev")
      throw std::invalid_argument("projection.multigrid_smoother: unknown '" + cfg_.multigridSmoother +
                                  "' (sgs | chebyshev)");
    if (cfg_.multigridRefresh < 0)
      throw std::invalid_argument("projection.multigrid_refresh: must be >= 0");
  }

  GridGeom geom_;
  CellRows rows_;
  Range3 cells_;
  PoissonSettings cfg_;
  bool exact_ = true, ready_ = false;
  int nrows_ = 0;
  MPI_Comm comm_ = MPI_COMM_NULL; // the duplicate held by tcomm_
  Teuchos::RCP<const Teuchos::Comm<int>> tcomm_;
  Teuchos::RCP<const Map> map_;
  Teuchos::RCP<Graph> graph_;
  Teuchos::RCP<Matrix> A_;                 // null without a matrix (see the constructor)
  Teuchos::RCP<MatrixFreeOperator> mf_; // exact operator, projection.matrix_free
  Teuchos::RCP<const Operator> op_;      // what CG multiplies by: mf_ or A_
  Teuchos::RCP<Vector> b_, x_, x0_, t_;
  Teuchos::RCP<MV> nearNull_;  // exact operator + multigrid: MueLu's near-null space (2 vectors)
  SlotView slot_;
  RowFlags ident_;
  RowFlags pattern_;          // per row: bit 3 corner + d set when coef_d(corner) != 0 (fillValues)
  double anorm_ = 0;          // ||A||_inf
  std::unique_ptr<NullSpace> ns_;
  std::unique_ptr<FastDiagonalization> fd_; // preconditioner fast_diagonalization
  Teuchos::RCP<CountedOperator> counted_; // A as Belos sees it
  Teuchos::RCP<Ifpack2::Preconditioner<Scalar, LO, GO, Node>> ifpack_;
  Teuchos::RCP<MueLu::TpetraOperator<Scalar, LO, GO, Node>> muelu_;
  Teuchos::RCP<Problem> problem_;
  Teuchos::RCP<Solver> solver_;
  int baseIts_ = -1;          // iterations of the first solve after the last full build
  bool rebuildDue_ = false;   // a solve took clearly more: rebuild at the next update
  int sinceBuild_ = 0;        // ReuseTpetraPreconditioner calls since the last full multigrid build
  double pendingSetup_ = 0;   // setCoefficients() seconds not yet reported by solve()
};

} // namespace

std::unique_ptr<PoissonSolver> makePoissonSolver(const Grid& g, const PoissonSettings& cfg) {
  return std::make_unique<TpetraPoisson>(g, cfg);
}

} // namespace voigt
