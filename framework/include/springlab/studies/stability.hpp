#pragma once
// Where each method stops being stable: the largest dt that survives a fixed simulated time
// under the blow-up check, found by bracketing and bisection, against the prediction: the
// exact limit of the step that runs (stepStableDt: the linearised step at the start, with
// the scene's dampers, contacts and pressure), beside the undamped rule c / w_max (c: the
// method's stability constant, w_max: the Lanczos estimate at the start).
// And a map over stiffness x dt for one integrator: stable and unstable cells, with the
// predicted boundary at each stiffness.
#include <mutex>
#include <string>
#include <vector>

#include "springlab/studies/run.hpp"

namespace springlab::studies {

struct StabilityOptions {
  std::vector<std::string> integrators;  // empty: every registered integrator
  double duration = 0.0;     // s of simulated time per trial; 0: 300 periods of the stiffest mode, or
                             // longer, until a mode growing as the step does at 1.03 x the
                             // predicted limit has grown by 1e20
  double tolerance = 0.005;  // relative width of the final bracket
  long maxSteps = 4000000;   // a trial needing more steps is not run (the bracket stops there)
  int threads = 0;
  bool progress = true;
  // s, > 0: each trial first runs the method at half its predicted limit until this time (the
  // scene at rest, past its landing or its first gust), and only then at the trial's dt: the
  // measured limit is then that of the rest the prediction linearises at, without the
  // transients on the way there (a landing stiffer than the rest). 0: trials start at t = 0.
  double fromRest = 0.0;
  // Where the trials failed, the stiffest state on the way (CriticalDt::stiffestOnTheWay): a calm
  // run (calmRun: the scene from its start at half the predicted limit) up to the time the
  // smallest failing trial was stopped, linearised at 128 evenly spaced states after fromRest.
  // Skipped where the calm run would take more than stiffestOnTheWayWork mass-steps.
  bool stiffestOnTheWay = false;
  double stiffestOnTheWayWork = 1e9;
};

// One method's largest stable dt. `measured` is the lower end of the final bracket; it is
// +inf when even the largest trial survived, 0 when not even the smallest did.
struct CriticalDt {
  std::string integrator;
  double stabilityConstant = 0.0;  // c
  double undamped = 0.0;           // s, c / w_max; 0 when the method has no undamped limit
  double predicted = 0.0;          // s, stepStableDt: 0 no stable dt, +inf no limit
  // s, the largest dt that survived its trial; 0: every trial failed down to the smallest dt
  // tried; +inf: every trial survived; NaN: not measured, since a trial below the last failing
  // dt needs more than maxSteps steps (explicit Euler on the ball: 0.05 ms for 303 s).
  double measured = 0.0;
  double duration = 0.0;           // s of simulated time per trial
  int trials = 0;
  // s, the scene's time where the trial at the bracket's upper end (the smallest dt that
  // failed) was stopped; NaN: none failed, or it failed by the rest check (no time to name).
  double failedAt = NAN;
  // A diagnostic of where the trials failed (StabilityOptions::stiffestOnTheWay): s, the smallest
  // limit of a state a calm run passes through before failedAt, where that is more than 1 %
  // below `predicted` (else `predicted` itself), and that state's time (NaN: the rest's); NaN:
  // not computed. A frozen state's limit, not a prediction: it names the trampoline's catch
  // (the measured limit 0.99 times it), and it is far below what the trials survive where a
  // contact or the stretch limit caps the growth (the hanging cloth's catch, the slope's friction).
  double stiffestOnTheWay = NAN;
  double stiffestOnTheWayAt = NAN;
};

struct Stability {
  std::string scene;
  double duration = 0.0;
  double maxAngularFrequency = 0.0;  // rad/s, Lanczos estimate
  double gershgorinBound = 0.0;      // rad/s, Simulation::angularFrequencyBound
  std::vector<CriticalDt> methods;
  std::vector<std::string> skipped;
};

// The default trial duration of a scene: 300 periods of its stiffest mode.
double defaultStabilityDuration(double maxAngularFrequency);

// When a run from the scene's start comes to rest (s): symplectic Euler at half its limit, from
// the start, its check off, until its kinetic energy has stayed below kRestKinetic times its
// peak so far for `window`; the last time it was above. 0 where it does not rest by `until`
// (the wind ball rolls on), or the run cannot be made (no finite limit, not finite). A fallen
// body's rest, where the prediction linearises (StepSpectrum::restsAfterImpact): the ball
// dropped on its floor (14 s), a dropped cloth; looked for up to 10 times the trial's floor.
constexpr double kRestKinetic = 1e-3;
double restArrival(const Registry& registry, const SceneDocument& scene, double window, double until);

// restArrival of one scene (window: the first ask's, up to 10 windows), run once by whichever
// thread asks first and shared by the chart's
// methods (its run is symplectic Euler's whatever the method charted: the self-colliding
// cloth's 2.5 s of fall, once instead of once per method).
class SceneRestArrival {
 public:
  double get(const Registry& registry, const SceneDocument& scene, double window);

 private:
  std::once_flag once_;
  double arrival_ = 0.0;
};

// The trial time of one method: at least `atLeast`, and long enough for a mode that grows as
// the linearised step does at 1.03 x the predicted limit to grow by 1e20 (from round-off to
// a motion the blow-up check sees), counted from restArrival where the prediction is a fallen
// body's rest, at most 100 x atLeast.
// *growthOnly (when given): the same without the arrival, the rest check's time.
double stabilityTrialDuration(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                              double predicted, double atLeast, double* growthOnly = nullptr,
                              SceneRestArrival* sharedArrival = nullptr);

// Largest stable dt of one integrator, bisection from a first guess. With swingDt > 0 (half
// the predicted limit) each trial's blow-up check allows what a stable run holds, measured once
// at swingDt over `duration` and shared by the trials (StableSwing, RunSpec::swing). With
// restTime > 0 as well, each trial runs at swingDt until restTime first (RunSpec::restTime) and
// lasts `duration` from there.
// The rest check (past the limit, where the scene rests at swingDt) runs for restCheckDuration
// (0: `duration`): from the rest it needs the growth's time, not a fall's.
CriticalDt criticalDt(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                      double duration, double firstGuess, double tolerance = 0.005, long maxSteps = 4000000,
                      double stiffnessScale = 1.0, double swingDt = 0.0, double restTime = 0.0,
                      double restCheckDuration = 0.0);

Stability stability(const Registry& registry, const SceneDocument& scene, const StabilityOptions& options);

struct StabilityMapOptions {
  std::string integrator;           // empty: the scene's
  std::vector<double> stiffnessScales;  // empty: 10^-2 .. 10^2, 3 per decade
  int dtCount = 17;                 // dt values, log spaced over 10^-1.5 .. 10^1.5 x the prediction at scale 1
  double duration = 0.0;            // s; 0: as the stability study at scale 1
  long maxSteps = 400000;
  int threads = 0;
  bool progress = true;
};

struct StabilityMapCell {
  double stiffnessScale = 1.0;
  double dt = 0.0;
  bool stable = true;
  bool run = true;  // false: skipped, more than maxSteps
};

struct StabilityMap {
  std::string scene;
  std::string integrator;
  double stabilityConstant = 0.0;
  double springConstant = 0.0;  // N/m, the first spring's k at scale 1
  double duration = 0.0;
  std::vector<double> scales;
  std::vector<double> maxAngularFrequency;  // [scales] rad/s
  std::vector<double> predicted;            // [scales] s, stepStableDt at each stiffness
  std::vector<StabilityMapCell> cells;
};

StabilityMap stabilityMap(const Registry& registry, const SceneDocument& scene, const StabilityMapOptions& options);

void writeCsv(const Stability& study, const std::string& path);
void writeCsv(const StabilityMap& map, const std::string& cellsPath, const std::string& boundaryPath);

}  // namespace springlab::studies
