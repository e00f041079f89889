#pragma once
// The springs of a regular grid sorted into families for a force pass the compiler can
// vectorise. A family is every spring joining mass i to mass i + d for one index offset d
// (a cloth has six: two structural, two shear, two bend). Within a family, springs whose
// first masses follow each other form runs: their ends are two contiguous stretches of the
// masses, so one spring force per spring can be computed in a loop without indirection, into
// the family's buffer at the index of its first mass. The loop reads what it needs as
// structures of arrays: the positions and velocities copied once per pass (load()), each
// spring's k, L0 and kd copied once when sorted, in run order: a vector register takes four
// springs' x (or k) in one load instead of shuffling them out of three-double Vec3s and
// 40-byte Spring records. gather() then adds, for every mass, each family's buffer at its own
// index minus the buffer at its index - d: no read-modify-write chain through f (consecutive
// springs of a grid share a mass, and each such update waits for the previous one's store),
// one store per mass, and a sum whose order depends neither on the list order nor on the
// thread count.
// Springs that fit no family (a second spring between the same masses, an offset too rare
// to be worth a buffer) are left over, in list order, for the caller's plain loop.
//
// The copies are the model's: they hold while the springs change only through
// Simulation::editModel, whose hook calls refresh(). check() compares a slice of the records
// with the copies on every pass (all of them every kCheckPasses passes), so a spring edited
// behind editModel's back is reported, not silently ignored for ever.
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
// Whether the force pass runs its AVX2 loops: hasAvx2(), unless a test turned them off
// (allowAvx2(false)) to compare them with the baseline's, which must give the same bits.
bool useAvx2();
void allowAvx2(bool allowed);

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
  static constexpr int kBlockMasses = 512;

  // Whether these families were made for this spring list (the same vector storage and size)
  // and this many masses.
  bool fits(const std::vector<Spring>& springs, int masses) const {
    return springs.data() == records_ && springs.size() == springCount_ && masses == masses_;
  }
  // After a model edit: copy every family spring's k, L0 and kd again. False when a spring no
  // longer joins the masses its run says (the list was rewired, reordered or resized): sort it
  // again then.
  bool refresh(const std::vector<Spring>& springs);
  // Compare the next slice of the springs with the copies (every spring once in kCheckPasses
  // calls); returns the index of a spring edited since, or -1.
  static constexpr int kCheckPasses = 256;
  int check(const std::vector<Spring>& springs);

  // Copy positions and velocities into the structures of arrays the runs read.
  void load(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel);
  // What load() copied, each [masses]: x, y, z of the positions, then of the velocities.
  const double* loaded(int component) const { return soa_.data() + static_cast<std::size_t>(component) * soaStride_; }
  // k, L0 and kd of the springs in order(), [order().size()] each.
  const double* stiffness() const { return k_.data(); }
  const double* restLength() const { return restLength_.data(); }
  const double* damping() const { return kd_.data(); }
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
  // The spring records [first, last) of order() against the copies: the first mismatch or -1.
  int mismatch(const std::vector<Spring>& springs, std::size_t first, std::size_t last) const;

  int masses_ = -1;
  std::size_t springCount_ = 0;
  const Spring* records_ = nullptr;          // the list sorted (its storage), for fits()
  int pad_ = 0;                              // zeros before and after each buffer: |largest offset|
  std::vector<int> offsets_;                 // [families] d
  std::vector<std::vector<Vec3>> buffers_;   // [families][pad + masses + pad] N
  std::vector<Run> runs_;
  std::vector<int> order_;
  std::vector<int> leftovers_;
  std::vector<int> firstMass_, secondMass_;  // [order] the masses each spring must join
  std::vector<double> k_, restLength_, kd_;  // [order] copies of the records
  std::size_t checked_ = 0;                  // check() resumes at this index of order()
  std::size_t soaStride_ = 0;                // masses, rounded up to 8 doubles, + 24
  std::vector<double> soa_;                  // [6][soaStride_] x, y, z, vx, vy, vz
};

}  // namespace springlab
