# Every launcher of kernels/*.hpp (a line `inline <type> name(`) must be called in
# tests/device/kernels_*.cpp (kernels_all.cpp and its parts), so that the device-compile check instantiates every kernel
# (issue 25). Helpers with no dispatch of their own are listed in _voigt_not_launchers.
#   cmake -P tests/device/launchers.cmake        CTest device.launchers: fails, naming the missing
#   include(launchers.cmake); voigt_check_launchers(<mode>)   <mode>: WARNING (tests/device)
if(CMAKE_SCRIPT_MODE_FILE)
  cmake_minimum_required(VERSION 3.20) # script mode: IN_LIST, CMAKE_CURRENT_FUNCTION_LIST_DIR
endif()
# withLimiter, limiterNamed: host-side choices; scalarFacesXYZ, momentumStage: the shared
# bodies of launchers that are called (addNodeAdvectionFaces..., momentumStage1/2);
# mirror*GhostsAxis: the per-axis bodies that mirror*Ghosts instantiates for all three axes;
# reduce_rows, reduceRowsImpl: the row-wise reduction that kineticEnergy and solidMoments use.
# fdLinePairs: host backends only (on a device the same passes run one by one); tested bit for
# bit against them (tests/solvers, Poisson.FastDiagLinePairs).
set(_voigt_not_launchers withLimiter limiterNamed scalarFacesXYZ momentumStage flatSym mirrorNodeGhostsAxis
    mirrorCellGhostsAxis reduce_rows reduceRowsImpl fdLinePairs)
function(voigt_check_launchers mode)
  get_filename_component(_root "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../.." ABSOLUTE)
  file(GLOB _headers "${_root}/kernels/*.hpp")
  file(GLOB _parts "${_root}/tests/device/kernels_*.cpp")
  set(_calls "")
  foreach(_p IN LISTS _parts)
    file(READ "${_p}" _part)
    string(APPEND _calls "${_part}")
  endforeach()
  set(_missing "")
  foreach(_h IN LISTS _headers)
    file(STRINGS "${_h}" _lines REGEX "^inline [^(]* [A-Za-z_][A-Za-z0-9_]*\\(")
    foreach(_l IN LISTS _lines)
      string(REGEX REPLACE "^inline [^(]* ([A-Za-z_][A-Za-z0-9_]*)\\(.*" "\\1" _name "${_l}")
      if(_name IN_LIST _voigt_not_launchers)
        continue()
      endif()
      string(REGEX MATCH "[^A-Za-z0-9_]${_name}(<[^>]*>)?\\(" _hit "${_calls}")
      if(NOT _hit)
        get_filename_component(_f "${_h}" NAME)
        list(APPEND _missing "${_f}:${_name}")
      endif()
    endforeach()
  endforeach()
  if(_missing)
    message(${mode} "tests/device/kernels_all.cpp calls no ${_missing}: add a call, so that the "
      "device-compile check compiles it for the GPU (issue 25)")
  else()
    message(STATUS "tests/device/kernels_all.cpp calls every launcher of kernels/")
  endif()
endfunction()
if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  voigt_check_launchers(FATAL_ERROR)
endif()
