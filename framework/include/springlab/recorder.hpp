#pragma once
// Writes a headless run to a file: per saved frame the time, the energies, the momentum,
// and every mass's position and velocity. The format follows the file's extension:
// .json (one document) or .csv (one row per mass per frame).
//
// Each frame goes to the file when it is recorded, not kept: a run of the 642-mass ball for
// 176 000 steps held as one JSON tree took more than 24 GB and was killed by the kernel with
// no word from us; streamed, it needs one frame's memory. A run that ends by an exception the
// caller does not catch still gets a whole document (the destructor closes it with a status
// that says so); a process killed midway leaves the frames it made, without the closing lines.
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
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  ~Recorder();
  void record(const Simulation& sim);
  // Finish the file; `status` is "ok" or the reason the run stopped (kept in JSON output).
  void close(const std::string& status);

 private:
  std::string path_;
  bool json_;
  std::ofstream out_;
  long frames_ = 0;      // frames written
  bool closed_ = false;  // close() has run
};

}  // namespace springlab
