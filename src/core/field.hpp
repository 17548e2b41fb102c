#pragma once
// Field storage. Every field is a Kokkos View over the local index space of
// grid.hpp (owned + ghosts), LayoutLeft so x is fastest, as in the HDF5 files.
#include <Kokkos_Core.hpp>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace voigt {

using ExecSpace = Kokkos::DefaultExecutionSpace;
// Math that device code may call (sqrt, fabs, pow, ...): Kokkos 3's Experimental
// namespace, Kokkos 4's own. On the host these are std::'s (same results).
#if KOKKOS_VERSION >= 40000
namespace km = Kokkos;
#else
namespace km = Kokkos::Experimental;
#endif
// max/min inline: the same bits as std::fmax/fmin for every pair of non-NaN doubles,
// signed zeros included (glibc's fmax is maxsd, which returns b on ties: checked), but
// no call through the PLT, which GCC emits for fmax/fmin without -ffinite-math-only
// (15 calls per cell in the re-initialisation stage). They differ only when b is NaN.
KOKKOS_INLINE_FUNCTION double maxOf(double a, double b) { return a > b ? a : b; }
KOKKOS_INLINE_FUNCTION double minOf(double a, double b) { return a < b ? a : b; }
// Fields live in device memory. Trilinos 13.2's Tpetra makes Kokkos::Cuda's default memory
// space CudaUVMSpace (managed memory, pages that migrate when host code touches them), so a
// CUDA build names CudaSpace; host code reaches fields only through toHost/toDevice
// (core/host_access.hpp), and Tpetra's UVM views assign to CudaSpace views.
#if defined(KOKKOS_ENABLE_CUDA)
using MemSpace = Kokkos::CudaSpace;
#else
using MemSpace = ExecSpace::memory_space;
#endif
using Field = Kokkos::View<double***, Kokkos::LayoutLeft, MemSpace>;
using IntField = Kokkos::View<int***, Kokkos::LayoutLeft, MemSpace>;

struct VecField {
  Field c[3];
  KOKKOS_INLINE_FUNCTION double& operator()(int d, int i, int j, int k) const { return c[d](i, j, k); }
};

enum class Centring { Cell, Node };

struct Grid;

// Named, lazily allocated fields. Effects declare what they need; nothing else
// is ever allocated (the brief: a field nobody asked for costs nothing).
class FieldStore {
 public:
  struct Decl {
    Centring centring;
    int components; // 1 scalar, 3 vector
    bool isInt;
    std::string owner; // effect that asked for it first
    // Recomputed from the state within every step before anything reads it (scratch,
    // coefficients, diagnostics): the per-step blow-up check leaves it out, the check
    // before anything is written includes it (StepEngine::checkFinite). A field that
    // any effect declares as state is state.
    bool derived = false;
    // State that a checkpoint written before the field existed may lack: a restart from
    // one leaves it zero (the owner's saved state says whether it is valid) instead of failing.
    bool optionalOnRestart = false;
  };

  void declare(const std::string& name, Centring c, int components, const std::string& owner,
               bool isInt = false);
  void declareDerived(const std::string& name, Centring c, int components, const std::string& owner);
  void markOptionalOnRestart(const std::string& name) { decls_.at(name).optionalOnRestart = true; }
  bool declared(const std::string& name) const { return decls_.count(name) > 0; }
  const std::map<std::string, Decl>& decls() const { return decls_; }
  // Bytes all declared fields take on this rank.
  long long bytes(const Grid& g) const;

  void allocate(const Grid& g); // allocate every declared field, zero-filled
  Field scalar(const std::string& name) const;
  VecField vector(const std::string& name) const;
  IntField integer(const std::string& name) const;
  bool allocated(const std::string& name) const;
  std::vector<std::string> allocatedNames() const;

 private:
  std::map<std::string, Decl> decls_;
  std::map<std::string, Field> scalars_;
  std::map<std::string, VecField> vectors_;
  std::map<std::string, IntField> ints_;
};

// Owned-index ranges as Kokkos policies (Cabana-style index spaces).
// Iterate Left: i fastest, matching LayoutLeft (the default follows the space's
// preferred layout, LayoutRight on host, which strides through memory).
using Policy3 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3, Kokkos::Iterate::Left, Kokkos::Iterate::Left>>;

} // namespace voigt
