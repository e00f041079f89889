#pragma once
// The springs of a regular grid sorted into families for a force pass the compiler can
// vectorise. A family is every spring joining mass i to mass i + d for one index offset d
// (a cloth has six: two structural, two shear, two bend). Within a family, springs whose
// first masses follow each other form runs: their ends are two contiguous stretches of the
// position and velocity arrays, so one spring force per spring can be computed in a loop
// without indirection (the spring's own k, L0 and kd are still read from its record), into
// the family's buffer at the index of its first mass. gather() then adds, for every mass,
// each family's buffer at its own index minus the buffer at its index - d: no
// read-modify-write chain through f (consecutive springs of a grid share a mass, and each
// such update waits for the previous one's store), one store per mass, and a sum whose
// order depends neither on the list order nor on the thread count.
// Springs that fit no family (a second spring between the same masses, an offset too rare
// to be worth a buffer) are left over, in list order, for the caller's plain loop.
#include <cstddef>
#include <vector>

#include "springlab/math.hpp"
#include "springlab/spring.hpp"

// GCC on x86-64 builds the force pass's loops twice: for the machine's baseline and for AVX2
// (SPRINGLAB_TARGET_AVX2), and runs the second where the CPU has it (hasAvx2()): 4 doubles per
// instruction there, a portable binary everywhere. AVX2 without FMA: the same operations in the
// same order, so both give bitwise the same results. Other compilers build the baseline only.
// (Explicit functions, not target_clones: GCC 12's clones lose `restrict` on their parameters,
// and with it the vectorisation.) Not on Windows: MinGW-w64's GCC does not align the stack to
// 32 bytes for AVX spills there (GCC bug 54412), so an AVX2 function can fault.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(_WIN32)
#define SPRINGLAB_AVX2_VARIANT 1
#define SPRINGLAB_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define SPRINGLAB_AVX2_VARIANT 0
#define SPRINGLAB_TARGET_AVX2
#endif

namespace springlab {

// Whether this CPU (and its operating system) runs AVX2 instructions.
bool hasAvx2();

class SpringFamilies {
 public:
  // Springs order()[spring + t], t < count, join mass first + t to mass first + t + offset(family).
  struct Run {
    int first = 0;
    int count = 0;
    int spring = 0;
    int family = 0;
  };

  SpringFamilies() = default;
  // Families of `springs` between `masses` masses; offsets shared by fewer than a quarter as
  // many springs as there are masses stay left over (at most kMaxFamilies families).
  SpringFamilies(const std::vector<Spring>& springs, int masses);

  static constexpr int kMaxFamilies = 8;
  // Runs are cut into blocks of this many masses (see the constructor).
  static constexpr int kBlockMasses = 128;

  // Whether these families were made for this many springs and masses.
  bool fits(std::size_t springs, int masses) const { return springs == springCount_ && masses == masses_; }
  int families() const { return static_cast<int>(offsets_.size()); }
  int offset(int family) const { return offsets_[static_cast<std::size_t>(family)]; }
  const std::vector<Run>& runs() const { return runs_; }
  const std::vector<int>& order() const { return order_; }        // spring indices, run after run
  const std::vector<int>& leftovers() const { return leftovers_; }  // in list order
  // The family's force on the first mass of each of its springs, indexed by that mass
  // (zero where the mass starts no spring of the family). Springs write it, gather() reads it.
  Vec3* forces(int family) { return buffers_[static_cast<std::size_t>(family)].data() + pad_; }

  // f[i] += sum over families of forces(family)[i] - forces(family)[i - offset(family)].
  void gather(std::vector<Vec3>& f) const;

 private:
  int masses_ = -1;
  std::size_t springCount_ = 0;
  int pad_ = 0;                              // zeros before and after each buffer: |largest offset|
  std::vector<int> offsets_;                 // [families] d
  std::vector<std::vector<Vec3>> buffers_;   // [families][pad + masses + pad] N
  std::vector<Run> runs_;
  std::vector<int> order_;
  std::vector<int> leftovers_;
};

}  // namespace springlab
