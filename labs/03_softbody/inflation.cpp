#include <algorithm>
#include <cmath>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double inflatedGas(double target, double time, double inflationTime) {
  // TODO exercise 3.5 (pumping the gas in): write this part; see handouts/03_softbody.md, Exercise 3.5 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.5", "pumping the gas in", "handouts/03_softbody.md, Exercise 3.5 (physics in section 2, The physics)");
}

double gasEnergy(double nRT, double volume, double restVolume) {
  // TODO exercise 3.5 (pumping the gas in): write this part; see handouts/03_softbody.md, Exercise 3.5 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.5", "pumping the gas in", "handouts/03_softbody.md, Exercise 3.5 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
