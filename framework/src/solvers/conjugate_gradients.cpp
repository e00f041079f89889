// The preconditioned conjugate-gradient loop (see springlab/solvers/conjugate_gradients.hpp).
#include <springlab/solvers/conjugate_gradients.hpp>

namespace springlab {

int preconditionedCG(const BlockSystem& system, Eigen::VectorXd& x, double tolerance,
                     const Preconditioner& precondition, ConjugateGradientVectors& v) {
  const Eigen::VectorXd& b = system.rhs();
  const Eigen::Index rows = b.size();
  if (x.size() != rows) x.setZero(rows);
  const double bNorm2 = b.squaredNorm();
  if (rows == 0 || bNorm2 == 0.0) {
    x.setZero();
    return 0;
  }

  system.multiply(x, v.q);
  v.r = b - v.q;
  const double stop2 = tolerance * tolerance * bNorm2;
  const int maxIterations = static_cast<int>(2 * rows);
  precondition(v.r, v.z);
  v.p = v.z;
  double rz = v.r.dot(v.z);
  int iterations = 0;
  while (v.r.squaredNorm() > stop2 && iterations < maxIterations) {
    system.multiply(v.p, v.q);
    const double alpha = rz / v.p.dot(v.q);
    x += alpha * v.p;
    v.r -= alpha * v.q;
    precondition(v.r, v.z);
    const double rzNext = v.r.dot(v.z);
    v.p = v.z + (rzNext / rz) * v.p;
    rz = rzNext;
    ++iterations;
  }
  return iterations;
}

}  // namespace springlab
