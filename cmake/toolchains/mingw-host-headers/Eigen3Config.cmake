# Eigen from the host (/usr/include/eigen3), header only: see host_headers.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
if(NOT TARGET Eigen3::Eigen)
  add_library(Eigen3::Eigen INTERFACE IMPORTED GLOBAL)
  set_target_properties(Eigen3::Eigen PROPERTIES INTERFACE_INCLUDE_DIRECTORIES /usr/include/eigen3
                        INTERFACE_SYSTEM_INCLUDE_DIRECTORIES /usr/include/eigen3)
endif()
