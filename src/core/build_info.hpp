#pragma once
// What built this binary, for provenance: summary.json and every checkpoint record
// the revision of each run segment (a long run may continue on a newer build).

namespace voigt {
// The source tree's commit at build time (12 hex digits; "-dirty" when src/, kernels/,
// cmake/ or CMakeLists.txt differ from it; "unknown" without git). cmake/revision.cmake.
const char* buildRevision();
// The -march flags chosen by CMake's VOIGT_ARCH ("compiler default" if none).
const char* buildIsa();
} // namespace voigt
