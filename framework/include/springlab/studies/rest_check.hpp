#pragma once
// Does the scene's rest hold at dt? The oracle for a mode that goes unstable at the step's
// limit and is then capped by something nonlinear (a contact, the stretch limit, the wind's
// drag): the run stays bounded, its energy and its step reversal stay within what the
// blow-up check allows, and only the rest it should hold says it is past the limit.
//
// Runs of the real step (not linearised) from the state the limit is computed at (the settled
// state, or the method's own rest): one as it is and kRestDirections more, each moved by 1e-8 of
// the scene's size in a pseudo-random direction (every coordinate, not only the modes the limit
// probes), their velocities compared with the first along the way (stepPerturbationGrowth). A
// rest that holds keeps the difference within the step's transient amplification: at 0.97 times
// the limit at most 54 times the disturbance (the ball under the user's sphere, midpoint rule;
// most stay below 3) on the shipped scenes whose runs stay where the limit is computed (not the
// ball dropped from the air, which rests on the floor, nor the wind ball pushed along it:
// stability.cpp). Past the limit it grows until the nonlinearity caps it: the wind ball under
// velocity Verlet 4e3 times at 1.03 times its limit, every other resting scene 8e4 or more, or
// non-finite (stop 46's measurements, before the settling followed a falling body to its rest).
//
// The median over the directions decides, not one: a capped wobble past the limit is a limit
// cycle that flips sign every step, and a disturbance sets its phase. Where the moved run's
// wobble ends in step with the reference's the two stay close: the wind ball at 1.03 times its
// limit where its settling stopped before it followed the ball's fall (1.445 ms), 2.2e3-5e3
// times for most of 300 directions, 449 times for eight and 3.2 times for one; the median of
// every three consecutive seeds breaks. At its present limit (1.475 ms) each of 60 directions
// breaks alone at 1.03 times and holds at 0.97 (studies.WindBall). The closed form holds the
// check too: on a chain at rest, undamped to overdamped, the rest holds at 0.97 times the
// closed-form limit and breaks at 1.03 times (studies.DampedChainRest).
//
// It applies only where the scene rests: at half the limit the runs must stay within
// kRestBaselineLimit of each other (26 or less on the resting scenes, the trampoline's the
// largest). Where they do not (a swinging rope, a flag in the wind: 2.5e3 to 3e4) the scene's
// own motion separates nearby runs at every dt, and the rest check has nothing to say. The
// chart and `sim` ask it only past the step's limit (stability.cpp says why).
#include <string>
#include <vector>

#include "springlab/registry.hpp"
#include "springlab/scene_document.hpp"

namespace springlab::studies {

struct RestGrowth {
  double growth = 0.0;  // the median over the directions of each one's largest difference over
                        // the disturbance
  std::vector<double> growths;  // each direction's (+inf: its run ended early)
  bool finite = true;   // both runs stayed finite to the end
  double dt = 0.0;      // s
  double duration = 0.0;  // s, simulated
};

constexpr double kRestDisturbance = 1e-8;      // of the scene's typical length (velocities: x w_max)
constexpr double kRestBaselineLimit = 100.0;   // at half the limit, at most: the scene rests
constexpr double kRestGrowthLimit = 1000.0;    // at dt, more: the rest does not hold
constexpr int kRestDirections = 3;             // disturbed runs, the median decides

// The runs at dt over `duration` (at least 200 steps), on a copy of the scene with every
// spring's k multiplied by stiffnessScale. NotImplemented propagates.
// `seed` picks the first disturbance's direction, the others seed + 1, ... (the chart and `sim`
// take 1).
RestGrowth measureRestGrowth(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                             double stiffnessScale, double dt, double duration, unsigned seed = 1,
                             int directions = kRestDirections);

// The check applies (the baseline at half the limit says the scene rests) ...
bool restCheckApplies(const RestGrowth& baseline);
// ... and then says the rest does not hold at dt.
bool restBroken(const RestGrowth& atDt);

// "a disturbance of 1e-8 of the scene's size (the median of 3 directions) grows 1.1e+04-fold in 3 s at dt = ... (at half the
// limit: 2.1-fold)": the blow-up message's clause.
std::string describeRestGrowth(const RestGrowth& atDt, const RestGrowth& baseline);

}  // namespace springlab::studies
