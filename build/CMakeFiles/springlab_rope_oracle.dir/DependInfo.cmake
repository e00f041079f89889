
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/solutions/01_rope/build_rope.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/build_rope.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/build_rope.cpp.o.d"
  "/work/main/solutions/01_rope/explicit_euler.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/explicit_euler.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/explicit_euler.cpp.o.d"
  "/work/main/solutions/01_rope/fixed_end.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/fixed_end.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/fixed_end.cpp.o.d"
  "/work/main/solutions/01_rope/gravity_air.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/gravity_air.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/gravity_air.cpp.o.d"
  "/work/main/solutions/01_rope/ground_contact.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/ground_contact.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/ground_contact.cpp.o.d"
  "/work/main/solutions/01_rope/integrators.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/integrators.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/integrators.cpp.o.d"
  "/work/main/solutions/01_rope/position_verlet.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/position_verlet.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/position_verlet.cpp.o.d"
  "/work/main/solutions/01_rope/register.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/register.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/register.cpp.o.d"
  "/work/main/solutions/01_rope/rope.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/rope.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/rope.cpp.o.d"
  "/work/main/solutions/01_rope/spring_force.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/spring_force.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/spring_force.cpp.o.d"
  "/work/main/solutions/01_rope/velocity_verlet.cpp" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/velocity_verlet.cpp.o" "gcc" "CMakeFiles/springlab_rope_oracle.dir/solutions/01_rope/velocity_verlet.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build/framework/CMakeFiles/springlab_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
