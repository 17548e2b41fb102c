#pragma once
// What built this binary, for provenance: summary.json and every checkpoint record
// the revision of each run segment (a long run may continue on a newer build).

namespace voigt {
// `git describe --always --dirty --abbrev=12` of the source tree at build time
// ("unknown" without git). Generated: cmake/revision.cmake.
const char* buildRevision();
// The -march flags chosen by CMake's VOIGT_ARCH ("compiler default" if none).
const char* buildIsa();
} // namespace voigt
