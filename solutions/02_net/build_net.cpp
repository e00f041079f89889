#include <springlab/net/exercises.hpp>

namespace springlab::net {

NetLayout buildNet(const NetParameters& p) {
  // BEGIN EXERCISE 2.1
  NetLayout layout;
  const int columns = p.resolution;
  const int rows = gridRows(p);
  auto index = [columns](int i, int j) { return j * columns + i; };

  // Masses on the grid, at rest; pinned ones where the scene says.
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const double u = static_cast<double>(i) / (columns - 1);
      const double v = static_cast<double>(j) / (rows - 1);
      layout.pos.push_back(p.origin + u * p.width * p.uAxis + v * p.height * p.vAxis);
      layout.vel.push_back(Vec3::Zero());
      layout.masses.push_back(Mass{p.particleMass, pinnedAt(p.pins, i, j, columns, rows)});
    }
  }

  // Two counter-clockwise triangles per cell.
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < columns; ++i) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      layout.triangles.push_back({a, b, c});
      layout.triangles.push_back({a, c, d});
    }
  }

  // Areal density: each mass carries a third of the area of its triangles.
  if (p.massModel == MassModel::Density) {
    for (Mass& m : layout.masses) m.m = 0.0;
    for (const Triangle& t : layout.triangles) {
      const Vec3& a = layout.pos[t.a];
      const double third = p.arealDensity * (layout.pos[t.b] - a).cross(layout.pos[t.c] - a).norm() / 6.0;
      layout.masses[t.a].m += third;
      layout.masses[t.b].m += third;
      layout.masses[t.c].m += third;
    }
  }

  // Springs of each enabled kind, at their rest length.
  auto connect = [&](int a, int b, SpringKind kind) {
    const SpringKindParameters& k = p.springs[kind];
    if (!k.enabled) return;
    const double length = (layout.pos[a] - layout.pos[b]).norm();
    layout.springs.push_back(Spring{a, b, k.stiffness, length, k.damping, kind});
  };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      if (i + 1 < columns) connect(index(i, j), index(i + 1, j), SpringKind::Structural);
      if (j + 1 < rows) connect(index(i, j), index(i, j + 1), SpringKind::Structural);
      if (i + 1 < columns && j + 1 < rows) {
        connect(index(i, j), index(i + 1, j + 1), SpringKind::Shear);
        connect(index(i + 1, j), index(i, j + 1), SpringKind::Shear);
      }
      if (i + 2 < columns) connect(index(i, j), index(i + 2, j), SpringKind::Bend);
      if (j + 2 < rows) connect(index(i, j), index(i, j + 2), SpringKind::Bend);
    }
  }
  return layout;
  // END EXERCISE 2.1
}

}  // namespace springlab::net
