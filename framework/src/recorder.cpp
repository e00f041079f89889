#include "springlab/recorder.hpp"

#include <iomanip>
#include <stdexcept>

namespace springlab {

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
nlohmann::json toJson(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

Recorder::Recorder(const std::string& path, const SceneSettings& settings, const Simulation& sim)
    : path_(path) {
  if (endsWith(path, ".json")) {
    json_ = true;
  } else if (endsWith(path, ".csv")) {
    json_ = false;
  } else {
    throw std::invalid_argument(path + ": output must end in .json or .csv");
  }
  out_.open(path);
  if (!out_) throw std::runtime_error(path + ": cannot write the output file");
  out_ << std::setprecision(17);

  // Header: what was run, so a file is self-describing. JSON: the document is opened here,
  // its frames follow one by one, and close() ends it with the run's status.
  if (json_) {
    const nlohmann::json header = {{"scene", settings.file},
                                   {"lab", settings.lab},
                                   {"integrator", sim.integrator().name()},
                                   {"dimension", sim.dimension},
                                   {"masses", sim.numOfMasses()}};
    const std::string text = header.dump(1);
    // The header's members without its closing brace, then the frames' array.
    const std::size_t lastMember = text.find_last_not_of("\n ", text.rfind('}') - 1);
    out_ << text.substr(0, lastMember + 1) << ",\n \"frames\": [";
  } else {
    out_ << "frame,time,mass,x,y,z,vx,vy,vz,kinetic,gravitational,elastic,other,total,px,py,pz\n";
  }
}

void Recorder::record(const Simulation& sim) {
  const Energies e = sim.energies();
  const Vec3 p = sim.momentum();
  if (json_) {
    nlohmann::json frame;
    frame["time"] = sim.state.time;
    frame["energy"] = {{"kinetic", e.kinetic}, {"gravitational", e.gravitational},
                       {"elastic", e.elastic}, {"other", e.other}, {"total", e.total()}};
    frame["momentum"] = toJson(p);
    frame["force_evaluations"] = sim.stats.forceEvaluations;
    frame["solver_iterations"] = sim.stats.solverIterations;
    frame["constraint_projections"] = sim.stats.constraintProjections;
    frame["back_substitutions"] = sim.stats.backSubstitutions;
    auto& observed = frame["observables"] = nlohmann::json::object();
    for (const Observable& o : sim.observables()) observed[o.name] = o.value;
    auto& pos = frame["pos"] = nlohmann::json::array();
    auto& vel = frame["vel"] = nlohmann::json::array();
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      pos.push_back(toJson(sim.state.pos[i]));
      vel.push_back(toJson(sim.state.vel[i]));
    }
    out_ << (frames_++ == 0 ? "\n" : ",\n") << frame.dump() << std::flush;
    return;
  }
  const long frame = frames_++;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    const Vec3& x = sim.state.pos[i];
    const Vec3& v = sim.state.vel[i];
    out_ << frame << ',' << sim.state.time << ',' << i << ',' << x.x() << ',' << x.y() << ',' << x.z() << ','
         << v.x() << ',' << v.y() << ',' << v.z() << ',' << e.kinetic << ',' << e.gravitational << ','
         << e.elastic << ',' << e.other << ',' << e.total() << ',' << p.x() << ',' << p.y() << ',' << p.z()
         << '\n';
  }
}

// A run left by an exception (a step that threw, a missing exercise): the document is ended
// all the same, so that what was recorded can be read.
Recorder::~Recorder() {
  if (closed_) return;
  try {
    close("the run stopped before its last step (an error, see the program's message)");
  } catch (...) {
    // A destructor must not throw; the file is then left as far as it was written.
  }
}

void Recorder::close(const std::string& status) {
  closed_ = true;
  if (json_) out_ << "\n ],\n \"status\": " << nlohmann::json(status).dump() << "\n}\n";
  out_.close();
  if (!out_) throw std::runtime_error(path_ + ": writing the output file failed");
}

}  // namespace springlab
