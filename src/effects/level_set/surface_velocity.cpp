#include "effects/level_set/surface_velocity.hpp"

#include <cmath>

#include "core/field_names.hpp"
#include "core/halo.hpp"
#include "kernels/surface_velocity.hpp"

namespace voigt {

void declareSurfaceVelocity(FieldStore& f, const std::string& owner) {
  f.declareDerived("surface_velocity", Centring::Node, 3, owner);
  f.declareDerived("surface_velocity_tmp", Centring::Node, 3, owner);
  f.declareDerived("psi_node", Centring::Node, 1, owner);
}

VecField solidSurfaceVelocity(State& st, const Field& psi, double kappa, const IntList& layer) {
  const Grid& g = st.grid;
  const VecField u = st.fields.vector(field::velocity);
  VecField v = st.fields.vector("surface_velocity"), w = st.fields.vector("surface_velocity_tmp");
  const Field pn = st.fields.scalar("psi_node");
  const double h = g.h[0];
  surface_velocity::nodeLevels(psi, pn, nodeRange(g, 1));
  const int n = surface_velocity::listLayer(g, pn, -(kappa + h), nodeRange(g), layer);
  const int sweeps = 2 * int(std::ceil((kappa / h + 1) / 2)); // a layer each; even: the result in v
  const IntField mask = st.fields.integer(field::fixMask);
  exchangeVelocity(st);
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(v.c[c], u.c[c]), Kokkos::deep_copy(w.c[c], u.c[c]);
  for (int s = 0; s < sweeps; ++s) {
    const VecField& from = s % 2 == 0 ? v : w;
    if (s > 0) st.halo->exchange(from); // u's ghosts were current for the first
    surface_velocity::sweep(g, pn, mask, from, s % 2 == 0 ? w : v, layer, n);
  }
  st.halo->exchange(v);
  return v;
}

} // namespace voigt
