// The implicit integrators built on exercises 2.8 and 2.9 (given). They run on any scene
// that provides its force Jacobians (Simulation::addForceJacobian).
#include <algorithm>
#include <cmath>

#include <springlab/net/net.hpp>
#include <springlab/solvers/block_jacobi_cg.hpp>
#include <springlab/solvers/smoothed_aggregation.hpp>

namespace springlab::net {

namespace {

// Both variants end the same way: v += dv, then x += dt v with the new velocity.
void applyVelocityChange(Simulation& sim, const std::vector<Vec3>& dv, double dt) {
  State& s = sim.state;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    s.vel[i] += dv[i];
    s.pos[i] += dt * s.vel[i];
  }
  s.time += dt;
}

// Linearised backward Euler, the whole sparse system solved by conjugate gradients.
class ImplicitEuler final : public Integrator {
 public:
  static constexpr std::string_view kName = "implicit_euler";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  double stabilityConstant() const override { return INFINITY; }
  void reset() override {
    guess_.resize(0);
    lastIterations_ = 0;
  }

  void step(Simulation& sim, double dt) override {
    const int n = sim.numOfMasses();
    // Forces and their Jacobians at the start of the step.
    sim.evaluateForces(sim.state, sim.force);
    sim.forceJacobian(sim.state, jacobian_, kName);

    // The system over the free masses (exercise 2.8).
    free_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) free_[static_cast<std::size_t>(i)] = sim.inverseMass(i) != 0.0;
    system_.prepare(free_, jacobian_);
    assembleImplicitEuler(sim, sim.force, jacobian_, dt, system_);

    // Conjugate gradients, warm-started from the last step's dv where the rows still fit.
    dv_.assign(static_cast<std::size_t>(n), Vec3::Zero());
    if (system_.size() > 0) {
      if (guess_.size() != system_.size()) guess_.setZero(system_.size());
      // Block Jacobi is cheapest where the system is well conditioned (heavy masses: a few
      // iterations); smoothed aggregation where block Jacobi's count runs into the hundreds.
      const std::string& choice = sim.solver.preconditioner;
      const bool amg =
          choice == "smoothed_aggregation" || (choice == "auto" && lastIterations_ > autoIterations(sim.solver.tolerance));
      int iterations = 0;
      if (amg) {
        amg_.tolerance = sim.solver.tolerance;
        iterations = amg_.solve(system_, guess_);  // "auto" stays with it until reset()
      } else {
        cg_.tolerance = sim.solver.tolerance;  // the scene's choice, 1e-6 by default
        iterations = cg_.solve(system_, guess_);
        lastIterations_ = iterations;
      }
      sim.stats.solverIterations += iterations;
      for (int i = 0; i < n; ++i) {
        if (system_.row(i) >= 0) dv_[static_cast<std::size_t>(i)] = guess_.segment<3>(system_.row(i));
      }
    }
    applyVelocityChange(sim, dv_, dt);
  }

 private:
  ForceJacobian jacobian_;
  BlockSystem system_;
  std::vector<char> free_;      // [n] 1 for a mass the forces move
  std::vector<Vec3> dv_;        // [n] m/s
  Eigen::VectorXd guess_;       // [3 x free masses] last solution, CG's starting point
  BlockJacobiCG cg_;
  SmoothedAggregationCG amg_;
  // "auto": block Jacobi above this count switches: 25 iterations per decade of the tolerance
  // (150 at 1e-6, 75 at 1e-3), since CG's count grows with the digits it must reach. Measured
  // on the fabric's 5 s run: at 1e-6 block Jacobi is cheaper at r = 32 (at most about 125
  // iterations a step), smoothed aggregation from r = 64 on (about 250); at 1e-3 at r = 64
  // block Jacobi averages 68 a step at 13.6 ms, smoothed aggregation 9 at 9.9 ms.
  static int autoIterations(double tolerance) {
    const double decades = tolerance > 0.0 ? -std::log10(tolerance) : 6.0;
    return static_cast<int>(25.0 * std::max(1.0, decades));
  }
  int lastIterations_ = 0;                    // block-Jacobi CG iterations of the last step
};

// Linearised backward Euler keeping each mass's own 3x3 block only (exercise 2.9): one
// block-Jacobi sweep of implicit Euler's system from dv = 0, each mass solved against its
// neighbours' old velocities. On light fabric at the scene's dt that is past its stable step:
// the cloth of net_hanging.json gains energy and never comes to rest (handouts/02_net.md, 2.f,
// gives the command that shows it). With the scene's
// "solver": {"block_sweeps": N, "block_tolerance": t} it sweeps on (given code) towards the
// full solve: dv_i = D_i^-1 (b_i + sum over its springs of C dv_j), until the residual
// relative to |b| is below t or after N sweeps; each sweep after the first counts as a solver
// iteration.
class ImplicitEulerBlocks final : public Integrator {
 public:
  static constexpr std::string_view kName = "implicit_euler_blocks";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  double stabilityConstant() const override { return INFINITY; }

  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    sim.forceJacobian(sim.state, jacobian_, kName);
    dv_.assign(static_cast<std::size_t>(sim.numOfMasses()), Vec3::Zero());
    implicitEulerBlocks(sim, sim.force, jacobian_, dt, diagonal_, dv_);
    if (sim.solver.blockSweeps > 1) sim.stats.solverIterations += sweepOn(sim, dt);
    applyVelocityChange(sim, dv_, dt);
  }

 private:
  // More block-Jacobi sweeps from the first one's dv. The first sweep solved D_i dv_i = b_i,
  // so b_i = D_i dv_i is known without assembling again; the pair (i, j) of the Jacobian
  // couples the two rows by -C with C = -dt dv - dt^2 dx (exercise 2.9 adds C to both
  // diagonal blocks). Returns the sweeps made.
  int sweepOn(const Simulation& sim, double dt) {
    const std::size_t n = dv_.size();
    b_.resize(n);
    inverse_.resize(n);
    coupled_.resize(n);
    double bNorm2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      b_[i] = diagonal_[i] * dv_[i];
      inverse_[i] = sim.inverseMass(static_cast<int>(i)) == 0.0 ? Mat3::Zero() : Mat3(diagonal_[i].inverse());
      bNorm2 += b_[i].squaredNorm();
    }
    const double tolerance2 = sim.solver.blockTolerance * sim.solver.blockTolerance * bNorm2;
    int sweeps = 0;
    while (sweeps + 1 < sim.solver.blockSweeps) {
      // sum over each mass's springs of C dv_other, at the last sweep's dv.
      std::fill(coupled_.begin(), coupled_.end(), Vec3::Zero());
      for (const ForceJacobian::Pair& p : jacobian_.pairs) {
        const Mat3 C = -dt * p.dv - dt * dt * p.dx;
        coupled_[static_cast<std::size_t>(p.i)] += C * dv_[static_cast<std::size_t>(p.j)];
        coupled_[static_cast<std::size_t>(p.j)] += C * dv_[static_cast<std::size_t>(p.i)];
      }
      // Residual of the last sweep (free masses only), then the next sweep.
      double residual2 = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        if (inverse_[i].isZero()) continue;
        residual2 += (b_[i] + coupled_[i] - diagonal_[i] * dv_[i]).squaredNorm();
      }
      if (residual2 <= tolerance2) break;
      for (std::size_t i = 0; i < n; ++i) dv_[i] = inverse_[i] * (b_[i] + coupled_[i]);
      ++sweeps;
    }
    return sweeps;
  }

  ForceJacobian jacobian_;
  std::vector<Mat3> diagonal_;  // [n] each mass's block of the implicit system
  std::vector<Vec3> dv_;        // [n] m/s
  std::vector<Vec3> b_;         // [n] right side, N s
  std::vector<Mat3> inverse_;   // [n] inverse diagonal blocks; zero for pinned masses
  std::vector<Vec3> coupled_;   // [n] sum of C dv_j over each mass's springs
};

}  // namespace

void registerXpbd(Registry& registry);                // xpbd.cpp
void registerProjectiveDynamics(Registry& registry);  // projective_dynamics.cpp

void registerIntegrators(Registry& registry) {
  registerXpbd(registry);
  registerProjectiveDynamics(registry);
  registry.addIntegrator("implicit_euler", [] { return std::make_unique<ImplicitEuler>(); });
  registry.addIntegrator("implicit_euler_blocks", [] { return std::make_unique<ImplicitEulerBlocks>(); });
}

}  // namespace springlab::net
