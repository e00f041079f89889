#pragma once
// General solver code: the one preconditioned conjugate-gradient loop every preconditioner of
// a BlockSystem runs (block Jacobi, smoothed aggregation): only z = M^-1 r differs.
#include <functional>

#include <Eigen/Core>

#include <springlab/solvers/block_system.hpp>

namespace springlab {

// z = M^-1 r for a symmetric positive definite M (z is resized by the callee).
using Preconditioner = std::function<void(const Eigen::VectorXd& r, Eigen::VectorXd& z)>;

// The loop's vectors, kept by the caller between solves so a step allocates nothing.
struct ConjugateGradientVectors {
  Eigen::VectorXd r, z, p, q;  // residual, preconditioned residual, direction, A p
};

// Textbook preconditioned CG (Saad, Algorithm 9.1) on A x = b of `system`, from the warm
// start x (zeroed when its size is not the system's), stopping at |b - A x| <= tolerance |b|
// or after 2 x rows iterations (as Eigen's ConjugateGradient). Returns the iterations made.
// Dot products run in a fixed order: the result does not depend on the number of threads.
int preconditionedCG(const BlockSystem& system, Eigen::VectorXd& x, double tolerance,
                     const Preconditioner& precondition, ConjugateGradientVectors& v);

}  // namespace springlab
