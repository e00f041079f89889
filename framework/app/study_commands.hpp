#pragma once
// The `chart` and `advise` subcommands: run the studies of springlab_studies and write their
// CSV files (plus a small JSON of facts for the plot's titles) into one folder. The entry
// script `springlab chart ...` then draws PNG and SVG charts from them (tools/plot_charts.py).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <springlab/registry.hpp>

namespace springlab::app {

struct StudyCommandOptions {
  std::string kind;                 // work-precision, stability, resolution
  std::string scene;
  std::string out;                  // folder; default out/charts/<scene name>
  std::vector<std::string> sets;    // --set KEY=VALUE
  std::vector<std::string> integrators;
  double time = 0.0;                // s of simulated time (0: the study's default)
  int threads = 0;
  int repeats = 3;
  int levels = 0;                   // 0: the study's default
  double largestDt = 0.0;           // s, work-precision's first dt; 0: the study's default
  std::string observable;
  double tolerance = 0.01;
  std::vector<int> resolutions;
  std::string mapIntegrator;
  bool noMap = false;
  double fromRest = 0.0;            // s, stability: trials start from the method's run at half its limit
};

// Add `chart` and `advise` to the app; returns the two subcommands.
std::pair<CLI::App*, CLI::App*> addStudyCommands(CLI::App& app, StudyCommandOptions& options);

int runChart(const Registry& registry, const StudyCommandOptions& options);
int runAdvise(const Registry& registry, const StudyCommandOptions& options);

}  // namespace springlab::app
