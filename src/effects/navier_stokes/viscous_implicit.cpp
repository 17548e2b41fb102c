// Semi-implicit viscosity: CG with Jacobi on (M - dt K) d = dt K q, the three components in
// one iteration (one halo exchange and two reductions each). Equations and the stability
// argument: kernels/viscous_implicit.hpp.
#include "effects/navier_stokes/viscous_implicit.hpp"

#include <algorithm>
#include <cmath>

#include "core/field_names.hpp"
#include "core/halo.hpp"
#include "kernels/viscous_implicit.hpp"

namespace voigt {

namespace {
const char* const kEdge = "viscous_edge";
const char* const kMass = "viscous_mass";
const char* const kInvDiag = "viscous_inv_diagonal";
const char* const kVectors[4] = {"viscous_solution", "viscous_residual", "viscous_direction", "viscous_product"};

void sum2(const Grid& g, viscous::TwoSums& s) {
  double in[2] = {s.a, s.b}, out[2];
  MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_SUM, g.comm);
  s.a = out[0], s.b = out[1];
}
} // namespace

void ImplicitViscosity::declareFields(FieldStore& f, const std::string& owner) {
  f.declareDerived(kEdge, Centring::Node, 3, owner);
  f.declareDerived(kMass, Centring::Node, 1, owner);
  f.declareDerived(kInvDiag, Centring::Node, 1, owner);
  for (const char* n : kVectors) f.declareDerived(n, Centring::Node, 3, owner);
}

VecField ImplicitViscosity::increment(State& st) { return st.fields.vector(kVectors[3]); }

void ImplicitViscosity::prepare(State& st) {
  const Grid& g = st.grid;
  VecField c = st.fields.vector(kEdge);
  // Ghosts beyond walls are never written (only owned nodes are computed, the halo fills the
  // rest), so zeroing once keeps the edges there 0 and the direction's ghosts finite.
  if (!zeroed_) {
    const VecField p = st.fields.vector(kVectors[2]);
    for (int d = 0; d < 3; ++d) Kokkos::deep_copy(c.c[d], 0.0), Kokkos::deep_copy(p.c[d], 0.0);
    zeroed_ = true;
  }
  viscous::edgeCoefficients(g, st.fields.scalar(field::viscosity), c, nodeRange(g));
  st.halo->exchange(c);
  viscous::massAndDiagonal(g, st.fields.scalar(field::density), c, st.dt, st.fields.scalar(kMass),
                           st.fields.scalar(kInvDiag), nodeRange(g));
}

void ImplicitViscosity::correct(State& st, const VecField& q, const VecField& u) {
  const Grid& g = st.grid;
  const Range3 nodes = nodeRange(g);
  const IntField mask = st.fields.integer(field::fixMask);
  const VecField c = st.fields.vector(kEdge);
  const Field m = st.fields.scalar(kMass), invDiag = st.fields.scalar(kInvDiag);
  const VecField x = st.fields.vector(kVectors[0]), r = st.fields.vector(kVectors[1]);
  const VecField p = st.fields.vector(kVectors[2]);
  const double dt = st.dt;
  st.halo->exchange(q);
  viscous::TwoSums s = viscous::startResidual(mask, c, invDiag, dt, q, r, x, p, nodes);
  sum2(g, s);
  const double bnorm = std::sqrt(s.a);
  int it = 0;
  double rz = s.b, rel = 0;
  // q is free once r holds dt K q: it takes the products A p.
  while (bnorm > 0 && it < kMaxIterations) {
    st.halo->exchange(p);
    double pq = viscous::applyOperator(mask, c, m, dt, p, q, nodes), pqg = 0;
    MPI_Allreduce(&pq, &pqg, 1, MPI_DOUBLE, MPI_SUM, g.comm);
    const double alpha = rz / pqg;
    s = viscous::updateIterate(invDiag, alpha, p, q, x, r, nodes);
    sum2(g, s);
    ++it;
    rel = std::sqrt(s.a) / bnorm;
    if (rel <= kTolerance) break;
    viscous::newDirection(invDiag, s.b / rz, r, p, nodes);
    rz = s.b;
  }
  if (bnorm > 0) viscous::addCorrection(x, 1.0, u, nodes);
  auto& k = st.counters;
  k["viscous_solves"] += 1;
  k["viscous_iterations"] += it;
  k["viscous_iterations_max"] = std::max(k["viscous_iterations_max"], double(it));
  if (rel > kTolerance) k["viscous_unconverged"] += 1;
}

} // namespace voigt
