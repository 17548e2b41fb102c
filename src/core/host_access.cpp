// The host-touch check and the copy counters: see host_access.hpp.
#include "core/host_access.hpp"

#include <execinfo.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace voigt::host_access {

namespace {

struct Region {
  char name[64];
  const char* data;  // the field's first element
  std::size_t bytes; // its span
  char* lo;          // the whole pages inside [data, data + bytes): what is protected
  char* hi;
  bool open;         // opened by a kernel's first touch; closed when the last kernel ends
};

// Single-threaded by construction (Serial backend; the check is for that build).
std::vector<Region> regions;
bool isArmed = false, pages = false;
int depth = 0; // kernels and deep copies in flight (they nest: deep_copy runs a kernel)
long long nKernels = 0, nDeepCopies = 0;
std::map<std::string, Copies> copyCounts;
std::map<std::string, StageWork> work; // by pipeline stage; "" between stages
std::string currentStage;               // the stage counted now
StageWork* current = nullptr;           // work[currentStage]
// Page mode: the pages a top-level kernel opened (reserved at arm(): the fault handler
// must not allocate); at its end they are counted and closed.
std::vector<char*> openPages;
std::size_t pageSize = 4096;

void setAccess(const Region& r, bool open) {
  if (r.hi > r.lo) mprotect(r.lo, std::size_t(r.hi - r.lo), open ? PROT_READ | PROT_WRITE : PROT_NONE);
}

// Regions open lazily: a kernel's first touch of a closed one faults, and the handler opens
// it (onFault); the last kernel to end closes what was opened. A kernel touches a few fields,
// so this costs a few mprotect calls a kernel instead of two per registered array.
void enter() { ++depth; }

void leave() {
  if (depth <= 0 || --depth > 0) return;
  for (Region& r : regions)
    if (r.open) setAccess(r, false), r.open = false;
  if (openPages.empty()) return;
  current->bytes += (long long)(openPages.size() * pageSize);
  std::sort(openPages.begin(), openPages.end());
  for (std::size_t i = 0; i < openPages.size();) { // close runs of adjacent pages at once
    std::size_t j = i + 1;
    while (j < openPages.size() && openPages[j] == openPages[j - 1] + pageSize) ++j;
    mprotect(openPages[i], (j - i) * pageSize, PROT_NONE);
    i = j;
  }
  openPages.clear();
}

void beginKernel(const char*, const uint32_t, uint64_t*) {
  ++nKernels;
  if (depth == 0) ++current->kernels;
  enter();
}
void endKernel(uint64_t) { leave(); }
void beginCopy(Kokkos_Profiling_SpaceHandle, const char*, const void*, Kokkos_Profiling_SpaceHandle, const char*,
               const void*, uint64_t) {
  ++nDeepCopies;
  enter();
}
void endCopy() { leave(); }

// Kokkos reports the allocation's start (its header) or its data: either way a field's data
// lies within a header's length of [ptr, ptr + size].
void deallocated(Kokkos_Profiling_SpaceHandle, const char*, const void* ptr, uint64_t size) {
  const char* p = static_cast<const char*>(ptr);
  for (std::size_t i = 0; i < regions.size();) {
    if (regions[i].data >= p && regions[i].data <= p + size + 256) {
      const Region& r = regions[i];
      if (!r.open) setAccess(r, true);
      openPages.erase(std::remove_if(openPages.begin(), openPages.end(),
                                     [&](char* q) { return q >= r.lo && q < r.hi; }),
                      openPages.end()); // never close pages the allocator gets back
      regions.erase(regions.begin() + long(i));
    } else {
      ++i;
    }
  }
}

void say(const char* s) {
  ssize_t ignored = write(STDERR_FILENO, s, std::strlen(s));
  (void)ignored;
}

void onFault(int sig, siginfo_t* info, void*) {
  const char* a = static_cast<const char*>(info->si_addr);
  for (Region& r : regions) {
    if (a < r.lo || a >= r.hi) continue;
    if (depth > 0) { // inside a kernel or a deep copy: open it (or the page) and retry
      if (pages && openPages.size() < openPages.capacity()) {
        char* page = r.lo + std::size_t(a - r.lo) / pageSize * pageSize;
        mprotect(page, pageSize, PROT_READ | PROT_WRITE);
        openPages.push_back(page);
      } else {
        setAccess(r, true);
        r.open = true;
      }
      return;
    }
    say("voigt: host-touch check: host code touched field '");
    say(r.name);
    say("' outside a Kokkos kernel, a deep_copy or toHost/toDevice (core/host_access.hpp); on a "
        "device this is a fault or a silent page migration. Backtrace (addr2line -Cfe PROGRAM +OFFSET "
        "names a frame):\n");
    void* frames[64];
    backtrace_symbols_fd(frames, backtrace(frames, 64), STDERR_FILENO);
    _exit(kHostTouchExit);
  }
  signal(sig, SIG_DFL); // not ours: fault again, the default way
}

} // namespace

void arm(bool countPages) {
  if (isArmed) return;
  isArmed = true;
  pages = countPages;
  pageSize = std::size_t(sysconf(_SC_PAGESIZE));
  openPages.reserve(1 << 20);
  current = &work[currentStage];
  namespace kt = Kokkos::Tools::Experimental;
  kt::set_begin_parallel_for_callback(beginKernel);
  kt::set_end_parallel_for_callback(endKernel);
  kt::set_begin_parallel_reduce_callback(beginKernel);
  kt::set_end_parallel_reduce_callback(endKernel);
  kt::set_begin_parallel_scan_callback(beginKernel);
  kt::set_end_parallel_scan_callback(endKernel);
  kt::set_begin_deep_copy_callback(beginCopy);
  kt::set_end_deep_copy_callback(endCopy);
  kt::set_deallocate_data_callback(deallocated);
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_sigaction = onFault;
  sa.sa_flags = SA_SIGINFO;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGSEGV, &sa, nullptr);
  sigaction(SIGBUS, &sa, nullptr);
}

bool armed() { return isArmed; }

bool armFromEnvironment() {
  const char* v = std::getenv("VOIGT_HOST_TOUCH_CHECK");
  if (v && *v && std::strcmp(v, "0") != 0) arm(std::strcmp(v, "pages") == 0);
  return isArmed;
}

void registerField(const std::string& name, const void* data, std::size_t bytes) {
  if (!isArmed || !data || bytes == 0 || isField(data)) return;
  const std::uintptr_t page = std::uintptr_t(pageSize);
  const std::uintptr_t b = std::uintptr_t(data), e = b + bytes;
  Region r{};
  std::strncpy(r.name, name.c_str(), sizeof r.name - 1);
  r.data = static_cast<const char*>(data);
  r.bytes = bytes;
  r.lo = reinterpret_cast<char*>((b + page - 1) / page * page);
  r.hi = reinterpret_cast<char*>(e / page * page);
  if (r.hi <= r.lo) return; // smaller than a page: nothing of its own to protect
  r.open = depth > 0; // registered inside a kernel: leave() closes it
  regions.push_back(r);
  if (!r.open) setAccess(regions.back(), false);
}

bool isField(const void* data) {
  for (const Region& r : regions)
    if (static_cast<const char*>(data) >= r.data && static_cast<const char*>(data) < r.data + r.bytes) return true;
  return false;
}

const std::map<std::string, Copies>& copies() { return copyCounts; }
const std::map<std::string, StageWork>& stageWork() { return work; }
bool countsPages() { return pages; }
std::string setStage(const std::string& stage) {
  if (!isArmed) return "";
  std::string was = std::move(currentStage);
  currentStage = stage;
  current = &work[stage];
  return was;
}
long long kernels() { return nKernels; }
long long deepCopies() { return nDeepCopies; }
void reset() {
  copyCounts.clear();
  nKernels = nDeepCopies = 0;
  work.clear();
  current = &work[currentStage];
}

void countCopy(const char* why, std::size_t bytes) {
  Copies& c = copyCounts[why];
  ++c.count;
  c.bytes += (long long)bytes;
}

} // namespace voigt::host_access
