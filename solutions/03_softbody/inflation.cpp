#include <algorithm>
#include <cmath>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double inflatedGas(double target, double time, double inflationTime) {
  // BEGIN EXERCISE 3.5
  // A steady pump: the gas rises in proportion to the time pumped until the target is in.
  if (inflationTime <= 0.0) return target;
  const double fraction = std::clamp(time / inflationTime, 0.0, 1.0);
  return fraction * target;
  // END EXERCISE 3.5
}

double gasEnergy(double nRT, double volume, double restVolume) {
  // BEGIN EXERCISE 3.5
  // The work the gas can still do as it expands from V to V0 at constant temperature.
  if (volume <= 0.0 || restVolume <= 0.0) return 0.0;
  return -nRT * std::log(volume / restVolume);
  // END EXERCISE 3.5
}

}  // namespace springlab::softbody
