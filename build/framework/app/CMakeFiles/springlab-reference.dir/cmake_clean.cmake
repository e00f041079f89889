file(REMOVE_RECURSE
  "CMakeFiles/springlab-reference.dir/main.cpp.o"
  "CMakeFiles/springlab-reference.dir/main.cpp.o.d"
  "CMakeFiles/springlab-reference.dir/register_labs.cpp.o"
  "CMakeFiles/springlab-reference.dir/register_labs.cpp.o.d"
  "springlab-reference"
  "springlab-reference.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/springlab-reference.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
