
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/framework/src/diagnostics.cpp" "framework/CMakeFiles/springlab_core.dir/src/diagnostics.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/diagnostics.cpp.o.d"
  "/work/main/framework/src/recorder.cpp" "framework/CMakeFiles/springlab_core.dir/src/recorder.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/recorder.cpp.o.d"
  "/work/main/framework/src/registry.cpp" "framework/CMakeFiles/springlab_core.dir/src/registry.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/registry.cpp.o.d"
  "/work/main/framework/src/rope_simulation.cpp" "framework/CMakeFiles/springlab_core.dir/src/rope_simulation.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/rope_simulation.cpp.o.d"
  "/work/main/framework/src/scene_reader.cpp" "framework/CMakeFiles/springlab_core.dir/src/scene_reader.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/scene_reader.cpp.o.d"
  "/work/main/framework/src/simulation.cpp" "framework/CMakeFiles/springlab_core.dir/src/simulation.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/simulation.cpp.o.d"
  "/work/main/framework/src/symplectic_euler.cpp" "framework/CMakeFiles/springlab_core.dir/src/symplectic_euler.cpp.o" "gcc" "framework/CMakeFiles/springlab_core.dir/src/symplectic_euler.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
