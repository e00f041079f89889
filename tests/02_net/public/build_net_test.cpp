// Exercise 2.1: the grid, its springs by kind, its triangles, masses and pins.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using BuildNet = springlab::testing::Seeded;
using springlab::testing::quietNet;

// Column and row of mass `index` in a grid of `columns` columns.
std::pair<int, int> cell(int index, int columns) { return {index % columns, index / columns}; }

TEST_F(BuildNet, GridOfMassesAtRest) {
  NetParameters p = quietNet(integer(2, 12), uniform(0.5, 2.0), uniform(0.5, 2.0));
  p.origin = vec3(-1, 1);
  p.uAxis = Vec3(1, 0, 0);
  p.vAxis = Vec3(0, -1, 0);
  const NetLayout net = buildNet(p);
  const int columns = p.resolution, rows = gridRows(p);
  ASSERT_EQ(net.masses.size(), static_cast<std::size_t>(columns * rows))
      << "a grid of " << columns << " x " << rows << " needs " << columns * rows << " masses " << seedText();
  ASSERT_EQ(net.pos.size(), net.masses.size()) << "one position per mass";
  ASSERT_EQ(net.vel.size(), net.masses.size()) << "one velocity per mass";
  for (int k = 0; k < columns * rows; ++k) {
    const auto [i, j] = cell(k, columns);
    const Vec3 want = p.origin + (p.width * i / (columns - 1)) * p.uAxis + (p.height * j / (rows - 1)) * p.vAxis;
    ASSERT_LT((net.pos[k] - want).norm(), 1e-12)
        << "mass " << k << " (column " << i << ", row " << j << ") is not at origin + u width i/(columns-1) + "
        << "v height j/(rows-1) " << seedText();
    ASSERT_EQ(net.vel[k], Vec3::Zero()) << "the net starts at rest";
  }
}

TEST_F(BuildNet, SpringsOfEachKindJoinTheRightNeighbours) {
  const NetParameters p = quietNet(integer(3, 10), 1.0, uniform(0.6, 1.6));
  const NetLayout net = buildNet(p);
  const int c = p.resolution, r = gridRows(p);
  // Expected (kind, lower index, higher index) of every spring.
  std::multiset<std::tuple<SpringKind, int, int>> want, got;
  auto add = [&](SpringKind kind, int a, int b) { want.insert({kind, std::min(a, b), std::max(a, b)}); };
  for (int j = 0; j < r; ++j) {
    for (int i = 0; i < c; ++i) {
      const int k = j * c + i;
      if (i + 1 < c) add(SpringKind::Structural, k, k + 1);
      if (j + 1 < r) add(SpringKind::Structural, k, k + c);
      if (i + 1 < c && j + 1 < r) {
        add(SpringKind::Shear, k, k + c + 1);
        add(SpringKind::Shear, k + 1, k + c);
      }
      if (i + 2 < c) add(SpringKind::Bend, k, k + 2);
      if (j + 2 < r) add(SpringKind::Bend, k, k + 2 * c);
    }
  }
  for (const Spring& s : net.springs) {
    got.insert({s.kind, std::min(s.mass1, s.mass2), std::max(s.mass1, s.mass2)});
    ASSERT_TRUE(s.kind == SpringKind::Structural || s.kind == SpringKind::Shear || s.kind == SpringKind::Bend)
        << "Spring::kind must be SpringKind::Structural, Shear or Bend, not " << s.kind;
    EXPECT_DOUBLE_EQ(s.springConstant, p.springs[s.kind].stiffness) << "each spring takes its kind's stiffness";
    EXPECT_DOUBLE_EQ(s.frictionConstant, p.springs[s.kind].damping) << "each spring takes its kind's damping";
    EXPECT_NEAR(s.springLength, (net.pos[s.mass1] - net.pos[s.mass2]).norm(), 1e-12)
        << "springs start at their rest length " << seedText();
  }
  EXPECT_EQ(got, want) << "a " << c << " x " << r << " net needs structural springs to its grid neighbours, shear "
                       << "springs across both diagonals of each cell and bend springs to the masses two apart, "
                       << "each once and with Spring::kind set " << seedText();
}

TEST_F(BuildNet, DisabledKindHasNoSprings) {
  for (SpringKind off : {SpringKind::Structural, SpringKind::Shear, SpringKind::Bend}) {
    NetParameters p = quietNet(integer(3, 8));
    p.springs[off].enabled = false;
    const NetLayout net = buildNet(p);
    int others = 0;
    for (const Spring& s : net.springs) {
      EXPECT_NE(s.kind, off) << "a disabled kind (" << off << ") must have no springs " << seedText();
      ++others;
    }
    EXPECT_GT(others, 0) << "the enabled kinds keep their springs";
  }
}

TEST_F(BuildNet, TrianglesCoverTheClothCounterClockwise) {
  NetParameters p = quietNet(integer(2, 10), uniform(0.5, 2.0), uniform(0.5, 2.0));
  p.uAxis = Vec3(0, 0, 1);
  p.vAxis = Vec3(1, 0, 0);
  const NetLayout net = buildNet(p);
  const int c = p.resolution, r = gridRows(p);
  ASSERT_EQ(net.triangles.size(), static_cast<std::size_t>(2 * (c - 1) * (r - 1)))
      << "two triangles per cell " << seedText();
  const Vec3 up = p.uAxis.cross(p.vAxis);
  double area = 0.0;
  for (const Triangle& t : net.triangles) {
    const Vec3 n = (net.pos[t.b] - net.pos[t.a]).cross(net.pos[t.c] - net.pos[t.a]);
    EXPECT_GT(n.dot(up), 0.0) << "triangle (" << t.a << ", " << t.b << ", " << t.c
                              << ") is not counter-clockwise seen from u_axis x v_axis " << seedText();
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, p.width * p.height, 1e-9) << "the triangles must cover the cloth exactly once " << seedText();
}

TEST_F(BuildNet, MassesAreConstantOrFromArealDensity) {
  NetParameters p = quietNet(integer(2, 12), uniform(0.5, 2.0), uniform(0.5, 2.0));
  p.particleMass = uniform(0.01, 2.0);
  for (const Mass& m : buildNet(p).masses) EXPECT_DOUBLE_EQ(m.m, p.particleMass) << "constant mass per particle";

  p.massModel = MassModel::Density;
  p.arealDensity = uniform(0.1, 3.0);
  const NetLayout net = buildNet(p);
  double total = 0.0;
  for (const Mass& m : net.masses) total += m.m;
  EXPECT_NEAR(total, p.arealDensity * p.width * p.height, 1e-9)
      << "with an areal density the net weighs density x width x height " << seedText();
  // A corner carries a third of one or two triangles; an inner mass of six.
  const int c = p.resolution;
  if (c >= 3 && gridRows(p) >= 3) {
    EXPECT_GT(net.masses[c + 1].m, 2.0 * net.masses[0].m) << "inner masses carry more area than corners";
  }
}

TEST_F(BuildNet, PinsHoldCornersAndEdges) {
  NetParameters p = quietNet(integer(3, 9));
  const int c = p.resolution, r = gridRows(p);
  p.pins = {Pin::Corner10, Pin::EdgeV1};
  const NetLayout net = buildNet(p);
  for (int k = 0; k < c * r; ++k) {
    const auto [i, j] = cell(k, c);
    const bool want = (i == c - 1 && j == 0) || j == r - 1;
    EXPECT_EQ(net.masses[k].pinned, want) << "mass at column " << i << ", row " << j
                                          << (want ? " must be pinned" : " must be free") << " for pins corner_10 and edge_v1";
  }
}

}  // namespace
}  // namespace springlab::net
