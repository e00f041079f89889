file(REMOVE_RECURSE
  "CMakeFiles/springlab-student.dir/main.cpp.o"
  "CMakeFiles/springlab-student.dir/main.cpp.o.d"
  "CMakeFiles/springlab-student.dir/register_labs.cpp.o"
  "CMakeFiles/springlab-student.dir/register_labs.cpp.o.d"
  "springlab-student"
  "springlab-student.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/springlab-student.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
