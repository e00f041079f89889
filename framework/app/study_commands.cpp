#include "study_commands.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <springlab/studies/resolution.hpp>
#include <springlab/studies/stability.hpp>
#include <springlab/studies/work_precision.hpp>

namespace springlab::app {

namespace {

namespace fs = std::filesystem;

SceneDocument loadDocument(const StudyCommandOptions& o) {
  SceneDocument doc = SceneDocument::read(o.scene);
  for (const std::string& s : o.sets) doc.set(s);
  return doc;
}

std::string outputFolder(const StudyCommandOptions& o) {
  const std::string folder = o.out.empty() ? "out/charts/" + fs::path(o.scene).stem().string() : o.out;
  fs::create_directories(folder);
  return folder;
}

// Facts the plots print in titles and notes.
void writeFacts(const std::string& path, const nlohmann::json& facts) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << facts.dump(1) << '\n';
}

nlohmann::json sceneFacts(const SceneDocument& doc, const StudyCommandOptions& o) {
  return {{"scene", o.scene}, {"name", doc.json.value("name", o.scene)}, {"sets", o.sets}};
}

void printSkipped(const std::vector<std::string>& skipped) {
  for (const std::string& s : skipped) std::cerr << "springlab chart: skipped " << s << "\n";
}

int chartWorkPrecision(const Registry& registry, const StudyCommandOptions& o) {
  const SceneDocument doc = loadDocument(o);
  studies::WorkPrecisionOptions wo;
  wo.integrators = o.integrators;
  if (o.time > 0.0) wo.duration = o.time;
  if (o.levels > 0) wo.levels = o.levels;
  if (o.largestDt > 0.0) wo.largestDt = o.largestDt;
  wo.repeats = o.repeats;
  wo.threads = o.threads;
  const studies::WorkPrecision study = studies::workPrecision(registry, doc, wo);
  const std::string folder = outputFolder(o);
  studies::writeCsv(study, folder + "/work_precision.csv");
  nlohmann::json facts = sceneFacts(doc, o);
  facts["duration_s"] = study.duration;
  facts["reference"] = "rk4";
  facts["reference_dt_s"] = study.referenceDt;
  facts["w_max_rad_s"] = study.maxAngularFrequency;
  facts["skipped"] = study.skipped;
  writeFacts(folder + "/work_precision.json", facts);
  printSkipped(study.skipped);
  std::cout << "wrote " << folder << "/work_precision.csv (" << study.points.size() << " runs, reference rk4 at dt = "
            << study.referenceDt << " s)\n";
  return 0;
}

int chartStability(const Registry& registry, const StudyCommandOptions& o) {
  const SceneDocument doc = loadDocument(o);
  studies::StabilityOptions so;
  so.integrators = o.integrators;
  so.duration = o.time;
  so.threads = o.threads;
  so.fromRest = o.fromRest;
  so.stiffestOnTheWay = true;
  const studies::Stability study = studies::stability(registry, doc, so);
  const std::string folder = outputFolder(o);
  studies::writeCsv(study, folder + "/stability.csv");
  printSkipped(study.skipped);

  // The table a student reads: measured against predicted.
  std::cout << "w_max = " << study.maxAngularFrequency << " rad/s (Lanczos), Gershgorin bound "
            << study.gershgorinBound << " rad/s; each trial runs at least " << study.duration
            << " s (longer where an instability just past the predicted limit grows slowly)\n";
  std::cout << std::left << std::setw(22) << "integrator" << std::setw(16) << "c / w_max" << std::setw(16)
            << "predicted dt" << std::setw(16) << "measured dt" << std::setw(20) << "measured/predicted"
            << "stiffest state before the trials failed\n";
  for (const studies::CriticalDt& m : study.methods) {
    // predicted: the exact limit of the step (stepStableDt); "none": no stable dt;
    // "unlimited": stable at every dt tried; "not smooth": a contact switches where the scene
    // settles, and the step has no linearisation there. c / w_max: the undamped rule, for comparison.
    const bool finite = std::isfinite(m.predicted) && m.predicted > 0.0;
    const std::string predicted = finite                   ? std::to_string(m.predicted)
                                  : std::isnan(m.predicted) ? "not smooth"
                                  : m.predicted > 0.0       ? "unlimited"
                                                            : "none";
    const std::string undamped = m.undamped > 0.0 && std::isfinite(m.undamped) ? std::to_string(m.undamped) : "-";
    // measured NaN: not measured, a trial would need more than the chart's steps.
    std::ostringstream measured;
    if (std::isnan(m.measured)) measured << "not tried"; else measured << m.measured;
    std::cout << std::setw(22) << m.integrator << std::setw(16) << undamped << std::setw(16) << predicted
              << std::setw(16) << measured.str()
              << std::setw(20) << (finite && !std::isnan(m.measured) ? std::to_string(m.measured / m.predicted) : "-");
    // Where a state the trials passed through before they failed is stiffer than the rest (the
    // trampoline's catch): its limit and time, and measured against it. A frozen state's limit:
    // a contact or the stretch limit may cap what it grows (the slope's friction).
    if (std::isfinite(m.stiffestOnTheWayAt) && !std::isnan(m.measured)) {
      std::cout << m.stiffestOnTheWay << " s at t = " << m.stiffestOnTheWayAt << " s (measured_over_stiffest = "
                << m.measured / m.stiffestOnTheWay << ")";
    } else {
      std::cout << (std::isfinite(m.stiffestOnTheWay) ? "the rest's" : "-");
    }
    std::cout << "\n";
  }

  nlohmann::json facts = sceneFacts(doc, o);
  facts["duration_s"] = study.duration;
  facts["w_max_rad_s"] = study.maxAngularFrequency;
  facts["gershgorin_rad_s"] = study.gershgorinBound;
  facts["skipped"] = study.skipped;
  facts["from_rest_s"] = o.fromRest;  // s, 0: the trials start at t = 0
  if (!o.noMap) {
    studies::StabilityMapOptions mo;
    mo.integrator = o.mapIntegrator;
    mo.threads = o.threads;
    mo.duration = o.time;
    const studies::StabilityMap map = studies::stabilityMap(registry, doc, mo);
    studies::writeCsv(map, folder + "/stability_map.csv", folder + "/stability_boundary.csv");
    facts["map_integrator"] = map.integrator;
    facts["map_stability_constant"] = map.stabilityConstant;
    facts["map_spring_constant_N_m"] = map.springConstant;
    facts["map_duration_s"] = map.duration;
  }
  writeFacts(folder + "/stability.json", facts);
  std::cout << "wrote " << folder << "/stability.csv" << (o.noMap ? "" : " and the stiffness x dt map") << "\n";
  return 0;
}

int chartResolution(const Registry& registry, const StudyCommandOptions& o) {
  const SceneDocument doc = loadDocument(o);
  studies::ResolutionOptions ro;
  ro.observable = o.observable;
  ro.tolerance = o.tolerance;
  if (o.time > 0.0) ro.duration = o.time;
  ro.resolutions = o.resolutions;
  ro.integrator = o.integrators.empty() ? "" : o.integrators.front();
  ro.threads = o.threads;
  const studies::ResolutionStudy study = studies::resolutionStudy(registry, doc, ro);
  const std::string folder = outputFolder(o);
  studies::writeCsv(study, folder + "/resolution.csv", folder + "/resolution_series.csv");

  const studies::ResolutionRow& chosen = study.rows[study.chosen];
  const studies::ResolutionRow& finest = study.rows.back();
  const std::string key = registry.resolutionRule(doc.json.at("lab").get<std::string>()).key;
  std::cout << "observable " << study.observable << " (" << study.unit << ") over " << study.times.back()
            << " s with " << study.integrator << ", relative error against " << key << " = " << finest.resolution
            << ":\n";
  for (const studies::ResolutionRow& r : study.rows) {
    std::cout << "  " << key << " = " << std::setw(5) << r.resolution << "  dt = " << std::setw(10) << r.dt
              << "  error = " << std::setw(12) << r.error << "  cost = " << r.cost << " mass-evaluations, "
              << r.wallSeconds << " s wall" << (&r == &chosen ? "   <- coarsest within tolerance" : "") << "\n";
  }
  std::cout << key << " = " << chosen.resolution << " is within " << o.tolerance << " of " << key << " = "
            << finest.resolution << " at " << (chosen.cost > 0 ? finest.cost / chosen.cost : 0.0)
            << " times less cost (" << (chosen.wallSeconds > 0 ? finest.wallSeconds / chosen.wallSeconds : 0.0)
            << " times less wall time)\n";

  nlohmann::json facts = sceneFacts(doc, o);
  facts["observable"] = study.observable;
  facts["unit"] = study.unit;
  facts["tolerance"] = study.tolerance;
  facts["integrator"] = study.integrator;
  facts["resolution_key"] = doc.json.at("lab").get<std::string>() + "." + key;
  facts["chosen"] = chosen.resolution;
  writeFacts(folder + "/resolution.json", facts);
  std::cout << "wrote " << folder << "/resolution.csv\n";
  return 0;
}

}  // namespace

std::pair<CLI::App*, CLI::App*> addStudyCommands(CLI::App& app, StudyCommandOptions& o) {
  auto common = [&o](CLI::App* c) {
    c->add_option("scene", o.scene, "scene file (JSON)")->required();
    c->add_option("--set", o.sets, "change a scene key first: KEY=VALUE, e.g. rope.masses=40 (repeatable)");
    c->add_option("--threads", o.threads, "threads for independent runs (default: all cores)");
    c->add_option("--time", o.time, "simulated time of each run in s (default: the study's)");
  };
  auto* chart = app.add_subcommand("chart", "speed against accuracy: write a study's CSV files (the entry script plots them)");
  chart->add_option("kind", o.kind, "work-precision, stability or resolution")
      ->required()
      ->check(CLI::IsMember({"work-precision", "stability", "resolution"}));
  common(chart);
  chart->add_option("--out", o.out, "output folder (default out/charts/<scene>)");
  chart->add_option("--integrators", o.integrators, "integrators to compare (default: all registered)")->delimiter(',');
  chart->add_option("--repeats", o.repeats, "work-precision: timed runs after the warm-up (median)");
  chart->add_option("--levels", o.levels, "work-precision: dt values per integrator");
  chart->add_option("--largest-dt", o.largestDt,
                    "work-precision: the first dt in s (default: about twice RK4's limit); a frame's dt shows the methods stable there")
      ->check(CLI::PositiveNumber);
  chart->add_option("--observable", o.observable, "resolution: the scene observable to compare (default: its first)");
  chart->add_option("--tol", o.tolerance, "resolution: relative tolerance");
  chart->add_option("--resolutions", o.resolutions, "resolution: values of the resolution key")->delimiter(',');
  chart->add_option("--map-integrator", o.mapIntegrator, "stability: integrator of the stiffness x dt map (default: the scene's)");
  chart->add_flag("--no-map", o.noMap, "stability: skip the stiffness x dt map");
  chart->add_option("--from-rest", o.fromRest,
                    "stability: trials first run each method at half its predicted limit for this many seconds "
                    "(the scene at rest, past its landing), then at the trial's dt (default 0: from the start)")
      ->check(CLI::NonNegativeNumber);

  auto* advise = app.add_subcommand("advise", "print the cheapest resolution, integrator and dt within a tolerance, as JSON to paste into the scene");
  common(advise);
  advise->add_option("--tol", o.tolerance, "relative tolerance on the observable (default 0.01)");
  advise->add_option("--observable", o.observable, "the scene observable to keep accurate (default: its first)");
  advise->add_option("--integrators", o.integrators, "integrators to consider (default: all registered)")->delimiter(',');
  advise->add_option("--resolutions", o.resolutions, "values of the resolution key to try (default: the scene's over 8, 4, 2 and 1)")->delimiter(',');
  return {chart, advise};
}

int runChart(const Registry& registry, const StudyCommandOptions& o) {
  if (o.kind == "work-precision") return chartWorkPrecision(registry, o);
  if (o.kind == "stability") return chartStability(registry, o);
  return chartResolution(registry, o);
}

int runAdvise(const Registry& registry, const StudyCommandOptions& o) {
  const SceneDocument doc = loadDocument(o);
  studies::AdviseOptions ao;
  ao.tolerance = o.tolerance;
  ao.observable = o.observable;
  if (o.time > 0.0) ao.duration = o.time;
  ao.integrators = o.integrators;
  ao.resolutions = o.resolutions;
  ao.threads = o.threads;
  const studies::Advice advice = studies::advise(registry, doc, ao);

  // The reasoning on stderr, the snippet alone on stdout (so it can be redirected to a file).
  // The tolerance is split: half for the resolution, half for the time step.
  const std::string lab = doc.json.at("lab").get<std::string>();
  const double half = 0.5 * o.tolerance;
  std::cerr << "--tol " << o.tolerance << ": the answer keeps the observable within " << o.tolerance
            << " (relative) of a finer model and step, " << half << " for the resolution and " << half
            << " for the time step\n";
  if (!advice.resolution.rows.empty()) {
    std::cerr << "resolution: " << lab << "." << registry.resolutionRule(lab).key << " = " << advice.chosenResolution
              << " keeps " << advice.resolution.observable << " within " << half << " of "
              << registry.resolutionRule(lab).key << " = " << advice.resolution.rows.back().resolution
              << (advice.resolution.chosen + 1 == static_cast<int>(advice.resolution.rows.size())
                      ? " (the scene's own, the finest tried: no coarser one fits; --resolutions tries others)"
                      : "")
              << "\n";
  }
  // One column per field, as wide as its longest entry (integrator names run to 21 letters).
  size_t nameWidth = 10;
  for (const studies::Candidate& c : advice.candidates) nameWidth = std::max(nameWidth, c.integrator.size() + 2);
  std::cerr << "integrators at that resolution (the largest dt within " << half << " of RK4 at dt = "
            << advice.referenceDt << " s, over " << ao.duration << " s):\n";
  for (const studies::Candidate& c : advice.candidates) {
    std::cerr << "  " << std::left << std::setw(static_cast<int>(nameWidth)) << c.integrator;
    if (c.dt > 0.0) {
      std::cerr << "dt = " << std::setw(12) << c.dt << " error " << std::setw(12) << c.error << std::setw(10)
                << c.evaluationsPerSecond << " force evaluations (and solver iterations) per simulated second"
                << (&c == &advice.candidates[static_cast<size_t>(std::max(advice.best, 0))] && advice.best >= 0
                        ? "   <- the cheapest"
                        : "")
                << "\n";
    } else {
      std::cerr << c.note << "\n";
    }
  }
  if (advice.best < 0) {
    std::cerr << "springlab advise: no integrator met the tolerance; try a looser --tol\n";
    return 6;
  }
  std::cout << advice.snippet.dump(2) << "\n";
  return 0;
}

}  // namespace springlab::app
