// Which twin of SPRINGLAB_AVX2_TWINS runs (see avx2.hpp).
#include "fast/avx2.hpp"

namespace springlab {

namespace {
bool avx2Allowed = true;
}  // namespace

bool hasAvx2() {
#if SPRINGLAB_AVX2_VARIANT
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

bool useAvx2() { return avx2Allowed && hasAvx2(); }
void allowAvx2(bool allowed) { avx2Allowed = allowed; }

}  // namespace springlab
