# GoogleTest for the tests: the installed one when it links with this compiler and standard
# library, else built here from its sources, with no flag to set.
#
# Why a check: a GoogleTest package is built for one C++ standard library. Debian's libgtest-dev
# is built with libstdc++, so a build with clang and libc++ (-stdlib=libc++, macOS's family) or
# a cross build finds it, compiles against its headers, and fails only at link time with
# undefined std::__1 symbols. A test program linked against it at configure time tells first.
#
# Sources: SPRINGLAB_GTEST_SOURCE when set (any GoogleTest source tree), else Debian's and
# Ubuntu's /usr/src/googletest (package googletest, which libgtest-dev pulls in).
#
# Sets SPRINGLAB_GTEST_FROM ("installed", or "built from DIR") for the summary line; a missing
# GoogleTest goes to SPRINGLAB_MISSING as "gtest", as every missing library does.

set(SPRINGLAB_GTEST_SOURCE "" CACHE PATH
    "Build GoogleTest from these sources (default: the installed GoogleTest, or /usr/src/googletest when the installed one does not link with this compiler)")

# Builds GoogleTest from `dir` as part of this build (targets GTest::gtest, GTest::gtest_main).
function(springlab_gtest_from_source dir)
  set(INSTALL_GTEST OFF CACHE BOOL "" FORCE)
  set(BUILD_GMOCK OFF CACHE BOOL "" FORCE)
  add_subdirectory(${dir} ${CMAKE_BINARY_DIR}/googletest EXCLUDE_FROM_ALL)
  # Its headers as SYSTEM (add_subdirectory's SYSTEM needs CMake 3.25), so that our warnings
  # do not reach them.
  get_target_property(gtest_includes gtest INTERFACE_INCLUDE_DIRECTORIES)
  set_target_properties(gtest PROPERTIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${gtest_includes}")
endfunction()

# Whether a GoogleTest program links against the installed GoogleTest with this compiler and
# flags (cmake/gtest_check, a project of its own). A success is cached per compiler and flags,
# so a second configure costs nothing; a failure checks again (a GoogleTest installed since).
function(springlab_installed_gtest_links result)
  set(key "${CMAKE_CXX_COMPILER};${CMAKE_CXX_FLAGS};${CMAKE_EXE_LINKER_FLAGS};${CMAKE_PREFIX_PATH};${GTest_DIR};${CMAKE_TOOLCHAIN_FILE}")
  if(SPRINGLAB_GTEST_LINKS AND SPRINGLAB_GTEST_LINKS_KEY STREQUAL key)
    set(${result} ${SPRINGLAB_GTEST_LINKS} PARENT_SCOPE)
    return()
  endif()
  set(dir ${CMAKE_BINARY_DIR}/CMakeFiles/springlab_gtest_check)
  file(REMOVE_RECURSE ${dir})
  try_compile(links ${dir} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/gtest_check springlab_gtest_check
              CMAKE_FLAGS "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}"
                          "-DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS}"
                          "-DCMAKE_EXE_LINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS}"
                          "-DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}"
                          "-DCMAKE_PREFIX_PATH=${CMAKE_PREFIX_PATH}"
                          "-DGTest_DIR=${GTest_DIR}"
                          "-DCMAKE_TOOLCHAIN_FILE=${CMAKE_TOOLCHAIN_FILE}"
                          "-DVCPKG_TARGET_TRIPLET=${VCPKG_TARGET_TRIPLET}"
              OUTPUT_VARIABLE output)
  file(WRITE ${CMAKE_BINARY_DIR}/springlab-gtest-check.log "${output}")
  # Not linking, or not installed at all: the check project's configure says which.
  string(FIND "${output}" "GTestConfig.cmake" not_found)
  if(links OR not_found EQUAL -1)
    set(installed TRUE)
  else()
    set(installed FALSE)
  endif()
  set(SPRINGLAB_GTEST_INSTALLED ${installed} CACHE INTERNAL "an installed GoogleTest was found")
  set(SPRINGLAB_GTEST_LINKS ${links} CACHE INTERNAL "the installed GoogleTest links with this compiler")
  set(SPRINGLAB_GTEST_LINKS_KEY "${key}" CACHE INTERNAL "compiler and flags SPRINGLAB_GTEST_LINKS was checked with")
  set(${result} ${links} PARENT_SCOPE)
endfunction()

set(SPRINGLAB_GTEST_FROM "")
if(SPRINGLAB_BUILD_TESTS)
  if(SPRINGLAB_GTEST_SOURCE)
    springlab_gtest_from_source(${SPRINGLAB_GTEST_SOURCE})
    set(SPRINGLAB_GTEST_FROM "built from ${SPRINGLAB_GTEST_SOURCE}")
  else()
    set(gtest_source_dir "")
    foreach(candidate /usr/src/googletest /usr/src/gtest)
      if(EXISTS ${candidate}/CMakeLists.txt AND NOT gtest_source_dir)
        set(gtest_source_dir ${candidate})
      endif()
    endforeach()
    # The check project finds the installed GoogleTest itself: found here, its targets
    # (GTest::gtest) would clash with a source build's, which defines the same names.
    springlab_installed_gtest_links(gtest_links)
    if(gtest_links)
      find_package(GTest REQUIRED)
      set(SPRINGLAB_GTEST_FROM "installed")
    elseif(gtest_source_dir)
      if(SPRINGLAB_GTEST_INSTALLED)
        set(why "the installed one does not link with ${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} and the flags '${CMAKE_CXX_FLAGS}' (another standard library?; the linker's messages: springlab-gtest-check.log)")
      else()
        set(why "no installed GoogleTest was found")
      endif()
      message(STATUS "GoogleTest: ${why}: building it from ${gtest_source_dir}")
      springlab_gtest_from_source(${gtest_source_dir})
      set(SPRINGLAB_GTEST_FROM "built from ${gtest_source_dir}")
    else()
      # No sources to fall back on: the installed GoogleTest as before the check (the check
      # itself may be what fails, on a platform it does not know), or none.
      find_package(GTest QUIET)
      if(GTest_FOUND)
        set(SPRINGLAB_GTEST_FROM "installed")
        message(WARNING "GoogleTest: a test program did not link against the installed GoogleTest "
                "with ${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} and the flags "
                "'${CMAKE_CXX_FLAGS}' (${CMAKE_BINARY_DIR}/springlab-gtest-check.log), and no "
                "GoogleTest sources were found to build it from: the tests may not link. Set "
                "-DSPRINGLAB_GTEST_SOURCE=<a GoogleTest source tree> (Debian/Ubuntu: package "
                "googletest, in /usr/src/googletest).")
      else()
        list(APPEND SPRINGLAB_MISSING gtest)
      endif()
    endif()
  endif()
endif()
