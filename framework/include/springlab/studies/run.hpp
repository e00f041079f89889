#pragma once
// One study run: a scene document, an integrator and a dt, stepped for a simulated duration
// with the blow-up check on, sampled at fixed times. Every study (work-precision, stability,
// resolution, advisor) is made of these.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "springlab/diagnostics.hpp"
#include "springlab/registry.hpp"
#include "springlab/scene_document.hpp"

namespace springlab::studies {

// What a stable run holds: in a run of the scene at dt (half the stability limit) over a
// trial's simulated time, the largest rise of the total energy less the wind's work (and of the
// step's own, less the corrections' work too: the two energies the passivity detector holds)
// above its lowest so far (not its start: a damped scene can lose energy faster than the step
// swings it up, and hide the rise), the largest step reversal it sustains (StepReversal) and
// the reversal along its time (ReversalProfile). Negative: not measured (that run went
// non-finite; a reversal: too short a run to fill the window).
struct StableSwing {
  double total = -1.0, own = -1.0;  // J
  double reversal = -1.0;           // m/s
  ReversalProfile profile;
};
// At most kMaxSwingSteps steps (past them, detector 5 holds a run to the profile's last bins).
constexpr long kMaxSwingSteps = 4'000'000;
StableSwing measureStableSwing(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                               double stiffnessScale, double dt, double duration);
// Hold sim's blow-up check to that swing (BlowUpCheck::setEnergySwing, setReversalSwing,
// setReversalProfile): the chart's trials and `sim` past the step's limit.
void holdToSwing(Simulation& sim, const StableSwing& swing);

struct RunSpec {
  SceneDocument scene;
  std::string integrator;      // registered name
  double dt = 0.0;             // s
  long stepsPerSample = 1;     // samples are taken every stepsPerSample steps (and at t = 0)
  int samples = 0;             // samples after t = 0; the run lasts samples * stepsPerSample steps
  double stiffnessScale = 1.0; // every spring's k is multiplied by this (stability maps)
  bool keepPositions = true;   // store every mass's position at each sample
  // s, > 0: first measure what a stable run holds (StableSwing) in a run at this dt (half the
  // stability limit) over this run's time, and let the blow-up check allow it
  // (BlowUpCheck::setEnergySwing, setReversalSwing, setReversalProfile); 0: the defaults.
  double swingDt = 0.0;
  // That swing measured beforehand, for runs that share it (a bisection's trials); null: measured
  // here when swingDt > 0, over this run's time.
  std::shared_ptr<const StableSwing> swing = nullptr;
  // s, > 0: the run first steps the scene at restDt until this time, its blow-up check on (a
  // user who lets the scene settle, then raises dt), and only then at dt; its samples and
  // steps count from the start. The swing run then covers the rest too.
  double restTime = 0.0;
  double restDt = 0.0;  // s, the step up to restTime (half the stability limit)
  // Watch for a capped instability (BlowUpCheck detectors 5 and 6, from the step reversal and
  // the kinetic energy the swing run held); false turns both off (a test of the other detectors).
  bool watchReversal = true;
  // A blow-up's message names the likely cause from the step's exact limit (seconds per
  // blow-up on an 80-mass rope); a chart's trials turn it off, they keep only the verdict.
  bool explainBlowUp = true;
  // The scene's step limit (stepStableDt at stiffnessScale), already computed: the detectors that
  // count only past it (BlowUpCheck::beyondLimit) read it instead of computing it again (a
  // bisection's trials share one: the 80-mass rope's costs 3 s, and each trial paid it). Unset:
  // computed where a detector first asks.
  std::optional<double> knownStepLimit = std::nullopt;
};

struct RunResult {
  bool stable = true;         // false: the blow-up check stopped it
  std::string failure;        // the blow-up message, when not stable
  double stoppedAt = NAN;     // s, the scene's time where the blow-up check stopped it
  long steps = 0;
  long forceEvaluations = 0;
  long solverIterations = 0;
  int masses = 0;
  double wallSeconds = 0.0;   // stepping only, not building the scene
  std::vector<double> times;                   // [samples + 1] s
  std::vector<std::vector<Vec3>> positions;    // [samples + 1][n] m (keepPositions)
  std::vector<std::string> observableNames;    // the scene's observables()
  std::vector<std::vector<double>> observables;  // [samples + 1][observables]
};

// Build the scene and run it. NotImplemented and SceneError propagate (the caller decides
// whether a missing exercise skips an integrator or stops the study); a blow-up does not.
RunResult runScene(const Registry& registry, const RunSpec& spec);

// Largest distance between the same mass in two runs at each common sample (m); runs that
// stopped early compare only the samples both have. Empty when the runs differ in size.
std::vector<double> positionErrors(const RunResult& run, const RunResult& reference);

// The values of one observable over a run; std::invalid_argument naming the known ones.
std::vector<double> observableSeries(const RunResult& run, const std::string& name);

// Every spring's k times factor (the stability map's stiffness scale): a model edit, before
// the run starts.
void scaleSprings(Simulation& sim, double factor);

// The largest angular frequency of the scene at its initial state (Lanczos estimate),
// with every spring's k multiplied by stiffnessScale.
double sceneLanczosEstimate(const Registry& registry, const SceneDocument& scene, double stiffnessScale = 1.0);

// The exact stability limit of the integrator's step on the scene (stepStableDt: the
// linearised step at the settled state, dampers, contacts and pressure included), with every
// spring's k multiplied by stiffnessScale. NotImplemented propagates.
double sceneStepStableDt(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                         double stiffnessScale = 1.0);

// The integrator's stability constant c (dt < c / w_max for undamped springs), by name.
double stabilityConstant(const Registry& registry, const std::string& integrator);

// The integrators a study compares: `requested` as given, or else every registered one that
// can run this scene. An integrator refuses a scene it cannot handle with
// std::invalid_argument (an implicit method on a scene without force Jacobians); such
// integrators are left out with a note on stderr, not reported as failures.
std::vector<std::string> studyIntegrators(const Registry& registry, const SceneDocument& scene,
                                          const std::vector<std::string>& requested);

// Median of a list (the list is copied).
double median(std::vector<double> values);

}  // namespace springlab::studies
