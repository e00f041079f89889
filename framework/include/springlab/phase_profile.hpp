#pragma once
// Where a step's time goes, split like the cloth thesis' performance table: forces,
// integration (the integrator's own work, e.g. the implicit solve), collisions, stretch
// limiting, normals, and the rest (blow-up check, bookkeeping). Off by default; when on,
// each phase costs two clock reads. Phases nest: time spent in an inner phase (normals
// inside the force pass) is charged to the inner one only, so the phases add up to the total.
#include <array>
#include <chrono>
#include <string_view>

namespace springlab {

enum class Phase : int { kOther = 0, kForces, kIntegration, kCollisions, kStretchLimit, kNormals, kCount };

// The table's column name of each phase.
std::string_view phaseName(Phase phase);

class PhaseProfile {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr int kPhases = static_cast<int>(Phase::kCount);

  void setEnabled(bool on) { enabled_ = on; }
  void clear() { seconds_.fill(0.0); }
  // Seconds charged to a phase since the last clear().
  double seconds(Phase phase) const { return seconds_[static_cast<std::size_t>(phase)]; }
  double totalSeconds() const;

  // Charges the time until it ends to `phase` (pausing the phase it interrupts).
  class Scope {
   public:
    Scope(PhaseProfile& profile, Phase phase) : profile_(profile.enabled_ ? &profile : nullptr) {
      if (profile_) outer_ = profile_->enter(phase);
    }
    ~Scope() {
      if (profile_) profile_->leave(outer_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseProfile* profile_;
    Phase outer_ = Phase::kOther;
  };

 private:
  // Charge the time since the last switch to the current phase (when inside a scope), make
  // `phase` current and return the phase it replaces.
  Phase enter(Phase phase) {
    charge();
    ++depth_;
    const Phase outer = current_;
    current_ = phase;
    return outer;
  }
  // Back to the phase a scope interrupted; outside every scope the clock stops.
  void leave(Phase outer) {
    charge();
    --depth_;
    current_ = outer;
  }
  void charge() {
    const Clock::time_point now = Clock::now();
    if (depth_ > 0) seconds_[static_cast<std::size_t>(current_)] += std::chrono::duration<double>(now - since_).count();
    since_ = now;
  }

  bool enabled_ = false;
  int depth_ = 0;  // open scopes
  Phase current_ = Phase::kOther;
  Clock::time_point since_{};
  std::array<double, kPhases> seconds_{};
};

}  // namespace springlab
