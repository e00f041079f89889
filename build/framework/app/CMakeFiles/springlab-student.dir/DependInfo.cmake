
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/framework/app/main.cpp" "framework/app/CMakeFiles/springlab-student.dir/main.cpp.o" "gcc" "framework/app/CMakeFiles/springlab-student.dir/main.cpp.o.d"
  "/work/main/build/framework/app/register_labs.cpp" "framework/app/CMakeFiles/springlab-student.dir/register_labs.cpp.o" "gcc" "framework/app/CMakeFiles/springlab-student.dir/register_labs.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build/framework/CMakeFiles/springlab_core.dir/DependInfo.cmake"
  "/work/main/build/CMakeFiles/springlab_rope_student.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
