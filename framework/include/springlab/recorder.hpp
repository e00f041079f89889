#pragma once
// Writes a headless run to a file: per saved frame the time, the energies, the momentum,
// and every mass's position and velocity. The format follows the file's extension:
// .json (one document) or .csv (one row per mass per frame).
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "springlab/registry.hpp"
#include "springlab/simulation.hpp"

namespace springlab {

class Recorder {
 public:
  // Throws std::invalid_argument for an extension other than .json or .csv, and
  // std::runtime_error when the file cannot be written.
  Recorder(const std::string& path, const SceneSettings& settings, const Simulation& sim);
  void record(const Simulation& sim);
  // Finish the file; `status` is "ok" or the reason the run stopped (kept in JSON output).
  void close(const std::string& status);

 private:
  std::string path_;
  bool json_;
  std::ofstream out_;
  nlohmann::json document_;  // JSON output, written on close()
  long csvFrames_ = 0;        // frames written to CSV output
};

}  // namespace springlab
