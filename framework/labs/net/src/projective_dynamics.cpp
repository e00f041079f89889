// Projective dynamics for springs (given loop; Liu et al. 2013 "fast mass-springs", Bouaziz
// et al. 2014), built on exercise 2.12. Implicit Euler as a minimisation over the new
// positions x of
//   1/(2h^2) |x - y|_M^2 + sum_springs k/2 |x_i - x_j - d|^2,   |d| = L0,
// with y = x_old + h v + h^2 M^-1 f_ext. The local step fixes d per spring (exercise 2.12);
// the global step solves (M/h^2 + sum k A^T A) x = M y/h^2 + sum k A^T d with a matrix that
// depends only on the model and h: factored once (sparse Cholesky), refactored when the model
// or dt changes, back-substituted once per iteration.
// What it leaves out: the springs' dampers (kd). A damper is not a projective energy; taken
// explicitly it is unstable at cloth's dt (kd/m dt >> 2), and as isotropic damping
// kd (v_i - v_j) in the matrix it resists every rotation of a spring, so a hanging cloth creeps
// into its drape over tens of seconds (measured: 10 s to get within 0.4 %). Implicit Euler's
// own numerical damping and the scene's air friction remain.
// Contacts, stretch limiting and self-collision stay in the scene's afterStep.
#include <cmath>
#include <memory>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <springlab/net/net.hpp>

#include "external_forces.hpp"

namespace springlab::net {

namespace {

class ProjectiveDynamics final : public Integrator {
 public:
  static constexpr std::string_view kName = "projective_dynamics";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  // No undamped limit: every iterate lowers a convex energy. (A fixed number of iterations
  // is not the minimum: on the 8 x 8 fabric, 10 iterations grow past about 0.8 s, a hundred
  // times the scene's dt; the stability chart finds it.)
  double stabilityConstant() const override { return INFINITY; }
  // A fixed number of iterations from the inertial prediction stops short of the implicit
  // step: it rests a little below the springs' equilibrium (handout 02, section 7.b).
  bool restsAtStaticEquilibrium() const override { return false; }
  void reset() override { model_.clear(); }

  std::vector<std::string> optionNames() const override { return {"iterations"}; }
  void setOption(const std::string& option, int value) override {
    if (option == "iterations") iterations_ = value;
    else Integrator::setOption(option, value);
  }

  void step(Simulation& sim, double h) override {
    State& s = sim.state;
    const int n = sim.numOfMasses();
    if (modelChanged(sim, h)) factor(sim, h);

    // Inertia: y = x + h v + h^2 M^-1 f_ext; masses the scene moves go on at their velocity.
    externalForces(sim, external_);
    target_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) target_[i] = s.pos[i] + h * s.vel[i] + (h * h * sim.inverseMass(i)) * external_[i];
    x_ = target_;  // the first iterate

    // The right side's constant part: inertia, and the pinned ends' coupling (their new
    // positions are known).
    const double inverseH = 1.0 / h, inverseH2 = inverseH * inverseH;
    constant_.assign(static_cast<std::size_t>(rows_), Vec3::Zero());
    for (int i = 0; i < n; ++i) {
      if (row_[i] >= 0) constant_[row_[i]] = (sim.masses[i].m * inverseH2) * target_[i];
    }
    for (const Spring& sp : sim.springs()) {
      const int r1 = row_[sp.mass1], r2 = row_[sp.mass2];
      if (r1 >= 0 && r2 < 0) constant_[r1] += sp.springConstant * target_[sp.mass2];
      if (r2 >= 0 && r1 < 0) constant_[r2] += sp.springConstant * target_[sp.mass1];
    }

    // Local step (exercise 2.12), then the global solve, `iterations` times.
    for (int it = 0; it < iterations_ && rows_ > 0; ++it) {
      rhs_ = constant_;
      for (const Spring& sp : sim.springs()) {
        const int r1 = row_[sp.mass1], r2 = row_[sp.mass2];
        if (r1 < 0 && r2 < 0) continue;
        const Vec3 d = sp.springConstant * projectSpring(x_[sp.mass1], x_[sp.mass2], sp.springLength);
        if (r1 >= 0) rhs_[r1] += d;
        if (r2 >= 0) rhs_[r2] -= d;
      }
      backSubstitute(rhs_);
      for (int i = 0; i < n; ++i) {
        if (row_[i] >= 0) x_[i] = rhs_[row_[i]];
      }
    }
    sim.stats.solverIterations += iterations_;
    sim.stats.backSubstitutions += iterations_;

    // Velocities from the positions' change (the kinematic masses keep theirs).
    for (int i = 0; i < n; ++i) {
      if (row_[i] >= 0) s.vel[i] = (x_[i] - s.pos[i]) * inverseH;
      s.pos[i] = x_[i];
    }
    s.time += h;
  }

 private:
  // Whether the matrix is stale: the free masses, their masses, the springs or h changed
  // (pinning, a grab, the panel's sliders, a study's scaling). O(n + springs) per step.
  bool modelChanged(const Simulation& sim, double h) {
    signature_.clear();
    signature_.push_back(h);
    for (int i = 0; i < sim.numOfMasses(); ++i) signature_.push_back(sim.inverseMass(i) == 0.0 ? 0.0 : sim.masses[i].m);
    for (const Spring& sp : sim.springs()) {
      signature_.insert(signature_.end(), {static_cast<double>(sp.mass1), static_cast<double>(sp.mass2), sp.springConstant});
    }
    if (signature_ == model_) return false;
    model_ = signature_;
    return true;
  }

  // M/h^2 + sum k A^T A over the free masses, one scalar matrix for x, y and z.
  void factor(Simulation& sim, double h) {
    const int n = sim.numOfMasses();
    row_.assign(static_cast<std::size_t>(n), -1);
    rows_ = 0;
    for (int i = 0; i < n; ++i) {
      if (sim.inverseMass(i) != 0.0) row_[i] = rows_++;
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
      if (row_[i] >= 0) entries.emplace_back(row_[i], row_[i], sim.masses[i].m / (h * h));
    }
    for (const Spring& sp : sim.springs()) {
      const double weight = sp.springConstant;
      const int r1 = row_[sp.mass1], r2 = row_[sp.mass2];
      if (r1 >= 0) entries.emplace_back(r1, r1, weight);
      if (r2 >= 0) entries.emplace_back(r2, r2, weight);
      if (r1 >= 0 && r2 >= 0) {
        entries.emplace_back(r1, r2, -weight);
        entries.emplace_back(r2, r1, -weight);
      }
    }
    Eigen::SparseMatrix<double> matrix(rows_, rows_);
    matrix.setFromTriplets(entries.begin(), entries.end());
    if (rows_ > 0) {
      cholesky_.compute(matrix);
      if (cholesky_.info() != Eigen::Success) {
        throw std::runtime_error("projective_dynamics: the global matrix M/h^2 + L is not positive definite "
                                 "(a mass of zero or a negative stiffness?)");
      }
    }
    ++sim.stats.factorizations;
  }

  // b = (M/h^2 + L)^-1 b, b a 3-vector per row: P A P^T = L L^T, so x = P^T L^-T L^-1 P b.
  // One pass over the factor per triangle for all three coordinates (Eigen's solve with a
  // 3-column right side makes three passes: about 2.5 times the time at r = 32).
  void backSubstitute(std::vector<Vec3>& b) {
    const auto& L = cholesky_.matrixL().nestedExpression();  // lower, column-major
    const auto& permutation = cholesky_.permutationP().indices();
    const bool permuted = permutation.size() > 0;
    permuted_.resize(b.size());
    for (int i = 0; i < rows_; ++i) permuted_[permuted ? permutation[i] : i] = b[i];
    // L z = P b, column by column: each column's diagonal, then the entries below it.
    for (int j = 0; j < rows_; ++j) {
      Eigen::SparseMatrix<double>::InnerIterator it(L, j);
      while (it && it.row() < j) ++it;
      const Vec3 z = permuted_[j] / it.value();
      permuted_[j] = z;
      for (++it; it; ++it) permuted_[it.row()] -= it.value() * z;
    }
    // L^T w = z, from the last row up: row j of L^T is column j of L.
    for (int j = rows_ - 1; j >= 0; --j) {
      Eigen::SparseMatrix<double>::InnerIterator it(L, j);
      while (it && it.row() < j) ++it;
      const double diagonal = it.value();
      Vec3 sum = permuted_[j];
      for (++it; it; ++it) sum -= it.value() * permuted_[it.row()];
      permuted_[j] = sum / diagonal;
    }
    for (int i = 0; i < rows_; ++i) b[i] = permuted_[permuted ? permutation[i] : i];
  }

  int iterations_ = 10;  // local/global iterations per step
  std::vector<double> model_, signature_;  // the model the factor belongs to, and the current one
  std::vector<int> row_;                   // [n] row of each free mass in the system, -1 when kinematic
  int rows_ = 0;                           // free masses
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> cholesky_;
  std::vector<Vec3> external_, target_, x_;  // [n] N, m (y), m (the iterate)
  std::vector<Vec3> constant_, rhs_, permuted_;  // [rows] right sides, the permuted solve
};

}  // namespace

void registerProjectiveDynamics(Registry& registry) {
  registry.addIntegrator(std::string(ProjectiveDynamics::kName), [] { return std::make_unique<ProjectiveDynamics>(); });
}

}  // namespace springlab::net
