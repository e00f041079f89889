// Long-range attachments (see springlab/net/tethers.hpp).
#include <cmath>
#include <cstddef>

#include <springlab/net/tethers.hpp>

namespace springlab::net {

int Tethers::apply(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<double>& inverseMass,
                   double maxStretch, double dt) {
  const std::size_t n = pos.size();
  if (rest_.size() != n) return 0;  // not built from this net's rest shape

  // The pins of this step: the viewer can pin and release masses between steps.
  pins_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (inverseMass[i] == 0.0) pins_.push_back(static_cast<int>(i));
  }
  if (pins_.empty()) return 0;

  const double reach = (1.0 + maxStretch) * (1.0 + maxStretch);  // squared bound per squared rest distance
  const double inverseDt = 1.0 / dt;
  int moved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (inverseMass[i] == 0.0) continue;
    bool movedThis = false;
    // Pins one after the other (Gauss-Seidel over the few pins): each move is inwards.
    for (const int p : pins_) {
      const std::size_t pi = static_cast<std::size_t>(p);
      const Vec3 d = pos[i] - pos[pi];
      const double bound2 = reach * (rest_[i] - rest_[pi]).squaredNorm();
      // Most masses are within reach: squared lengths, no square root.
      const double l2 = d.squaredNorm();
      if (l2 <= bound2) continue;
      const double l = std::sqrt(l2);
      const Vec3 move = (std::sqrt(bound2) / l - 1.0) * d;
      pos[i] += move;
      vel[i] += inverseDt * move;
      movedThis = true;
    }
    if (movedThis) ++moved;
  }

  return moved;
}

}  // namespace springlab::net
