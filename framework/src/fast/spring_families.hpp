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
// The copies are the model's: Simulation::editModel, the one writer of the springs, calls
// the lab's hook, which calls refresh() (or sorts again).
#include <cstddef>
#include <vector>

#include "springlab/math.hpp"
#include "springlab/spring.hpp"

namespace springlab {

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

  // After a model edit: copy every family spring's k, L0 and kd again. False when the springs
  // no longer join the masses their runs say (the list was rewired, reordered or resized) or
  // the number of masses changed: sort them again then.
  bool refresh(const std::vector<Spring>& springs, int masses);

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
  int masses_ = -1;
  std::size_t springCount_ = 0;
  int pad_ = 0;                              // zeros before and after each buffer: |largest offset|
  std::vector<int> offsets_;                 // [families] d
  std::vector<std::vector<Vec3>> buffers_;   // [families][pad + masses + pad] N
  std::vector<Run> runs_;
  std::vector<int> order_;
  std::vector<int> leftovers_;
  std::vector<int> firstMass_, secondMass_;  // [order] the masses each spring must join
  std::vector<double> k_, restLength_, kd_;  // [order] copies of the records
  std::size_t soaStride_ = 0;                // masses, rounded up to 8 doubles, + 24
  std::vector<double> soa_;                  // [6][soaStride_] x, y, z, vx, vy, vz
};

}  // namespace springlab
