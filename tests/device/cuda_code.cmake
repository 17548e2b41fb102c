# VOIGT_CUDA_CODE: the GPU codes to embed instead of Kokkos's single -arch=sm_XX (machine code
# for sm_XX + its PTX), e.g. sm_80,sm_90,compute_80: Kokkos 3.4 knows no Hopper, but nvcc 13
# does, so an H200 gets sm_90 machine code and needs no JIT at start (device-check sets it).
# Included by this folder's project and by the top-level one (a Kokkos-CUDA Trilinos).
set(VOIGT_CUDA_CODE "" CACHE STRING "nvcc -code list replacing Kokkos's -arch=sm_XX (CUDA only)")

# Rewrites -arch=sm_XX in the compile options of those of Kokkos's targets that exist.
function(voigt_apply_cuda_code)
  if(NOT VOIGT_CUDA_CODE)
    return()
  endif()
  foreach(_t Kokkos::kokkoscore Kokkos::kokkos)
    if(NOT TARGET ${_t})
      continue()
    endif()
    get_target_property(_opts ${_t} INTERFACE_COMPILE_OPTIONS)
    if(_opts)
      string(REGEX REPLACE "-arch=sm_([0-9]+)" "-arch=compute_\\1;-code=${VOIGT_CUDA_CODE}" _opts "${_opts}")
      set_target_properties(${_t} PROPERTIES INTERFACE_COMPILE_OPTIONS "${_opts}")
    endif()
  endforeach()
  message(STATUS "CUDA codes: ${VOIGT_CUDA_CODE}")
endfunction()
