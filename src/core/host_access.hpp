#pragma once
// Explicit copies between the fields (device memory: Kokkos::CudaSpace in a CUDA build,
// field.hpp) and the host, and the check that a step touches no field from the host
// otherwise (issue 55, "device-resident step").
//
// toHost/toDevice are the only way host code reads or writes a field: on a device they
// copy, on the host they alias (create_mirror_view), and every call is counted by reason
// (summary.json "host_copies"), so a run shows what crosses the bus and how often.
//
// The host-touch check (VOIGT_HOST_TOUCH_CHECK=1, or arm()) makes the Serial build behave
// as if fields lived in device memory: the pages of every FieldStore field and guard()-ed
// device array are mprotect-ed PROT_NONE; while a Kokkos kernel (parallel_for/reduce/scan)
// or a deep_copy runs (Kokkos Tools callbacks say when), a touch opens the array until the
// kernel ends; toHost/toDevice make real copies. Host code that dereferences one anywhere
// else faults, and the handler names it and prints a backtrace before the process exits
// with kHostTouchExit. The pages at the two ends of an array that it shares with other data
// stay open (at most 4 KiB each end).
//
// VOIGT_HOST_TOUCH_CHECK=pages opens single pages instead of whole arrays and counts, per
// pipeline stage, the pages each kernel touched (summary.json host_touch_check.per_stage):
// the bytes the stage's kernels stream through memory, counted at 4 KiB granularity (read
// and written alike, each page once a kernel), for the arrays Voigt owns (not Tpetra's or
// Belos' vectors). Slow (a fault per page per kernel): small grids, a few steps.
#include <Kokkos_Core.hpp>

#include <cstddef>
#include <map>
#include <string>

namespace voigt {

namespace host_access {

constexpr int kHostTouchExit = 86;

// Turns the check on (idempotent): Kokkos must be initialised. Fields allocated before
// this are not protected. countPages: the page mode above.
void arm(bool countPages = false);
bool countsPages();
bool armed();
// arm() if VOIGT_HOST_TOUCH_CHECK is set to anything but "" or "0"; returns armed().
bool armFromEnvironment();

// A field's storage (FieldStore::allocate): protected from now on while armed. It stays
// registered until Kokkos frees it (deallocate callback).
void registerField(const std::string& name, const void* data, std::size_t bytes);
bool isField(const void* data);

struct Copies {
  long long count = 0, bytes = 0;
};
// Every toHost/toDevice since the start (or reset), by reason.
const std::map<std::string, Copies>& copies();
// Kernels and deep copies Kokkos reported while armed (zero otherwise).
long long kernels();
long long deepCopies();
void reset();

// Kernels launched (top level) and, in page mode, bytes touched, per pipeline stage
// (Pipeline::run names the stage; "" is everything between stages: setup, output, checks).
struct StageWork {
  long long kernels = 0, bytes = 0;
};
// Returns the stage it replaces (stages nest: momentum runs stress and forces).
std::string setStage(const std::string& stage);
const std::map<std::string, StageWork>& stageWork();

void countCopy(const char* why, std::size_t bytes);

} // namespace host_access

// Device scratch arrays beside the fields (a solver's work buffers, an effect's scratch
// grids) join the check the same way; a no-op unless armed.
template <class V>
void guard(const V& v) {
  host_access::registerField(v.label(), v.data(), v.span() * sizeof(typename V::value_type));
}

// A host buffer for a device view's data (staging for MPI, no copy made): on a device a
// separate allocation; on the host the view itself, except under the check for a guarded
// view, where it is separate as on a device.
template <class V>
typename V::HostMirror hostMirror(const V& v) {
  if (host_access::armed() && host_access::isField(v.data())) return Kokkos::create_mirror(v);
  return Kokkos::create_mirror_view(v);
}

// A host copy of a device view (a field or any device array) for host code: counted under
// `why`. Armed and a field: a separate allocation (the emulated device copy).
template <class V>
typename V::HostMirror toHost(const V& v, const char* why) {
  host_access::countCopy(why, v.span() * sizeof(typename V::value_type));
  auto h = hostMirror(v);
  Kokkos::deep_copy(h, v); // no-op where h aliases v
  return h;
}

// Writes a host copy (from toHost) back to the device view: counted under `why`.
template <class V, class H>
void toDevice(const V& v, const H& h, const char* why) {
  host_access::countCopy(why, v.span() * sizeof(typename V::value_type));
  Kokkos::deep_copy(v, h);
}

} // namespace voigt
