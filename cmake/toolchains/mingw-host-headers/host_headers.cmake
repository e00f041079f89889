# springlab_host_headers(TARGET NAME... ): an imported INTERFACE target whose include folder
# holds links to the host's /usr/include/NAME folders only (cross builds: see mingw-w64.cmake).
function(springlab_host_headers target)
  if(TARGET ${target})
    return()
  endif()
  set(dir ${CMAKE_BINARY_DIR}/host-headers)
  foreach(name IN LISTS ARGN)
    if(NOT EXISTS ${dir}/${name})
      file(MAKE_DIRECTORY ${dir})
      file(CREATE_LINK /usr/include/${name} ${dir}/${name} SYMBOLIC)
    endif()
  endforeach()
  add_library(${target} INTERFACE IMPORTED GLOBAL)
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${dir}
                        INTERFACE_SYSTEM_INCLUDE_DIRECTORIES ${dir})
endfunction()
