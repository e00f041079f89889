#pragma once
// The net's fast spring pass: the forces and Jacobians of exercises 2.2 and 2.7 for every
// spring, as the plain loops of net.cpp compute them, by a faster route: the springs sorted
// into families (fast/spring_families.hpp) whose loops the compiler vectorises (AVX2 where the
// CPU has it), and threads for large nets. Net asks it first; where it declines, the plain
// loop runs. Students read net.cpp; nothing here changes what its loops mean.
#include <vector>

#include <springlab/force_jacobian.hpp>
#include <springlab/spring.hpp>
#include <springlab/state.hpp>

#include "fast/spring_families.hpp"

namespace springlab::net {

class FastSpringForces {
 public:
  // Follow a model edit: sort the springs into families again, or only copy their new k, L0
  // and kd when they still join the same masses in the same order.
  void modelEdited(const std::vector<Spring>& springs, int masses);
  // f += every spring's force at s (exercise 2.2): +F on mass1, -F on mass2. The sums differ
  // from the plain loop's in round-off only (their order does not depend on the list's order
  // or the thread count). False, adding nothing, when the springs form no family.
  bool addSpringForces(const State& s, const std::vector<Spring>& springs, std::vector<Vec3>& f);
  // J.pairs += every spring's Jacobians at s (exercise 2.7), in the order of `springs`, on
  // several threads. False, adding nothing, when one thread would do.
  bool addSpringJacobians(const State& s, const std::vector<Spring>& springs, ForceJacobian& J);

 private:
  // The family springs' forces of state s into the families' buffers.
  void familyForces(const State& s, int springCount);

  SpringFamilies families_;
};

}  // namespace springlab::net
