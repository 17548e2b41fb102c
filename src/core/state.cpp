#include "core/state.hpp"

#include "core/field_names.hpp"

namespace voigt {

void exchangeVelocity(State& st) {
  if (st.velocityHalosCurrent) return;
  st.halo->exchange(st.fields.vector(field::velocity));
  st.velocityHalosCurrent = true;
}

} // namespace voigt
