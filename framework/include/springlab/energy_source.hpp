#pragma once
// Which of a lab's force terms feeds energy into the scene: the warning `sim` and the viewer
// print when a run that did not blow up ends (a wind with its sign turned drives a flag to a
// hundred joules where the correct one gives a tenth of a joule, without a blow-up).
#include <optional>
#include <string>

namespace springlab {

class Simulation;

// A force that depends on velocity can only take energy out of a passive scene (dampers, air
// friction, drag towards the wind's velocity): doubling every velocity changes its power
// v . f by at most 0. A term whose power grows instead pushes the masses along their own
// motion, and feeds them energy at every step however small dt is. Each of the lab's terms
// (forceTermNames, each left out in turn, as the blow-up diagnosis does) is tested at the
// current state; the message names the first that does this, with the kinetic energy now.
// Nothing when none does, when the lab names no terms, or when nothing moves. The forces are
// evaluated four times per term; the run's statistics are left as they were.
std::optional<std::string> energySourceWarning(Simulation& sim);

}  // namespace springlab
