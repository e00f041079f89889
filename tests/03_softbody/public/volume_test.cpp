// Exercise 3.3: the volume (3D) and area (2D) inside the body.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

class Volume : public springlab::testing::Seeded {};

TEST_F(Volume, ExactForAUnitCube) {
  // A unit cube from 12 triangles, and the same cube split finer: volume 1 either way.
  for (int divisions : {1, 3}) {
    const SurfaceMesh cube = boxMesh(Vec3(0.5, 0.5, 0.5), divisions);
    EXPECT_NEAR(enclosedVolume(cube.vertices, cube.triangles), 1.0, 1e-12)
        << "a unit cube (" << cube.triangles.size() << " triangles, wound outward) must have volume 1";
  }
}

TEST_F(Volume, ExactForATetrahedron) {
  // Corners at the origin and on the axes: V = a b c / 6.
  const double a = 2.0, b = 3.0, c = 0.5;
  const std::vector<Vec3> pos = {Vec3::Zero(), Vec3(a, 0, 0), Vec3(0, b, 0), Vec3(0, 0, c)};
  const std::vector<Triangle> faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_NEAR(enclosedVolume(pos, faces), a * b * c / 6.0, 1e-12) << "the tetrahedron's volume is a b c / 6";
}

TEST_F(Volume, ChangesSignWhenTheWindingFlips) {
  const SurfaceMesh m = icosphere(1.3, 2), flipped = reversed(m);
  const double out = enclosedVolume(m.vertices, m.triangles), in = enclosedVolume(flipped.vertices, flipped.triangles);
  EXPECT_GT(out, 0.0) << "faces wound counter-clockwise seen from outside must give a positive volume";
  EXPECT_NEAR(in, -out, 1e-12) << "turning every face over must flip the volume's sign and keep its size";
}

TEST_F(Volume, DoesNotDependOnWhereTheOriginIs) {
  std::mt19937_64 rng(static_cast<unsigned>(integer(0, 1 << 30)));
  const SurfaceMesh m = springlab::testing::lumpySphere(2, 1.0, 0.2, Vec3::Zero(), rng);
  const double here = enclosedVolume(m.vertices, m.triangles);
  std::vector<Vec3> moved = m.vertices;
  const Vec3 shift = vec3(-50, 50);
  for (Vec3& v : moved) v += shift;
  EXPECT_NEAR(enclosedVolume(moved, m.triangles), here, 1e-9 * (1 + shift.norm()))
      << "moving a closed body must not change its volume " << seedText();
}

TEST_F(Volume, SphereConvergesToFourThirdsPiRCubed) {
  // Inscribed polyhedra approach the sphere from below, the error shrinking about 4x per split.
  const double r = 0.8, exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  double lastError = INFINITY;
  for (int s = 0; s <= 4; ++s) {
    const SurfaceMesh m = icosphere(r, s);
    const double error = exact - enclosedVolume(m.vertices, m.triangles);
    EXPECT_GT(error, 0.0) << "a polyhedron inscribed in a sphere encloses less than the sphere";
    EXPECT_LT(error, 0.35 * lastError) << "the volume error must shrink about fourfold per subdivision";
    lastError = error;
  }
  EXPECT_LT(lastError / exact, 3e-3) << "2562 vertices should give the sphere's volume within 0.3 %";
}

TEST(Area, ShoelaceIsExactForASquareAndConvergesForARing) {
  const std::vector<Vec3> square = {Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(3, 4, 0), Vec3(1, 4, 0)};
  const std::vector<Segment> loop = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  EXPECT_NEAR(enclosedArea(square, loop), 6.0, 1e-12) << "a 2 x 3 rectangle run counter-clockwise has area 6";
  const std::vector<Segment> backwards = {{1, 0}, {2, 1}, {3, 2}, {0, 3}};
  EXPECT_NEAR(enclosedArea(square, backwards), -6.0, 1e-12) << "run clockwise, the area must be negative";
  // A regular n-gon in a circle of radius r: (n/2) r^2 sin(2 pi / n), towards pi r^2.
  for (int n : {3, 17, 200}) {
    const SurfaceMesh ring = ringMesh(n, 30.0);
    EXPECT_NEAR(enclosedArea(ring.vertices, ring.segments), 0.5 * n * 900.0 * std::sin(2 * std::numbers::pi / n), 1e-9)
        << "wrong area for a regular " << n << "-gon";
  }
}

}  // namespace
}  // namespace springlab::softbody
