// The cloth's drawn triangles stay outside the spheres of the shipped scenes: the colliders
// hold the masses colliders.contact_offset out of their surface, so the flat triangles
// between masses resting on a sphere do not cut into it (the viewer draws the sphere at its
// radius and the cloth as those triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>

#include <springlab/net/net.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// The deepest any drawn point of the cloth (each triangle's corners, edge midpoints and
// centroid) lies inside the sphere, in m (0 when none is inside).
double deepestInside(const Simulation& sim, const Vec3& center, double radius) {
  double deepest = 0.0;
  for (const Triangle& t : sim.triangles) {
    const Vec3& a = sim.state.pos[static_cast<std::size_t>(t.a)];
    const Vec3& b = sim.state.pos[static_cast<std::size_t>(t.b)];
    const Vec3& c = sim.state.pos[static_cast<std::size_t>(t.c)];
    for (const Vec3& p : {a, b, c, Vec3(0.5 * (a + b)), Vec3(0.5 * (b + c)), Vec3(0.5 * (c + a)),
                          Vec3((a + b + c) / 3.0)}) {
      deepest = std::max(deepest, radius - (p - center).norm());
    }
  }
  return deepest;
}

class ClothOnASphere : public ::testing::TestWithParam<std::string> {};

TEST_P(ClothOnASphere, DrawnTrianglesStayOutsideTheSphere) {
  // Four simulated seconds with the scene's own integrator and step, as the viewer runs it.
  LoadedScene loaded = allLabs().loadScene(shippedScene(GetParam()));
  auto& net = dynamic_cast<net::Net&>(*loaded.sim);
  ASSERT_FALSE(net.spheres().empty()) << GetParam() << " has no sphere";
  EXPECT_GT(net.settings.contactOffset, 0.0) << "the default contact offset is a quarter of the grid spacing";
  const int steps = static_cast<int>(4.0 / loaded.settings.dt);
  double deepest = 0.0;
  for (int k = 0; k < steps; ++k) {
    net.operate(loaded.settings.dt);
    for (const net::SphereCollider& s : net.spheres()) deepest = std::max(deepest, deepestInside(net, s.center, s.radius));
  }
  EXPECT_EQ(deepest, 0.0) << GetParam() << ": a drawn triangle of the cloth cuts " << 1e3 * deepest
                          << " mm into the sphere";
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, ClothOnASphere,
                         ::testing::Values("net_sphere_slope_weak_wind.json", "net_sphere_slope_strong_wind.json",
                                           "net_sphere_drop.json", "net_hanging.json"),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                           return scene.param.substr(0, scene.param.find('.'));
                         });

TEST(ClothOnASphere, WithoutAnOffsetTrianglesCutIn) {
  // What the offset is for: with the masses on the surface itself, the flat triangles between
  // them cut into the sphere (the measure above sees it).
  SceneDocument document = shippedScene("net_sphere_slope_weak_wind.json");
  document.json["net"]["colliders"]["contact_offset"] = 0.0;
  LoadedScene loaded = allLabs().loadScene(document);
  auto& net = dynamic_cast<net::Net&>(*loaded.sim);
  double deepest = 0.0;
  for (int k = 0; k < 240; ++k) {
    net.operate(loaded.settings.dt);
    for (const net::SphereCollider& s : net.spheres()) deepest = std::max(deepest, deepestInside(net, s.center, s.radius));
  }
  std::cout << "without an offset the cloth's triangles cut up to " << 1e3 * deepest << " mm into the sphere\n";
  EXPECT_GT(deepest, 0.0);
}

TEST(ClothOnASphere, ContactOffsetIsAKeyOfTheScene) {
  // An explicit offset replaces the default; 0 puts the masses on the surface itself.
  SceneDocument document = shippedScene("net_sphere_slope_weak_wind.json");
  document.json["net"]["colliders"]["contact_offset"] = 0.0;
  LoadedScene loaded = allLabs().loadScene(document);
  EXPECT_EQ(dynamic_cast<net::Net&>(*loaded.sim).settings.contactOffset, 0.0);
}

}  // namespace
}  // namespace springlab
