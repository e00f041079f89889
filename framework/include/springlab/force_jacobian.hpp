#pragma once
// The derivatives of a system's forces, dF/dx and dF/dv, as 3x3 blocks: what implicit
// integrators (linearised backward Euler) need besides the forces. A scene provides them
// through Simulation::addForceJacobian; forces it leaves out are treated explicitly.
#include <vector>

#include <Eigen/Core>

namespace springlab {

using Mat3 = Eigen::Matrix3d;

struct ForceJacobian {
  // A force that depends on the difference of two masses' states, as a spring does:
  // F_i = f(x_i - x_j, v_i - v_j) and F_j = -F_i. Then, with D = dF_i/dx_i (dx below):
  //   dF_i/dx_i = dF_j/dx_j = D,   dF_i/dx_j = dF_j/dx_i = -D,   and the same for dv.
  struct Pair {
    int i = 0;                   // index of the first mass
    int j = 0;                   // index of the second mass
    Mat3 dx;                     // dF_i/dx_i, N/m (symmetric for springs)
    Mat3 dv;                     // dF_i/dv_i, N s/m
    // Unset, as Eigen leaves a matrix: pairs.resize(p) then writes each pair once, in
    // parallel, instead of zeroing 144 bytes per spring first.
    Pair() {}
    Pair(int first, int second, const Mat3& dxBlock, const Mat3& dvBlock) : i(first), j(second), dx(dxBlock), dv(dvBlock) {}
  };
  // A force on one mass that depends on its own state only (air friction, a ground).
  struct Own {
    int i = 0;
    Mat3 dx = Mat3::Zero();      // dF_i/dx_i, N/m
    Mat3 dv = Mat3::Zero();      // dF_i/dv_i, N s/m
  };

  std::vector<Pair> pairs;  // [p] in the same order at every step while the model is unchanged
  std::vector<Own> own;     // [o] several entries for one mass add up

  void clear() {
    pairs.clear();
    own.clear();
  }
};

}  // namespace springlab
