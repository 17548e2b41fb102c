# Writes OUT (a C++ source with voigt::buildRevision() and voigt::buildIsa()) from the
# source tree's git state: the commit, 12 hex digits. Run at configure time and at every build (target
# voigt_revision); configure_file leaves OUT untouched when nothing changed, so a build
# after a commit recompiles this one file and relinks, and an unchanged tree nothing.
# Without git (a release tarball) the revision is "unknown".
set(rev "unknown")
find_program(_git git)
# "-dirty" when what the binary is built from differs from the commit: changed or untracked
# files under src/, kernels/, cmake/, CMakeLists.txt or tests/device/cuda_code.cmake (not the
# case ledgers and results that running studies rewrite).
if(_git AND EXISTS "${SRC}/.git")
  execute_process(COMMAND "${_git}" -C "${SRC}" rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE _out OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc ERROR_QUIET)
  if(_rc EQUAL 0 AND _out)
    set(rev "${_out}")
    # --no-optional-locks: a build must not take .git/index.lock from a commit made meanwhile.
    execute_process(COMMAND "${_git}" --no-optional-locks -C "${SRC}" status --porcelain --
                            src kernels cmake CMakeLists.txt tests/device/cuda_code.cmake
                    OUTPUT_VARIABLE _changed OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(_changed)
      set(rev "${rev}-dirty")
    endif()
  endif()
endif()
set(VOIGT_REVISION "${rev}")
set(VOIGT_ISA_TEXT "${ISA}")
configure_file("${SRC}/cmake/build_info.cpp.in" "${OUT}" @ONLY)
