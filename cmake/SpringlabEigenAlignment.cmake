# springlab_eigen_alignment(<max> <static>): EIGEN_MAX_ALIGN_BYTES and
# EIGEN_MAX_STATIC_ALIGN_BYTES as Eigen sets them under this build's compiler and flags (16
# and 16 for generic x86-64, 32 with AVX, ...), for a target that must build with
# EIGEN_DONT_VECTORIZE yet allocate and lay out Eigen objects like the rest of the program.
# Empty when none of the usual values compiles (the caller then keeps Eigen's defaults).
# Compile checks only, so it works when cross-compiling; the results are cached.
include(CheckCXXSourceCompiles)

function(springlab_eigen_alignment outMax outStatic)
  set(CMAKE_REQUIRED_LIBRARIES Eigen3::Eigen)
  set(CMAKE_REQUIRED_QUIET ON)
  set(found "")
  foreach(bytes 16 32 64 0)
    check_cxx_source_compiles("#include <Eigen/Core>
static_assert(EIGEN_MAX_ALIGN_BYTES == ${bytes}, \"\");
int main() { return 0; }" SPRINGLAB_EIGEN_MAX_ALIGN_${bytes})
    if(SPRINGLAB_EIGEN_MAX_ALIGN_${bytes})
      set(found ${bytes})
      break()
    endif()
  endforeach()
  set(foundStatic "")
  foreach(bytes 16 32 64 0)
    check_cxx_source_compiles("#include <Eigen/Core>
static_assert(EIGEN_MAX_STATIC_ALIGN_BYTES == ${bytes}, \"\");
int main() { return 0; }" SPRINGLAB_EIGEN_MAX_STATIC_ALIGN_${bytes})
    if(SPRINGLAB_EIGEN_MAX_STATIC_ALIGN_${bytes})
      set(foundStatic ${bytes})
      break()
    endif()
  endforeach()
  if(found STREQUAL "" OR foundStatic STREQUAL "" OR found STREQUAL "0")
    set(found "")
    set(foundStatic "")
  endif()
  set(${outMax} "${found}" PARENT_SCOPE)
  set(${outStatic} "${foundStatic}" PARENT_SCOPE)
endfunction()
