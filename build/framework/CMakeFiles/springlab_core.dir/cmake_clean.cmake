file(REMOVE_RECURSE
  "CMakeFiles/springlab_core.dir/src/diagnostics.cpp.o"
  "CMakeFiles/springlab_core.dir/src/diagnostics.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/recorder.cpp.o"
  "CMakeFiles/springlab_core.dir/src/recorder.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/registry.cpp.o"
  "CMakeFiles/springlab_core.dir/src/registry.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/rope_simulation.cpp.o"
  "CMakeFiles/springlab_core.dir/src/rope_simulation.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/scene_reader.cpp.o"
  "CMakeFiles/springlab_core.dir/src/scene_reader.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/simulation.cpp.o"
  "CMakeFiles/springlab_core.dir/src/simulation.cpp.o.d"
  "CMakeFiles/springlab_core.dir/src/symplectic_euler.cpp.o"
  "CMakeFiles/springlab_core.dir/src/symplectic_euler.cpp.o.d"
  "libspringlab_core.a"
  "libspringlab_core.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/springlab_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
