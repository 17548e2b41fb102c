#include "core/state.hpp"

#include "core/field_names.hpp"

namespace voigt {

void exchangeVelocity(State& st) {
  if (st.velocityHalosCurrent) return;
  st.halo->exchange(st.fields.vector(field::velocity));
  st.velocityHalosCurrent = true;
}

void exchangeWithVelocity(State& st, const Field& f) {
  if (st.velocityHalosCurrent) return st.halo->exchange(f);
  const VecField u = st.fields.vector(field::velocity);
  st.halo->exchange(std::vector<Field>{f, u.c[0], u.c[1], u.c[2]});
  st.velocityHalosCurrent = true;
}

} // namespace voigt
