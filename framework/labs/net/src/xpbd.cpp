// Extended position-based dynamics (given loop; Macklin, Mueller and Chentanez 2016) on the
// scene's springs, built on exercise 2.11. Each spring is a distance constraint of compliance
// 1/k and constraint damping from its kd, so with enough iterations its equilibrium is the
// force model's. External forces once per step; per substep of h = dt / substeps: predict, project
// every constraint `iterations` times (Gauss-Seidel in colour order, multipliers from zero or,
// with the option warm_start, from the last substep's), v = (x - x_old)/h.
// Contacts, stretch limiting and self-collision stay in the scene's afterStep (once per step).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include <springlab/net/net.hpp>

#include "external_forces.hpp"

namespace springlab::net {

namespace {

class Xpbd final : public Integrator {
 public:
  static constexpr std::string_view kName = "xpbd";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  // Stable at any dt: positions are projected, never pushed by a stiff force (with the
  // multipliers from zero, the default; the warm start is not, see warmStartFromTensions).
  double stabilityConstant() const override { return INFINITY; }
  // From zero multipliers a few sweeps stop short of the tension that holds the cloth: it
  // rests lower than the springs' equilibrium. Warm-started, it rests there.
  bool restsAtStaticEquilibrium() const override { return warmStart_; }
  // A restarted scene starts without tensions.
  void reset() override { tension_.clear(); }

  std::vector<std::string> optionNames() const override { return {"iterations", "substeps", "warm_start"}; }
  void setOption(const std::string& option, int value) override {
    if (option == "iterations") iterations_ = value;
    else if (option == "substeps") substeps_ = value;
    else if (option == "warm_start") warmStart_ = value != 0;
    else Integrator::setOption(option, value);
  }

  void step(Simulation& sim, double dt) override {
    // The external forces once per step, at its start, for every substep: they change slowly
    // (gravity, air, wind), and each evaluation costs three passes over the springs (the
    // scene's forces, then the springs' own taken out again), several times a projection sweep.
    externalForces(sim, external_);
    const double h = dt / substeps_;
    buildConstraints(sim, h);
    for (int k = 0; k < substeps_; ++k) substep(sim, h);
  }

 private:
  // One distance constraint as the sweep reads it: everything that does not change within a
  // step precomputed, so a projection is loads, one square root and two divisions.
  struct Constraint {
    int spring;             // index in sim.springs() (its tension is kept there between substeps)
    int mass1, mass2;
    double w1, w2;          // 1/kg, inverse masses this step (0: pinned or grabbed)
    double restLength;      // m
    double alphaTilde;      // 1 / (k h^2)
    double gamma;           // alpha~ (h^2 kd) / h = kd / (k h)
  };

  // The springs as constraints, in colour order. Why colours: in the scene's order
  // consecutive springs share a mass (a row of structural springs is a chain), so each
  // projection waits for the previous one's result (a square root and two divisions deep:
  // measured 28 ns a projection at r = 64). A greedy colouring orders the springs so that
  // consecutive ones share no mass; the processor overlaps them (Gauss-Seidel by colour, the
  // order the GPU versions use, run serially). The colouring is redone only when the springs'
  // ends change; stiffness, damping, masses and pins are read every step.
  void buildConstraints(const Simulation& sim, double h) {
    if (!sameTopology(sim)) colour(sim);
    const double inverseH2 = 1.0 / (h * h);
    inverseH2_ = inverseH2;
    constraints_.clear();
    for (const int c : order_) {
      const Spring& sp = sim.springs()[static_cast<std::size_t>(c)];
      if (sp.springConstant <= 0.0) continue;  // no stiffness, no constraint
      const double w1 = sim.inverseMass(sp.mass1), w2 = sim.inverseMass(sp.mass2);
      if (w1 == 0.0 && w2 == 0.0) continue;  // both ends held: nothing to move
      constraints_.push_back({c, sp.mass1, sp.mass2, w1, w2, sp.springLength, inverseH2 / sp.springConstant,
                              sp.frictionConstant / (sp.springConstant * h)});
    }
    lambda_.resize(constraints_.size());
    tension_.resize(sim.springs().size(), 0.0);
    h_ = h;
  }

  bool sameTopology(const Simulation& sim) const {
    if (ends_.size() != 2 * sim.springs().size()) return false;
    for (std::size_t c = 0; c < sim.springs().size(); ++c) {
      if (ends_[2 * c] != sim.springs()[c].mass1 || ends_[2 * c + 1] != sim.springs()[c].mass2) return false;
    }
    return true;
  }

  // Greedy colouring: each spring takes the lowest colour neither end has yet (a 64-bit set per
  // mass; a cloth mass has 12 springs, so about 20 colours). Past 64 colours a spring goes to
  // the last colour, which keeps the order valid Gauss-Seidel, only less overlapped.
  void colour(const Simulation& sim) {
    const std::size_t springs = sim.springs().size();
    tension_.clear();  // they belonged to the old springs
    ends_.resize(2 * springs);
    std::vector<std::uint64_t> used(static_cast<std::size_t>(sim.numOfMasses()), 0);
    std::vector<int> colourOf(springs);
    std::vector<int> count(65, 0);
    for (std::size_t c = 0; c < springs; ++c) {
      const Spring& sp = sim.springs()[c];
      ends_[2 * c] = sp.mass1;
      ends_[2 * c + 1] = sp.mass2;
      std::uint64_t& a = used[static_cast<std::size_t>(sp.mass1)];
      std::uint64_t& b = used[static_cast<std::size_t>(sp.mass2)];
      const std::uint64_t free = ~(a | b);
      const int k = free == 0 ? 63 : std::countr_zero(free);
      a |= std::uint64_t{1} << k;
      b |= std::uint64_t{1} << k;
      colourOf[c] = k;
      ++count[static_cast<std::size_t>(k) + 1];
    }
    for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    order_.resize(springs);
    for (std::size_t c = 0; c < springs; ++c) order_[static_cast<std::size_t>(count[static_cast<std::size_t>(colourOf[c])]++)] = static_cast<int>(c);
  }

  void substep(Simulation& sim, double h) {
    State& s = sim.state;
    const int n = sim.numOfMasses();

    // Predict: the external forces move the masses freely for h (symplectic Euler).
    previous_ = s.pos;
    for (int i = 0; i < n; ++i) {
      s.vel[i] += (h * sim.inverseMass(i)) * external_[i];
      s.pos[i] += h * s.vel[i];
    }

    // Project every constraint, `iterations` sweeps, multipliers from zero or warm-started.
    Vec3* const pos = s.pos.data();
    const Vec3* const previous = previous_.data();
    if (warmStart_) warmStartFromTensions(pos, previous);
    else std::fill(lambda_.begin(), lambda_.end(), 0.0);
    for (int sweep = 0; sweep < iterations_; ++sweep) {
      for (std::size_t c = 0; c < constraints_.size(); ++c) {
        const Constraint& k = constraints_[c];
        const DistanceCorrection d = xpbdDistanceConstraint(pos[k.mass1], pos[k.mass2], previous[k.mass1], previous[k.mass2],
                                                            k.w1, k.w2, k.restLength, k.alphaTilde, k.gamma, lambda_[c]);
        pos[k.mass1] += d.dx1;
        pos[k.mass2] += d.dx2;
        lambda_[c] += d.dlambda;
      }
    }
    if (warmStart_) {
      for (std::size_t c = 0; c < constraints_.size(); ++c) tension_[static_cast<std::size_t>(constraints_[c].spring)] = lambda_[c] * inverseH2_;
    }
    sim.stats.solverIterations += iterations_;
    sim.stats.constraintProjections += static_cast<long>(iterations_) * static_cast<long>(constraints_.size());

    // Velocities from the positions' change; masses the scene moves keep theirs.
    const double inverseH = 1.0 / h;
    for (int i = 0; i < n; ++i) {
      if (sim.inverseMass(i) != 0.0) s.vel[i] = (s.pos[i] - previous_[i]) * inverseH;
    }
    s.time += h;
  }

  // Warm start: each multiplier starts from the last substep's (lambda = tension h^2), and the
  // masses first take the moves those multipliers stand for, w_i lambda grad C_i at the predicted
  // positions. Why: with multipliers from zero a sweep must rebuild the whole tension of a
  // hanging cloth each substep, and one sweep moves a correction about one spring, so the sweeps
  // end short and the cloth hangs stretched (r = 32, one sweep: 2.4 % too low at 8 substeps,
  // 0.2 % at 64). Warm-started, a resting cloth starts at its answer: x = x~ + M^-1 grad C^T
  // lambda and C + alpha~ lambda = 0 at lambda = -k h^2 C give f_ext = k C grad C, the force
  // model's equilibrium, at any number of sweeps and substeps. The gradients are taken where the
  // tensions were, at the substep's start (at the predicted positions the rest state would be off
  // by the turn h^2 a makes: 1.7 % of the gas force on the soft body). It costs about a sweep.
  void warmStartFromTensions(Vec3* pos, const Vec3* start) {
    const double h2 = h_ * h_;
    for (std::size_t c = 0; c < constraints_.size(); ++c) {
      const Constraint& k = constraints_[c];
      const double lambda = tension_[static_cast<std::size_t>(k.spring)] * h2;
      lambda_[c] = lambda;
      if (lambda == 0.0) continue;
      const Vec3 d = start[k.mass1] - start[k.mass2];
      const double l = d.norm();
      if (l == 0.0) continue;
      const Vec3 move = (lambda / l) * d;
      pos[k.mass1] += k.w1 * move;
      pos[k.mass2] -= k.w2 * move;
    }
  }

  int iterations_ = 10;  // Gauss-Seidel sweeps over the constraints per substep
  int substeps_ = 1;     // substeps per integrator step
  std::vector<Vec3> external_;   // [n] N
  std::vector<Vec3> previous_;   // [n] m, positions at the start of the substep
  std::vector<Constraint> constraints_;  // the projected springs, in colour order (this step)
  std::vector<double> lambda_;   // [constraints] their multipliers in this substep
  std::vector<int> order_;       // [springs] spring indices in colour order
  std::vector<int> ends_;        // [2 springs] the ends the colouring was made for
  std::vector<double> tension_;  // [springs] N, lambda / h^2 at the end of the last substep
  double h_ = 0.0;               // s, the substep of this step
  double inverseH2_ = 0.0;       // 1/s^2
  bool warmStart_ = false;  // scene: "warm_start": 1 (off by default: unstable below about 16 substeps at r = 64)
};

}  // namespace

void registerXpbd(Registry& registry) {
  registry.addIntegrator(std::string(Xpbd::kName), [] { return std::make_unique<Xpbd>(); });
}

}  // namespace springlab::net
