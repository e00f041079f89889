#include <algorithm>
#include <cmath>
#include <cstdint>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

std::vector<std::pair<int, int>> closePairs(const std::vector<Vec3>& pos, double distance) {
  // BEGIN EXERCISE 2.10
  std::vector<std::pair<int, int>> pairs;
  const int n = static_cast<int>(pos.size());
  if (n < 2 || !(distance > 0.0)) return pairs;

  // Cells of size `distance`, hashed into a table of 2n buckets (Teschner et al. 2003).
  const std::int64_t buckets = 2 * static_cast<std::int64_t>(n);
  auto cellOf = [distance](const Vec3& x) {
    return Eigen::Vector3i(static_cast<int>(std::floor(x.x() / distance)), static_cast<int>(std::floor(x.y() / distance)),
                           static_cast<int>(std::floor(x.z() / distance)));
  };
  auto hash = [buckets](const Eigen::Vector3i& c) {
    const std::int64_t h = (static_cast<std::int64_t>(c.x()) * 73856093) ^ (static_cast<std::int64_t>(c.y()) * 19349663) ^
                           (static_cast<std::int64_t>(c.z()) * 83492791);
    return static_cast<std::size_t>(((h % buckets) + buckets) % buckets);
  };

  // Counting sort of the points by bucket: start[b] .. start[b + 1] lists bucket b's points.
  std::vector<std::size_t> start(static_cast<std::size_t>(buckets) + 1, 0);
  std::vector<std::size_t> bucketOf(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) {
    bucketOf[i] = hash(cellOf(pos[i]));
    ++start[bucketOf[i] + 1];
  }
  for (std::size_t b = 0; b < static_cast<std::size_t>(buckets); ++b) start[b + 1] += start[b];
  std::vector<int> sorted(pos.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < pos.size(); ++i) sorted[fill[bucketOf[i]]++] = static_cast<int>(i);

  // Each point looks at its own cell and the 26 around it, keeping partners after it.
  const double d2 = distance * distance;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3i c = cellOf(pos[i]);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const std::size_t b = hash(c + Eigen::Vector3i(dx, dy, dz));
          for (std::size_t k = start[b]; k < start[b + 1]; ++k) {
            const int j = sorted[k];
            if (j > i && (pos[i] - pos[j]).squaredNorm() < d2) pairs.emplace_back(i, j);
          }
        }
      }
    }
  }

  // Two neighbouring cells may share a bucket: keep each pair once.
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
  // END EXERCISE 2.10
}

void separatePair(Vec3& x1, Vec3& x2, Vec3& v1, Vec3& v2, double w1, double w2, double thickness) {
  // BEGIN EXERCISE 2.10
  const double w = w1 + w2;
  if (w == 0.0) return;
  const Vec3 d = x1 - x2;
  const double l = d.norm();
  if (l >= thickness) return;
  const Vec3 n = l > 0.0 ? Vec3(d / l) : Vec3::UnitY();

  // Positions: apart to the thickness, the lighter mass moving more.
  const double gap = thickness - l;
  x1 += (w1 / w) * gap * n;
  x2 -= (w2 / w) * gap * n;

  // Velocities: an inelastic contact along n, equal and opposite impulses.
  const double approach = (v1 - v2).dot(n);
  if (approach < 0.0) {
    v1 -= (w1 / w) * approach * n;
    v2 += (w2 / w) * approach * n;
  }
  // END EXERCISE 2.10
}

}  // namespace springlab::net
