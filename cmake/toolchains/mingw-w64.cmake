# Cross build for 64-bit Windows with Debian's MinGW-w64 (g++-mingw-w64-x86-64), as
# `./springlab portability mingw` runs it: the core, the labs and their tests, run under wine.
# The viewer, the grader and the studies' POSIX parts stay out (the command builds only the
# test programs). Windows is LLP64: `long` is 32 bits there.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(triple x86_64-w64-mingw32)
# The -posix flavour: std::thread and std::mutex (GCC 12's win32 flavour has neither).
set(CMAKE_C_COMPILER ${triple}-gcc-posix)
set(CMAKE_CXX_COMPILER ${triple}-g++-posix)
set(CMAKE_RC_COMPILER ${triple}-windres)

# Libraries from the MinGW sysroot only; programs (python3, the compilers) from the host.
set(CMAKE_FIND_ROOT_PATH /usr/${triple})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The header-only libraries (Eigen, nlohmann/json, CLI11) come from the host's Debian packages,
# through config files that put only their own folders on the include path (never
# /usr/include, whose glibc headers would shadow MinGW's).
set(host_headers ${CMAKE_CURRENT_LIST_DIR}/mingw-host-headers)
set(Eigen3_DIR ${host_headers} CACHE PATH "")
set(nlohmann_json_DIR ${host_headers} CACHE PATH "")
set(CLI11_DIR ${host_headers} CACHE PATH "")

# libgcc, libstdc++ and winpthread linked into each .exe; OpenMP stays a DLL (libgomp-1.dll:
# FindOpenMP names its import library), which `portability mingw` puts on WINEPATH.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static -static-libgcc -static-libstdc++")
# ctest (and gtest_discover_tests) run the programs through wine.
find_program(SPRINGLAB_WINE NAMES wine64 wine PATHS /usr/lib/wine NO_CMAKE_FIND_ROOT_PATH)
set(CMAKE_CROSSCOMPILING_EMULATOR ${SPRINGLAB_WINE})
# Test programs list their tests when ctest runs (not after each link), so that a slow first
# start of wine cannot fail the build.
set(CMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE PRE_TEST)
