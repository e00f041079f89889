// springlab-<tree> and springlab-<tree>-<lab> (framework/app/CMakeLists.txt): run a scene headless
// (sim) or in the viewer (view).
// Exit codes: 0 success, 1 usage, 2 bad scene or option, 3 exercise not implemented,
// 4 the simulation blew up, 5 output could not be written.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include <springlab/energy_source.hpp>
#include <springlab/recorder.hpp>
#include <springlab/registry.hpp>
#include <springlab/step_stability.hpp>
#include <springlab/studies/rest_check.hpp>
#include <springlab/studies/run.hpp>

#include "study_commands.hpp"
#ifdef SPRINGLAB_HAS_VIEWER
#include <springlab/viewer.hpp>
#endif

namespace springlab {
void registerLabs(Registry& registry);  // register_labs.cpp, generated
}

namespace {

using namespace springlab;

struct SimOptions {
  std::string scene;
  long steps = 0;
  double dt = 0.0;  // 0: the scene's dt
  std::string integrator;
  std::string out;
  long saveEvery = 1;
  bool noBlowUpCheck = false;
  bool profile = false;
  std::vector<std::string> sets;  // --set KEY=VALUE
};

// "profile: forces 0.41 ms/step (38 %), integration ..." over the phases that took any time.
void printProfile(const Simulation& sim, long steps) {
  const double total = sim.profile.totalSeconds();
  std::cout << "profile: " << 1e3 * total / static_cast<double>(steps) << " ms/step";
  for (int p = 0; p < PhaseProfile::kPhases; ++p) {
    const Phase phase = static_cast<Phase>(p);
    const double seconds = sim.profile.seconds(phase);
    if (seconds <= 0.0) continue;
    std::cout << "; " << phaseName(phase) << " " << 1e3 * seconds / static_cast<double>(steps) << " ("
              << static_cast<int>(std::lround(100.0 * seconds / total)) << " %)";
  }
  std::cout << "\n";
}

// Past the step's stability limit a run can be unstable while its energy does not show it: a
// contact or the stretch limit caps the growing mode, and the masses reverse every step or keep
// moving where a stable step comes to rest (detectors 5 and 6, diagnostics.cpp). What tells
// that from the scene's own motion is the same scene at half the limit, the reference the
// stability chart's trials are held to: `sim` measures it too, for as long as the run, when dt
// is past the limit (the cube under the Runge-Kutta method at 1.03 times its limit ran to the
// end without it). The limit is the step's own (stepStableDt), computed once and given to the
// check past the limit. Nothing is measured at or below the limit, for a method with no
// stable dt or an unlimited one, or where the limit cannot be computed (a student's step still missing: the
// run itself then says so). The limit is computed on a copy of the scene, so that the run
// itself is not touched.
// Returns the limit when dt is past it (NaN otherwise), for the rest check after the run.
double watchPastTheLimit(const Registry& registry, const SceneDocument& document, Simulation& sim, double dt,
                         long steps) {
  double limit = NAN;
  try {
    LoadedScene copy = registry.loadScene(document);
    copy.sim->setIntegrator(registry.makeIntegrator(sim.integrator().name()));
    // One spectral radius at dt first: at most 1, dt is within the limit (the limit's own test,
    // without the allowance for a scene's physical growth, so never wrong that way) and the
    // bisection is not needed. The rope's limit took 3.1 s (ten dense eigenvalue solves of
    // its 480 coordinates), this radius a tenth of that.
    const double radius = stepSpectralRadius(*copy.sim, dt).radius;
    if (std::isfinite(radius) && radius <= 1.0 + StepStabilityOptions{}.radiusSlack) return NAN;
    limit = stepStableDt(*copy.sim);
  } catch (const std::exception&) {
    limit = NAN;
  }
  // Below the limit the check is left to compute it where a detector asks, as the viewer's and
  // the browser page's checks do: that computation restarts the integrator's history (all that
  // Simulation::SavedRun does not keep), which moves the run in its last bits, and the page's
  // run is held to the native one to 1e-9 (the flag under implicit Euler ended 8e-8 apart when
  // only the native run knew the limit).
  if (!(limit > 0.0) || !std::isfinite(limit) || dt <= limit) return NAN;
  sim.setKnownStepLimit(limit);
  std::cerr << "springlab sim: dt = " << dt << " s is " << dt / limit << " times the step's stability limit ("
            << limit << " s); the run is held to the same scene at half the limit, measured first\n";
  studies::holdToSwing(sim, studies::measureStableSwing(registry, document, sim.integrator().name(), 1.0, 0.5 * limit,
                                                       dt * static_cast<double>(steps)));
  return limit;
}

// A run past the limit that stayed bounded and within every allowance of the check may still
// hold a mode that something nonlinear caps (the wind ball under velocity Verlet at 1.03 times
// its limit: the floor keeps a step-alternating wobble of 1e-3 m/s). Where the scene rests at
// half the limit, its rest must hold at dt too (rest_check.hpp): the reason, when it does not.
std::optional<std::string> restNotHeld(const Registry& registry, const SceneDocument& document,
                                       const std::string& integrator, double dt, double limit, double duration) {
  try {
    const studies::RestGrowth baseline = studies::measureRestGrowth(registry, document, integrator, 1.0, 0.5 * limit,
                                                                    duration);
    if (!studies::restCheckApplies(baseline)) return std::nullopt;
    const studies::RestGrowth atDt = studies::measureRestGrowth(registry, document, integrator, 1.0, dt, duration);
    if (!studies::restBroken(atDt)) return std::nullopt;
    std::ostringstream s;
    s << "unstable: dt = " << dt << " s is " << dt / limit << " times the step's stability limit (" << limit
      << " s). The run stayed bounded, but the scene's rest does not hold at this dt: "
      << studies::describeRestGrowth(atDt, baseline)
      << ". Something in the scene that is not linear (a contact, the stretch limit, the wind's drag) keeps the "
         "growing mode from blowing up; take dt below the limit.";
    return s.str();
  } catch (const std::exception&) {
    return std::nullopt;  // a missing exercise: the run itself has said what it could
  }
}

// A file of every step can outgrow its disk: the ball under the midpoint rule for the stability
// chart's 303 s is 176 000 frames of 642 masses, about 14 GB of JSON. The size is known before
// the run (frames x masses x what a mass's line takes: about 300 bytes in CSV, 120 in JSON,
// measured on the rope and the ball), so a run that its disk cannot hold is refused with the
// --save-every that would fit, and one above 1 GB says how large it will be.
void checkOutputSize(const SimOptions& o, int masses) {
  const double perMassFrame = std::filesystem::path(o.out).extension() == ".csv" ? 300.0 : 120.0;
  const double frames = static_cast<double>(o.steps / o.saveEvery + 2);
  const double bytes = frames * static_cast<double>(masses) * perMassFrame;
  if (bytes < 1e9) return;
  std::error_code error;
  std::filesystem::path folder = std::filesystem::absolute(o.out, error).parent_path();
  while (!folder.empty() && !std::filesystem::exists(folder, error) && folder != folder.parent_path())
    folder = folder.parent_path();
  const std::filesystem::space_info space = std::filesystem::space(folder, error);
  // The --save-every that keeps the file near 100 MB.
  const long every = static_cast<long>(std::ceil(static_cast<double>(o.saveEvery) * bytes / 1e8));
  std::ostringstream what;
  what << "--out " << o.out << " would hold " << static_cast<long>(frames) << " frames of " << masses
       << " masses, about " << std::setprecision(3) << bytes / 1e9 << " GB";
  if (!error && static_cast<double>(space.available) < bytes) {
    throw std::invalid_argument(what.str() + ", and its disk has " + std::to_string(space.available / 1000000000) +
                                " GB free; save fewer frames with --save-every " + std::to_string(every) +
                                " (about 100 MB) or run without --out");
  }
  std::cerr << "springlab sim: " << what.str() << " (--save-every " << every << " keeps it near 100 MB)\n";
}

int runSim(const Registry& registry, const SimOptions& o) {
  // Load the scene and apply the command line's overrides.
  SceneDocument document = SceneDocument::read(o.scene);
  for (const std::string& assignment : o.sets) document.set(assignment);
  LoadedScene scene = registry.loadScene(document);
  Simulation& sim = *scene.sim;
  if (!o.integrator.empty()) sim.setIntegrator(registry.makeIntegrator(o.integrator));
  const double dt = o.dt > 0.0 ? o.dt : scene.settings.dt;
  if (!o.out.empty()) checkOutputSize(o, sim.numOfMasses());
  sim.setBlowUpCheck(!o.noBlowUpCheck);
  const double pastLimit = o.noBlowUpCheck ? NAN : watchPastTheLimit(registry, document, sim, dt, o.steps);
  sim.profile.setEnabled(o.profile);

  // Step, saving every saveEvery-th frame (and the first and the last). The output's folder
  // is made when missing (--out out/rope.csv); a folder that cannot be made is reported by the
  // recorder as an output that cannot be written. Without --out nothing is written: the run
  // prints its summary only (the handouts' "run it and read the energy" commands).
  std::optional<Recorder> recorder;
  if (!o.out.empty()) {
    if (const std::filesystem::path folder = std::filesystem::path(o.out).parent_path(); !folder.empty()) {
      std::error_code ignored;
      std::filesystem::create_directories(folder, ignored);
    }
    recorder.emplace(o.out, scene.settings, sim);
    recorder->record(sim);
  }
  std::string status = "ok";
  const auto start = std::chrono::steady_clock::now();
  long step = 0;
  try {
    for (step = 1; step <= o.steps; ++step) {
      sim.operate(dt);
      if (recorder && (step % o.saveEvery == 0 || step == o.steps)) recorder->record(sim);
    }
  } catch (const BlowUp& e) {
    if (recorder) {
      recorder->record(sim);
      recorder->close(e.what());
    }
    std::cerr << "springlab sim: " << e.what() << "\n";
    return 4;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (std::isfinite(pastLimit)) {
    if (const auto reason = restNotHeld(registry, document, sim.integrator().name(), dt, pastLimit,
                                        dt * static_cast<double>(o.steps))) {
      if (recorder) recorder->close(*reason);
      std::cerr << "springlab sim: " << *reason << "\n";
      return 4;
    }
  }
  if (recorder) recorder->close(status);

  // A one-line summary a student can compare between runs.
  const Energies e = sim.energies();
  std::cout << "sim: " << scene.settings.file << " with " << sim.integrator().name() << ", " << o.steps
            << " steps of dt = " << dt << " s (t = " << sim.state.time << " s), " << sim.stats.forceEvaluations
            << " force evaluations, " << sim.stats.solverIterations << " solver iterations, "
            << seconds << " s wall, " << (seconds > 0 ? static_cast<double>(o.steps) / seconds : 0.0)
            << " steps/s; total energy " << e.total() << " J (kinetic " << e.kinetic << " J);";
  // The scene's observables at the end (the numbers the handouts quote: drape_height, sag, ...).
  for (const Observable& ob : sim.observables()) {
    std::cout << " " << ob.name << " = " << ob.value << (ob.unit.empty() ? "" : " ") << ob.unit << ";";
  }
  std::cout << (o.out.empty() ? std::string(" nothing written (no --out)") : " wrote " + o.out) << "\n";
  if (o.profile) printProfile(sim, o.steps);
  // A run that did not blow up can still be wrong: a force that feeds energy in (a wind with
  // its sign turned) is named.
  if (const auto warning = energySourceWarning(sim)) std::cerr << "springlab sim: warning: " << *warning << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Registry registry;
  registerFramework(registry);
  registerLabs(registry);

  CLI::App app{std::string("springlab (") + SPRINGLAB_TREE + " code): run mass-spring scenes"};
  app.require_subcommand(1);

  SimOptions sim;
  auto* simCmd = app.add_subcommand("sim", "run a scene headless and write its states to a file");
  simCmd->add_option("scene", sim.scene, "scene file (JSON)")->required();
  simCmd->add_option("--steps", sim.steps, "number of steps")->required()->check(CLI::PositiveNumber);
  simCmd->add_option("--dt", sim.dt, "step in s (default: the scene's)")->check(CLI::PositiveNumber);
  simCmd->add_option("--integrator", sim.integrator, "integrator name (default: the scene's)");
  simCmd->add_option("--out", sim.out, "output file, .json or .csv (default: write nothing, print the summary)");
  simCmd->add_option("--save-every", sim.saveEvery, "save every K-th step (default 1)")->check(CLI::PositiveNumber);
  simCmd->add_flag("--no-blowup-check", sim.noBlowUpCheck, "keep stepping when the run blows up");
  simCmd->add_flag("--profile", sim.profile, "print where a step's time goes (forces, integration, collisions, ...)");
  simCmd->add_option("--set", sim.sets, "change a scene key first: KEY=VALUE, e.g. rope.masses=40 (repeatable)");

  app::StudyCommandOptions study;
  const auto [chartCmd, adviseCmd] = app::addStudyCommands(app, study);

  auto* listCmd = app.add_subcommand("list", "list the integrators and labs of this build");

#ifdef SPRINGLAB_HAS_VIEWER
  std::string viewScene;
  ViewerOptions view;
  view.tree = SPRINGLAB_TREE;
  auto* viewCmd = app.add_subcommand("view", "open the viewer on a scene");
  viewCmd->add_option("scene", viewScene, "scene file (JSON)")->required();
  viewCmd->add_option("--frames", view.frames, "close after N frames (0: run until closed)");
  viewCmd->add_option("--snapshot", view.snapshot, "write a PNG of the last frame");
  viewCmd->add_option("--width", view.width, "window width in pixels");
  viewCmd->add_option("--height", view.height, "window height in pixels");
  viewCmd->add_option("--integrator", view.integrator, "integrator name (default: the scene's)");
  viewCmd->add_option("--dt", view.dt, "step in s (default: the scene's)")->check(CLI::PositiveNumber);
#endif

  CLI11_PARSE(app, argc, argv);

  try {
    if (*simCmd) return runSim(registry, sim);
    if (*chartCmd) return app::runChart(registry, study);
    if (*adviseCmd) return app::runAdvise(registry, study);
    if (*listCmd) {
      std::cout << "integrators:";
      for (const auto& n : registry.integratorNames()) std::cout << ' ' << n;
      std::cout << "\nlabs:";
      for (const auto& n : registry.labNames()) std::cout << ' ' << n;
      std::cout << '\n';
      return 0;
    }
#ifdef SPRINGLAB_HAS_VIEWER
    if (*viewCmd) return runViewer(registry, viewScene, view);
#endif
  } catch (const SceneError& e) {
    std::cerr << "springlab: bad scene: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "springlab: " << e.what() << "\n";
    return 2;
  } catch (const NotImplemented& e) {
    std::cerr << "springlab: " << e.what() << "\n";
    return 3;
  } catch (const BlowUp& e) {
    std::cerr << "springlab: " << e.what() << "\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "springlab: " << e.what() << "\n";
    return 5;
  }
  return 1;
}
