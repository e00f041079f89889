file(REMOVE_RECURSE
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/build_rope.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/build_rope.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/explicit_euler.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/explicit_euler.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/fixed_end.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/fixed_end.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/gravity_air.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/gravity_air.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/ground_contact.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/ground_contact.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/integrators.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/integrators.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/position_verlet.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/position_verlet.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/register.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/register.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/rope.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/rope.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/spring_force.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/spring_force.cpp.o.d"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/velocity_verlet.cpp.o"
  "CMakeFiles/springlab_rope_student.dir/labs/01_rope/velocity_verlet.cpp.o.d"
  "libspringlab_rope_student.a"
  "libspringlab_rope_student.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/springlab_rope_student.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
