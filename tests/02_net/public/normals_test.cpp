// Exercise 2.3, vertex normals and areas (labs/02_net/normals.cpp): its public tests.
#include <gtest/gtest.h>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using VertexNormals = springlab::testing::Seeded;
using springlab::testing::quietNet;

TEST_F(VertexNormals, FlatClothFacesUAxisCrossVAxis) {
  NetParameters p = quietNet(integer(2, 9), uniform(0.5, 2), uniform(0.5, 2));
  p.uAxis = Vec3(1, 0, 0);
  p.vAxis = Vec3(0, -1, 0);
  const NetLayout net = buildNet(p);
  std::vector<Vec3> normals;
  std::vector<double> areas;
  vertexNormals(net.pos, net.triangles, normals, areas);
  ASSERT_EQ(normals.size(), net.pos.size()) << "one normal per mass";
  for (const Vec3& n : normals) {
    EXPECT_LT((n - p.uAxis.cross(p.vAxis)).norm(), 1e-12)
        << "a flat cloth's vertex normals are all u_axis x v_axis, of unit length " << seedText();
  }
}

TEST_F(VertexNormals, AreasAddUpToTheClothArea) {
  NetParameters p = quietNet(integer(2, 9), uniform(0.5, 2), uniform(0.5, 2));
  NetLayout net = buildNet(p);
  for (Vec3& x : net.pos) x += vec3(-0.01, 0.01);  // areas follow the current shape
  std::vector<Vec3> normals;
  std::vector<double> areas;
  vertexNormals(net.pos, net.triangles, normals, areas);
  ASSERT_EQ(areas.size(), net.pos.size()) << "one area per mass";
  double total = 0.0, surface = 0.0;
  for (double a : areas) total += a;
  for (const Triangle& t : net.triangles) {
    surface += 0.5 * (net.pos[t.b] - net.pos[t.a]).cross(net.pos[t.c] - net.pos[t.a]).norm();
  }
  EXPECT_NEAR(total, surface, 1e-12) << "each triangle gives a third of its area to each of its masses " << seedText();
}

TEST_F(VertexNormals, FoldAveragesItsFacesByArea) {
  // Two triangles sharing the edge 0-1, folded: the shared masses' normal is the unit
  // vector along the sum of both area-weighted face normals; the others keep their face's.
  const double h = uniform(0.2, 2.0);
  const std::vector<Vec3> pos{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 1), Vec3(0.5, h, -1)};
  const std::vector<Triangle> tris{{0, 1, 2}, {1, 0, 3}};
  std::vector<Vec3> normals;
  std::vector<double> areas;
  vertexNormals(pos, tris, normals, areas);
  const Vec3 n1 = (pos[1] - pos[0]).cross(pos[2] - pos[0]);
  const Vec3 n2 = (pos[0] - pos[1]).cross(pos[3] - pos[1]);
  EXPECT_LT((normals[0] - (n1 + n2).normalized()).norm(), 1e-12)
      << "a shared vertex's normal is normalize(sum of (b - a) x (c - a)) " << seedText();
  EXPECT_LT((normals[2] - n1.normalized()).norm(), 1e-12) << "a vertex of one face takes its face's unit normal";
  EXPECT_LT((normals[3] - n2.normalized()).norm(), 1e-12) << "a vertex of one face takes its face's unit normal";
  EXPECT_NEAR(areas[0], (n1.norm() + n2.norm()) / 6.0, 1e-12) << "a third of each adjacent triangle's area";
}

}  // namespace
}  // namespace springlab::net
