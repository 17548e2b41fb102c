# Writes OUT (a C++ source with voigt::buildRevision() and voigt::buildIsa()) from the
# source tree's git state. Run at configure time and at every build (target
# voigt_revision); configure_file leaves OUT untouched when nothing changed, so a build
# after a commit recompiles this one file and relinks, and an unchanged tree nothing.
# Without git (a release tarball) the revision is "unknown".
set(rev "unknown")
find_program(_git git)
if(_git AND EXISTS "${SRC}/.git")
  execute_process(COMMAND "${_git}" -C "${SRC}" describe --always --dirty --abbrev=12
                  OUTPUT_VARIABLE _out OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc ERROR_QUIET)
  if(_rc EQUAL 0 AND _out)
    set(rev "${_out}")
  endif()
endif()
set(VOIGT_REVISION "${rev}")
set(VOIGT_ISA_TEXT "${ISA}")
configure_file("${SRC}/cmake/build_info.cpp.in" "${OUT}" @ONLY)
