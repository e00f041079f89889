// Exercise 3.2, springs from the mesh (labs/03_softbody/mesh_springs.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>

namespace springlab::softbody {
namespace {

std::set<std::pair<int, int>> pairsOf(const std::vector<Spring>& springs) {
  std::set<std::pair<int, int>> out;
  for (const Spring& s : springs) out.insert(std::minmax(s.mass1, s.mass2));
  return out;
}

TEST(MeshSprings, OneSpringPerEdgeOfAClosedSurface) {
  // A closed triangle surface has E = 3 F / 2 edges; every edge once, none twice.
  for (const SurfaceMesh& m : {boxMesh(Vec3(1, 2, 3), 1), icosphere(1.0, 2), uvSphere(1.0, 5, 7)}) {
    const std::vector<Spring> springs = edgeSprings(m, 100.0, 1.0);
    EXPECT_EQ(springs.size(), 3 * m.triangles.size() / 2)
        << "a closed surface of " << m.triangles.size() << " triangles has " << 3 * m.triangles.size() / 2
        << " edges; each edge needs exactly one spring";
    EXPECT_EQ(pairsOf(springs).size(), springs.size()) << "two springs join the same pair of masses";
    for (const Spring& s : springs) {
      EXPECT_EQ(s.kind, SpringKind::Structural) << "edge springs are structural";
      EXPECT_EQ(s.springConstant, 100.0);
      EXPECT_EQ(s.frictionConstant, 1.0);
    }
  }
}

TEST(MeshSprings, RestAtTheMeshShape) {
  const SurfaceMesh m = uvSphere(0.7, 4, 6);
  for (const Spring& s : edgeSprings(m, 50.0, 0.0)) {
    EXPECT_NEAR(s.springLength, (m.vertices[s.mass1] - m.vertices[s.mass2]).norm(), 1e-12)
        << "a spring's rest length must be its edge's length, so the mesh starts at rest";
  }
  for (const Spring& s : oppositeSprings(m, 50.0, 0.0)) {
    EXPECT_NEAR(s.springLength, (m.vertices[s.mass1] - m.vertices[s.mass2]).norm(), 1e-12)
        << "an opposite spring must rest at the mesh's shape too";
  }
}

TEST(MeshSprings, RingHasOneSpringPerSegment) {
  const SurfaceMesh ring = ringMesh(17, 30.0);
  const std::vector<Spring> springs = edgeSprings(ring, 400.0, 15.0);
  ASSERT_EQ(springs.size(), 17u) << "a ring of 17 points has 17 segments, each a spring";
  for (const Spring& s : springs) {
    EXPECT_EQ((s.mass2 - s.mass1 + 17) % 17 == 1 || (s.mass1 - s.mass2 + 17) % 17 == 1, true)
        << "a ring spring must join neighbours along the loop";
    EXPECT_NEAR(s.springLength, 2 * 30.0 * std::sin(std::numbers::pi / 17), 1e-9) << "wrong rest length";
  }
}

TEST(MeshSprings, OppositeSpringsJoinAntipodesOfASphere) {
  // On an icosphere every vertex has an exact antipode: one spring per antipodal pair.
  const SurfaceMesh m = icosphere(1.0, 1);
  const std::vector<Spring> springs = oppositeSprings(m, 10.0, 0.5);
  EXPECT_EQ(springs.size(), m.vertices.size() / 2) << "each antipodal pair needs exactly one spring";
  for (const Spring& s : springs) {
    EXPECT_NEAR(s.springLength, 2.0, 1e-9) << "an opposite spring must cross the whole sphere";
    EXPECT_EQ(s.kind, SpringKind::Extra) << "opposite springs are of kind SpringKind::Extra";
  }
}

TEST(MeshSprings, SecondRingCrossesEveryEdgeOnce) {
  // Across each edge of an icosphere lies a different pair of corners: E springs, none an edge.
  const SurfaceMesh m = icosphere(1.0, 1);
  const auto edges = pairsOf(edgeSprings(m, 1.0, 0.0));
  const std::vector<Spring> cross = secondRingSprings(m, 5.0, 0.1);
  EXPECT_EQ(cross.size(), edges.size()) << "one spring across each of the " << edges.size() << " edges";
  EXPECT_EQ(pairsOf(cross).size(), cross.size()) << "two second-ring springs join the same masses";
  for (const Spring& s : cross) {
    EXPECT_FALSE(edges.count(std::minmax(s.mass1, s.mass2))) << "a second-ring spring must not lie on an edge";
    EXPECT_EQ(s.kind, SpringKind::Bend) << "second-ring springs are of kind SpringKind::Bend";
  }
  // In 2D: i to i + 2 around the loop.
  const std::vector<Spring> ring = secondRingSprings(ringMesh(9, 1.0), 5.0, 0.1);
  ASSERT_EQ(ring.size(), 9u) << "a loop of 9 points has 9 skip-one pairs";
  for (const Spring& s : ring) {
    EXPECT_TRUE((s.mass2 - s.mass1 + 9) % 9 == 2 || (s.mass1 - s.mass2 + 9) % 9 == 2)
        << "a 2D second-ring spring must skip exactly one point";
  }
}

}  // namespace
}  // namespace springlab::softbody
