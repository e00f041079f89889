// Compiles only where clang finds libc++ (tests/portability/CMakeLists.txt asks).
#include <string>
std::string probe;
