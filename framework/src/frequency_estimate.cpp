#include "springlab/frequency_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

namespace springlab {

namespace {

// One free coordinate: mass i, axis c.
struct Dof {
  int mass;
  int axis;
};

// Typical length of the scene, to size the finite-difference step.
double lengthScale(const Simulation& sim) {
  double sum = 0.0;
  for (const Spring& s : sim.springs()) sum += s.springLength;
  if (!sim.springs().empty() && sum > 0.0) return sum / static_cast<double>(sim.springs().size());
  return 1.0;
}

}  // namespace

FrequencyEstimate lanczosEstimate(Simulation& sim, const State& at, int maxIterations) {
  FrequencyEstimate result;
  const Stats savedStats = sim.stats;
  const std::vector<Vec3> savedForce = sim.force;

  // The coordinates that can move.
  std::vector<Dof> dofs;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (sim.inverseMass(i) == 0.0) continue;
    for (int c = 0; c < sim.dimension; ++c) dofs.push_back({i, c});
  }
  const int n = static_cast<int>(dofs.size());
  if (n == 0) return result;

  // B u = M^-1/2 K M^-1/2 u, with K d from central differences of the forces. The step moves
  // no coordinate by more than `eps`, small against the scene's lengths.
  const double eps = 1e-6 * lengthScale(sim);
  State plus = at, minus = at;
  std::vector<Vec3> fPlus, fMinus;
  auto applyB = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd d(n);
    for (int j = 0; j < n; ++j) d[j] = u[j] * std::sqrt(sim.inverseMass(dofs[j].mass));
    const double largest = d.cwiseAbs().maxCoeff();
    Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
    if (largest == 0.0) return out;
    const double h = eps / largest;
    for (int j = 0; j < n; ++j) {
      plus.pos[dofs[j].mass][dofs[j].axis] = at.pos[dofs[j].mass][dofs[j].axis] + h * d[j];
      minus.pos[dofs[j].mass][dofs[j].axis] = at.pos[dofs[j].mass][dofs[j].axis] - h * d[j];
    }
    sim.evaluateForces(plus, fPlus);
    sim.evaluateForces(minus, fMinus);
    result.forceEvaluations += 2;
    for (int j = 0; j < n; ++j) {
      const int i = dofs[j].mass, c = dofs[j].axis;
      out[j] = -(fPlus[i][c] - fMinus[i][c]) / (2.0 * h) * std::sqrt(sim.inverseMass(i));
    }
    return out;
  };

  // Lanczos with full reorthogonalisation from a fixed pseudo-random start (the same estimate
  // on every run); stop when the largest Ritz value settles.
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd q(n);
  for (int j = 0; j < n; ++j) q[j] = uniform(random);
  q.normalize();
  std::vector<Eigen::VectorXd> basis{q};
  std::vector<double> alpha, beta;
  double largest = 0.0;
  const int steps = std::min(maxIterations, n);
  for (int k = 0; k < steps; ++k) {
    Eigen::VectorXd w = applyB(basis.back());
    alpha.push_back(basis.back().dot(w));
    for (const Eigen::VectorXd& b : basis) w -= b.dot(w) * b;
    for (const Eigen::VectorXd& b : basis) w -= b.dot(w) * b;
    result.iterations = k + 1;

    // Largest eigenvalue of the tridiagonal matrix so far.
    const int m = static_cast<int>(alpha.size());
    Eigen::VectorXd diag = Eigen::Map<Eigen::VectorXd>(alpha.data(), m);
    Eigen::VectorXd sub = Eigen::Map<Eigen::VectorXd>(beta.data(), m - 1);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> tri;
    tri.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
    const double ritz = tri.eigenvalues().maxCoeff();
    const bool settled = k >= 4 && std::abs(ritz - largest) <= 1e-9 * std::abs(ritz);
    largest = ritz;

    const double b = w.norm();
    if (settled || b <= 1e-12 * std::max(std::abs(alpha.back()), 1e-300)) break;
    beta.push_back(b);
    basis.push_back(w / b);
  }

  sim.stats = savedStats;
  sim.force = savedForce;
  result.maxAngularFrequency = std::sqrt(std::max(largest, 0.0));
  return result;
}

}  // namespace springlab
