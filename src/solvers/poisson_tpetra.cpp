// Pressure Poisson solver on Tpetra + Belos CG + Ifpack2/MueLu (poisson.hpp).
// The only translation unit that includes Trilinos (besides trilinos_types.hpp).
#include <BelosSolverFactory.hpp>
#include <BelosSolverFactory_Tpetra.hpp>
#include <Ifpack2_Factory.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_DefaultMpiComm.hpp>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"
#include "solvers/poisson.hpp"
#include "solvers/trilinos_types.hpp"

namespace voigt {
namespace {

using namespace tpetra;
constexpr int kStencil = 27; // slot table width: offset o = (di+1) + 3 (dj+1) + 9 (dk+1)
constexpr int kCentre = 13;
using SlotView = Kokkos::View<int**, Kokkos::LayoutRight, MemSpace>;
using FlagView = Kokkos::View<int*, MemSpace>;

// Owned cell (local i,j,k) <-> row r; rows in local lexicographic order, i fastest.
struct Rows {
  int ng, n0, n1;
  KOKKOS_INLINE_FUNCTION int row(int i, int j, int k) const {
    return (i - ng) + n0 * ((j - ng) + n1 * (k - ng));
  }
  KOKKOS_INLINE_FUNCTION void cell(int r, int& i, int& j, int& k) const {
    i = ng + r % n0;
    j = ng + (r / n0) % n1;
    k = ng + r / (n0 * n1);
  }
};

auto devView(Vector& v) {
  return Kokkos::subview(v.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), 0);
}

// Field owned cells -> vector; identity rows zeroed when `ident` is non-empty.
void fieldToVec(const Field& f, Vector& v, Rows rw, Range3 cells, FlagView ident) {
  auto vv = devView(v);
  const bool zero = ident.extent(0) > 0;
  Kokkos::parallel_for(
      "poisson_field_to_vec", cells.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int r = rw.row(i, j, k);
        vv(r) = (zero && ident(r)) ? 0.0 : f(i, j, k);
      });
  Kokkos::fence();
}

void vecToField(Vector& v, const Field& f, Rows rw, Range3 cells) {
  auto vv = devView(v);
  Kokkos::parallel_for(
      "poisson_vec_to_field", cells.policy(),
      KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = vv(rw.row(i, j, k)); });
  Kokkos::fence();
}

class TpetraPoisson final : public PoissonSolver {
 public:
  TpetraPoisson(const Grid& g, const ProjectionCfg& cfg)
      : geom_(g), rows_{g.ng, g.ln[0], g.ln[1]}, cells_(cellRange(g)), cfg_(cfg) {
    MPI_Comm dup;
    MPI_Comm_dup(g.comm, &dup); // owned by Teuchos, freed with the last Map
    comm_ = dup;
    tcomm_ = Teuchos::rcp(new Teuchos::MpiComm<int>(Teuchos::opaqueWrapper(dup, MPI_Comm_free)));
    exact_ = cfg.op == ProjectionCfg::Op::Exact;
    nrows_ = (int)g.cellsOwned();
    buildGraph(g);
    A_ = Teuchos::rcp(new Matrix(graph_));
    A_->fillComplete();
    b_ = Teuchos::rcp(new Vector(map_));
    x_ = Teuchos::rcp(new Vector(map_));
    t_ = Teuchos::rcp(new Vector(map_));
    for (auto& v : pool_) v = Teuchos::rcp(new Vector(map_));
    ident_ = FlagView("poisson_identity_rows", nrows_);
    buildSolver();
  }

  void setCoefficients(const VecField& coef) override {
    A_->resumeFill();
    fillValues(coef);
    A_->fillComplete();
    findNullModes();
    if (ifpack_) ifpack_->compute();
    if (cfg_.preconditioner == "multigrid") {
      if (muelu_.is_null()) {
        Teuchos::ParameterList p;
        p.set("verbosity", "none");
        p.set("coarse: type", "RELAXATION"); // KLU2 fails on the singular operator
        auto& cp = p.sublist("coarse: params");
        cp.set("relaxation: type", "Symmetric Gauss-Seidel");
        cp.set("relaxation: sweeps", cfg_.sweeps);
        cp.set("relaxation: damping factor", cfg_.damping);
        muelu_ = MueLu::CreateTpetraPreconditioner(Teuchos::RCP<Operator>(A_), p);
        problem_->setLeftPrec(muelu_);
      } else {
        MueLu::ReuseTpetraPreconditioner(A_, *muelu_);
      }
    }
    ready_ = true;
  }

  PoissonStats solve(const Field& rhs, const Field& x) override {
    if (!ready_) throw std::logic_error("PoissonSolver::solve before setCoefficients");
    const double t0 = MPI_Wtime();
    PoissonStats st;
    st.nullModes = (int)modes_.size();
    fieldToVec(rhs, *b_, rows_, cells_, ident_);
    fieldToVec(x, *x_, rows_, cells_, ident_);
    projectOut(*b_); // compatibility: rhs must lie in range(A) = null(A)^perp
    projectOut(*x_);
    const double bn = b_->norm2();
    if (bn == 0) {
      x_->putScalar(0);
      st.converged = true;
    } else {
      problem_->setProblem(x_, b_);
      solver_->setProblem(problem_);
      try {
        st.converged = solver_->solve() == Belos::Converged;
      } catch (const std::exception& e) {
        fprintf(stderr, "CG EXC %s\n", e.what());
        st.converged = false; // CG breakdown: report, do not throw
      }
      st.iterations = solver_->getNumIters();
      zeroIdentityRows(*x_); // a multigrid correction may leak into them
      projectOut(*x_);       // the preconditioner may feed null modes into x
      A_->apply(*x_, *t_);
      t_->update(1.0, *b_, -1.0);
      st.relResidual = t_->norm2() / bn;
    }
    vecToField(*x_, x, rows_, cells_);
    st.seconds = MPI_Wtime() - t0;
    return st;
  }

  void apply(const Field& x, const Field& y) override {
    fieldToVec(x, *x_, rows_, cells_, FlagView());
    A_->apply(*x_, *t_);
    vecToField(*t_, y, rows_, cells_);
  }

  long long globalNonzeros() const override { return (long long)A_->getGlobalNumEntries(); }
  int nullModeCount() const override { return (int)modes_.size(); }

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

  // Row Map, graph (built once) and the slot table: slot(r, o) = index into the
  // local values array of row r's entry for offset o (-1 when absent).
  void buildGraph(const Grid& g) {
    std::vector<GO> gids(nrows_);
    for (int r = 0; r < nrows_; ++r) {
      int i, j, k;
      rows_.cell(r, i, j, k);
      const int gc[3] = {geom_.glob(0, i), geom_.glob(1, j), geom_.glob(2, k)};
      gids[r] = column(gc, kCentre);
    }
    map_ = Teuchos::rcp(new Map((Tpetra::global_size_t)g.cellsGlobal(), Teuchos::ArrayView<const GO>(gids),
                                0, tcomm_));
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
      graph_->insertGlobalIndices(gids[r], Teuchos::ArrayView<const GO>(cols));
    }
    graph_->fillComplete();
    slot_ = SlotView("poisson_slots", nrows_, kStencil);
    auto hs = Kokkos::create_mirror_view(slot_);
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
    Kokkos::deep_copy(slot_, hs);
  }

  void fillValues(const VecField& coef) {
    auto lcl = A_->getLocalMatrixDevice();
    auto vals = lcl.values;
    auto rowPtr = lcl.graph.row_map;
    auto slot = slot_;
    auto ident = ident_;
    const GridGeom G = geom_;
    const Rows rw = rows_;
    const bool exact = exact_;
    Kokkos::parallel_for(
        "poisson_fill", Kokkos::RangePolicy<ExecSpace>(0, nrows_), KOKKOS_LAMBDA(int r) {
          int l[3];
          rw.cell(r, l[0], l[1], l[2]);
          for (auto p = rowPtr(r); p < rowPtr(r + 1); ++p) vals(p) = 0;
          if (exact) {
            // A_{c,c'} = sum_{shared nodes n} sum_d coef_d(n)/w_n s_d(c,n) s_d(c',n) / (16 h_d^2)
            for (int cn = 0; cn < 8; ++cn) {
              const int a[3] = {cn & 1, (cn >> 1) & 1, (cn >> 2) & 1};
              const int n[3] = {l[0] + a[0], l[1] + a[1], l[2] + a[2]};
              const double w = G.nodeWeight(n[0], n[1], n[2]);
              double cf[3];
              for (int d = 0; d < 3; ++d)
                cf[d] = coef.c[d](n[0], n[1], n[2]) / (w * 16 * G.h[d] * G.h[d]) * (a[d] ? 1 : -1);
              if (cf[0] == 0 && cf[1] == 0 && cf[2] == 0) continue;
              for (int cm = 0; cm < 8; ++cm) {
                const int b[3] = {cm & 1, (cm >> 1) & 1, (cm >> 2) & 1}; // 1: c' on the high side of n
                bool exists = true;
                for (int d = 0; d < 3; ++d) exists = exists && G.cellExists(d, n[d] - 1 + b[d]);
                if (!exists) continue;
                double v = 0;
                for (int d = 0; d < 3; ++d) v += cf[d] * (b[d] ? -1 : 1);
                const int o = (a[0] + b[0]) + 3 * (a[1] + b[1]) + 9 * (a[2] + b[2]);
                vals(slot(r, o)) += v;
              }
            }
          } else {
            for (int d = 0; d < 3; ++d)
              for (int s = 0; s < 2; ++s) {
                double beta = 0; // mean coef_d over the face's 4 nodes
                for (int cn = 0; cn < 8; ++cn) {
                  const int a[3] = {cn & 1, (cn >> 1) & 1, (cn >> 2) & 1};
                  if (a[d] == s) beta += 0.25 * coef.c[d](l[0] + a[0], l[1] + a[1], l[2] + a[2]);
                }
                const double c = beta / (G.h[d] * G.h[d]);
                if (G.cellExists(d, l[d] + (s ? 1 : -1))) {
                  int o = kCentre + (s ? 1 : -1) * (d == 0 ? 1 : d == 1 ? 3 : 9);
                  vals(slot(r, o)) -= c;
                  vals(slot(r, kCentre)) += c;
                } else {
                  vals(slot(r, kCentre)) += 2 * c; // outflow: dp = 0 on the face; wall: beta = 0
                }
              }
          }
          bool empty = true;
          for (auto p = rowPtr(r); p < rowPtr(r + 1); ++p) empty = empty && vals(p) == 0;
          ident(r) = empty ? 1 : 0;
          if (empty) vals(slot(r, kCentre)) = 1; // all nodes prescribed: p is free, fix it to 0
        });
    Kokkos::fence();
  }

  // Candidate modes 1, (-1)^(i+j), (-1)^(j+k), (-1)^(k+i), (-1)^(i+j+k), zero on
  // identity rows; kept when numerically null, then orthonormalised.
  void findNullModes() {
    double dmax = 0;
    {
      auto lcl = A_->getLocalMatrixDevice();
      auto vals = lcl.values;
      auto slot = slot_;
      Kokkos::parallel_reduce(
          "poisson_maxdiag", Kokkos::RangePolicy<ExecSpace>(0, nrows_),
          KOKKOS_LAMBDA(int r, double& m) {
            const double v = vals(slot(r, kCentre));
            m = m > (v < 0 ? -v : v) ? m : (v < 0 ? -v : v);
          },
          Kokkos::Max<double>(dmax));
    }
    MPI_Allreduce(MPI_IN_PLACE, &dmax, 1, MPI_DOUBLE, MPI_MAX, comm_);
    modes_.clear();
    for (int m = 0; m < 5; ++m) {
      auto v = pool_[m];
      {
        auto vv = devView(*v);
        auto ident = ident_;
        const GridGeom G = geom_;
        const Rows rw = rows_;
        Kokkos::parallel_for(
            "poisson_mode", Kokkos::RangePolicy<ExecSpace>(0, nrows_), KOKKOS_LAMBDA(int r) {
              int l[3];
              rw.cell(r, l[0], l[1], l[2]);
              const int gi = G.glob(0, l[0]), gj = G.glob(1, l[1]), gk = G.glob(2, l[2]);
              const int e = m == 0 ? 0 : m == 1 ? gi + gj : m == 2 ? gj + gk : m == 3 ? gk + gi : gi + gj + gk;
              vv(r) = ident(r) ? 0.0 : ((e & 1) ? -1.0 : 1.0);
            });
        Kokkos::fence();
      }
      const double nv = v->norm2();
      if (nv == 0) continue;
      A_->apply(*v, *t_);
      if (t_->norm2() > 1e-10 * nv * dmax) continue;
      for (int pass = 0; pass < 2; ++pass)
        for (auto& q : modes_) v->update(-q->dot(*v), *q, 1.0);
      const double nq = v->norm2();
      if (nq <= 1e-8 * nv) continue; // dependent on the ones already kept
      v->scale(1.0 / nq);
      modes_.push_back(v);
    }
  }

  void zeroIdentityRows(Vector& v) const {
    auto vv = devView(v);
    auto ident = ident_;
    Kokkos::parallel_for(
        "poisson_zero_identity", Kokkos::RangePolicy<ExecSpace>(0, nrows_), KOKKOS_LAMBDA(int r) {
          if (ident(r)) vv(r) = 0;
        });
    Kokkos::fence();
  }

  void projectOut(Vector& v) const {
    for (auto& q : modes_) v.update(-q->dot(v), *q, 1.0);
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
    problem_ = Teuchos::rcp(new Problem(A_, x_, b_));
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
      problem_->setLeftPrec(ifpack_);
    } else if (pc != "none" && pc != "multigrid") {
      throw std::invalid_argument("projection.preconditioner: unknown '" + pc +
                                  "' (sgs | jacobi | none | multigrid)");
    }
  }

  GridGeom geom_;
  Rows rows_;
  Range3 cells_;
  ProjectionCfg cfg_;
  bool exact_ = true, ready_ = false;
  int nrows_ = 0;
  MPI_Comm comm_ = MPI_COMM_NULL; // the duplicate held by tcomm_
  Teuchos::RCP<const Teuchos::Comm<int>> tcomm_;
  Teuchos::RCP<const Map> map_;
  Teuchos::RCP<Graph> graph_;
  Teuchos::RCP<Matrix> A_;
  Teuchos::RCP<Vector> b_, x_, t_;
  SlotView slot_;
  FlagView ident_;
  Teuchos::RCP<Vector> pool_[5];          // candidate null modes (allocated once)
  std::vector<Teuchos::RCP<Vector>> modes_; // the kept ones, orthonormal
  Teuchos::RCP<Ifpack2::Preconditioner<Scalar, LO, GO, Node>> ifpack_;
  Teuchos::RCP<MueLu::TpetraOperator<Scalar, LO, GO, Node>> muelu_;
  Teuchos::RCP<Problem> problem_;
  Teuchos::RCP<Solver> solver_;
};

} // namespace

std::unique_ptr<PoissonSolver> makePoissonSolver(const Grid& g, const ProjectionCfg& cfg) {
  return std::make_unique<TpetraPoisson>(g, cfg);
}

} // namespace voigt
