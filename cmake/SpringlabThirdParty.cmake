# Libraries some platforms do not package: the system's copy when CMake finds one, the copy
# vendored in third_party/ otherwise (third_party/README.md says where each came from).
# SPRINGLAB_VENDORED=ON takes the vendored copies even where the system has its own.
#
# Each springlab_third_party_<name>() defines one target the project links, whatever its
# source, and sets SPRINGLAB_<NAME>_FROM ("system ..." or "vendored <version>") for the
# configure summary:
#   springlab_tinyobjloader  <tiny_obj_loader.h>, double precision (the core's OBJ reader)
#   springlab_imgui          <imgui.h>, <backends/imgui_impl_glfw.h>, <backends/imgui_impl_opengl3.h>
#   springlab_stb            <stb_image_write.h> (the viewer defines the implementation)
option(SPRINGLAB_VENDORED "Use the copies in third_party/ even where the system has the library" OFF)
set(SPRINGLAB_THIRD_PARTY ${CMAKE_CURRENT_LIST_DIR}/../third_party)
get_filename_component(SPRINGLAB_THIRD_PARTY ${SPRINGLAB_THIRD_PARTY} ABSOLUTE)

# "vendored <version>" for the summary; the version is the first line of third_party/<dir>/VERSION
# up to " (", its last word: that file is the one record of what was vendored.
function(springlab_vendored_version dir out)
  file(STRINGS ${SPRINGLAB_THIRD_PARTY}/${dir}/VERSION line LIMIT_COUNT 1)
  string(REGEX REPLACE " *\\(.*" "" line "${line}")
  string(REGEX REPLACE "^.* " "" line "${line}")  # its last word: the version
  set(${out} "vendored ${line}" PARENT_SCOPE)
endfunction()

# Whether a program using `target` (an installed library's imported target) links with this
# compiler and flags: a C++ library is built for one standard library, so a clang + libc++
# build (-stdlib=libc++) finds Debian's libstdc++-built copy and fails only when linking. Then
# the vendored copy serves instead. `code` is the program's body, after the library's #include.
# A success is cached per compiler and flags; a failure is checked again at each configure.
function(springlab_system_library_links result name target include code)
  set(key "${CMAKE_CXX_COMPILER};${CMAKE_CXX_FLAGS};${CMAKE_EXE_LINKER_FLAGS};${target}")
  if(SPRINGLAB_${name}_LINKS AND SPRINGLAB_${name}_LINKS_KEY STREQUAL key)
    set(${result} TRUE PARENT_SCOPE)
    return()
  endif()
  set(dir ${CMAKE_BINARY_DIR}/CMakeFiles/springlab_${name}_check)
  file(WRITE ${dir}/links.cpp "#include <${include}>\nint main() {\n${code}\n}\n")
  try_compile(links ${dir}/build SOURCES ${dir}/links.cpp LINK_LIBRARIES ${target}
              CXX_STANDARD 20 OUTPUT_VARIABLE output)
  file(WRITE ${CMAKE_BINARY_DIR}/springlab-${name}-check.log "${output}")
  set(SPRINGLAB_${name}_LINKS ${links} CACHE INTERNAL "the system's ${name} links with this compiler")
  set(SPRINGLAB_${name}_LINKS_KEY "${key}" CACHE INTERNAL "compiler and flags of SPRINGLAB_${name}_LINKS")
  set(${result} ${links} PARENT_SCOPE)
endfunction()

# ---- tinyobjloader ---------------------------------------------------------------------------
# Only a double-precision build is taken from the system (Debian's tinyobjloader_double, or a
# build exporting TINYOBJLOADER_USE_DOUBLE, e.g. vcpkg's "double" feature), so that a mesh
# reads to the same numbers on every platform.
function(springlab_third_party_tinyobjloader)
  add_library(springlab_tinyobjloader INTERFACE)
  if(NOT SPRINGLAB_VENDORED)
    find_package(tinyobjloader CONFIG QUIET)
    foreach(candidate tinyobjloader::tinyobjloader_double tinyobjloader::tinyobjloader)
      if(TARGET ${candidate})
        get_target_property(definitions ${candidate} INTERFACE_COMPILE_DEFINITIONS)
        if(candidate MATCHES "_double$" OR "TINYOBJLOADER_USE_DOUBLE" IN_LIST definitions)
          # (A std::string crosses into the library: the call a libc++ build cannot link.)
          springlab_system_library_links(links tinyobjloader ${candidate} tiny_obj_loader.h
            "tinyobj::ObjReader reader; return reader.ParseFromString(std::string(\"v 0 0 0\\n\"), std::string()) ? 0 : 1;")
          if(links)
            target_link_libraries(springlab_tinyobjloader INTERFACE ${candidate})
            set(SPRINGLAB_TINYOBJLOADER_FROM "system (${candidate})" PARENT_SCOPE)
            return()
          endif()
          message(STATUS "tinyobjloader: the system's (${candidate}) does not link with ${CMAKE_CXX_COMPILER_ID} "
                         "${CMAKE_CXX_COMPILER_VERSION} and the flags '${CMAKE_CXX_FLAGS}' (another standard "
                         "library?; springlab-tinyobjloader-check.log): using the vendored copy")
          break()
        endif()
      endif()
    endforeach()
  endif()
  # The vendored header, compiled once with its implementation, in double precision.
  set(unit ${CMAKE_BINARY_DIR}/third_party/tinyobjloader_impl.cpp)
  file(WRITE ${unit}.in "#define TINYOBJLOADER_IMPLEMENTATION\n#include <tiny_obj_loader.h>\n")
  configure_file(${unit}.in ${unit} COPYONLY)
  add_library(springlab_tinyobjloader_vendored STATIC ${unit})
  target_compile_definitions(springlab_tinyobjloader_vendored PUBLIC TINYOBJLOADER_USE_DOUBLE)
  target_include_directories(springlab_tinyobjloader_vendored SYSTEM PUBLIC ${SPRINGLAB_THIRD_PARTY}/tinyobjloader)
  target_link_libraries(springlab_tinyobjloader INTERFACE springlab_tinyobjloader_vendored)
  springlab_vendored_version(tinyobjloader from)
  set(SPRINGLAB_TINYOBJLOADER_FROM "${from}" PARENT_SCOPE)
endfunction()

# ---- Dear ImGui with its GLFW and OpenGL 3 backends ---------------------------------------------
# Found as: a CMake config (vcpkg's imgui[glfw-binding,opengl3-binding]: backend headers at
# the include root), then pkg-config (Debian's libimgui-dev: backends/ under /usr/include/imgui,
# compiled into libimgui), then the vendored sources. Needs the glfw target (the viewer's
# find_package(glfw3)). The viewer includes <backends/imgui_impl_*.h>; for a flat layout a
# folder of one-line forwarding headers supplies that path.
function(springlab_third_party_imgui)
  add_library(springlab_imgui INTERFACE)
  if(NOT SPRINGLAB_VENDORED)
    find_package(imgui CONFIG QUIET)
    if(TARGET imgui::imgui)
      get_target_property(dirs imgui::imgui INTERFACE_INCLUDE_DIRECTORIES)
      find_path(SPRINGLAB_IMGUI_GLFW_FLAT imgui_impl_glfw.h PATHS ${dirs} NO_DEFAULT_PATH)
      find_path(SPRINGLAB_IMGUI_GL3_FLAT imgui_impl_opengl3.h PATHS ${dirs} NO_DEFAULT_PATH)
      if(SPRINGLAB_IMGUI_GLFW_FLAT AND SPRINGLAB_IMGUI_GL3_FLAT)
        set(shim ${CMAKE_BINARY_DIR}/third_party/imgui_backends_shim)
        foreach(backend glfw opengl3)
          file(WRITE ${shim}/backends/imgui_impl_${backend}.h.in "#pragma once\n#include <imgui_impl_${backend}.h>\n")
          configure_file(${shim}/backends/imgui_impl_${backend}.h.in ${shim}/backends/imgui_impl_${backend}.h COPYONLY)
        endforeach()
        target_include_directories(springlab_imgui SYSTEM INTERFACE ${shim})
        target_link_libraries(springlab_imgui INTERFACE imgui::imgui)
        set(SPRINGLAB_IMGUI_FROM "system (CMake config)" PARENT_SCOPE)
        return()
      endif()
    endif()
    find_package(PkgConfig QUIET)
    if(PkgConfig_FOUND)
      pkg_check_modules(IMGUI QUIET IMPORTED_TARGET imgui)
    endif()
    if(IMGUI_FOUND)
      find_path(SPRINGLAB_IMGUI_BACKENDS backends/imgui_impl_glfw.h PATHS ${IMGUI_INCLUDE_DIRS} NO_DEFAULT_PATH)
      if(SPRINGLAB_IMGUI_BACKENDS)
        # Third-party headers are SYSTEM, so their warnings do not fail a -Werror build.
        target_include_directories(springlab_imgui SYSTEM INTERFACE ${IMGUI_INCLUDE_DIRS})
        target_link_libraries(springlab_imgui INTERFACE PkgConfig::IMGUI)
        set(SPRINGLAB_IMGUI_FROM "system (pkg-config ${IMGUI_VERSION})" PARENT_SCOPE)
        return()
      endif()
    endif()
  endif()
  # The vendored sources: the core and the two backends, without our warnings. The OpenGL 3
  # backend loads OpenGL itself (imgui_impl_opengl3_loader.h).
  set(dir ${SPRINGLAB_THIRD_PARTY}/imgui)
  add_library(springlab_imgui_vendored STATIC
    ${dir}/imgui.cpp ${dir}/imgui_draw.cpp ${dir}/imgui_tables.cpp ${dir}/imgui_widgets.cpp
    ${dir}/backends/imgui_impl_glfw.cpp ${dir}/backends/imgui_impl_opengl3.cpp)
  # imgui_demo.cpp is not vendored (the viewer never shows ImGui's demo window).
  target_include_directories(springlab_imgui_vendored SYSTEM PUBLIC ${dir})
  target_link_libraries(springlab_imgui_vendored PUBLIC glfw PRIVATE ${CMAKE_DL_LIBS})
  target_link_libraries(springlab_imgui INTERFACE springlab_imgui_vendored)
  springlab_vendored_version(imgui from)
  set(SPRINGLAB_IMGUI_FROM "${from}" PARENT_SCOPE)
endfunction()

# ---- stb_image_write --------------------------------------------------------------------------
# Header only: the system's (/usr/include/stb on Debian, vcpkg's include root) or the vendored.
function(springlab_third_party_stb)
  add_library(springlab_stb INTERFACE)
  if(NOT SPRINGLAB_VENDORED)
    find_path(SPRINGLAB_STB_DIR stb_image_write.h PATH_SUFFIXES stb)
    if(SPRINGLAB_STB_DIR)
      target_include_directories(springlab_stb SYSTEM INTERFACE ${SPRINGLAB_STB_DIR})
      set(SPRINGLAB_STB_FROM "system (${SPRINGLAB_STB_DIR})" PARENT_SCOPE)
      return()
    endif()
  endif()
  target_include_directories(springlab_stb SYSTEM INTERFACE ${SPRINGLAB_THIRD_PARTY}/stb)
  springlab_vendored_version(stb from)
  set(SPRINGLAB_STB_FROM "${from}" PARENT_SCOPE)
endfunction()
