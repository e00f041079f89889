// Two threads give the same cloth as one, bit for bit: the parallel loops split work so that
// every sum runs in the same order whatever the thread count (framework/src/fast/spring_batches.hpp).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <springlab/net/net.hpp>

namespace springlab {
namespace {

// A 72 x 72 cloth (5184 masses, ~30k springs: above every loop's parallel threshold),
// pinned at two corners, with wind and stretch limiting, after `steps` steps.
State clothAfter(const std::string& integrator, int threads, int steps) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  Registry registry;
  registerFramework(registry);
  net::registerLab(registry);
  net::NetParameters p;
  p.resolution = 72;
  p.vAxis = Vec3::UnitZ();
  p.massModel = net::MassModel::Constant;
  p.particleMass = 1.0;
  p.springs[SpringKind::Structural] = {true, 75.0, 0.25};
  p.springs[SpringKind::Shear] = {true, 22.0, 0.25};
  p.springs[SpringKind::Bend] = {true, 8.0, 0.25};
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.wind.model = net::WindModel::Thesis;
  p.wind.direction = Vec3(0.0, 0.0, -1.0);
  p.wind.strength = 4.0;
  net::Net cloth(3, p);
  cloth.setIntegrator(registry.makeIntegrator(integrator));
  const double dt = integrator == "symplectic_euler" ? 1e-3 : 1.0 / 60.0;
  for (int n = 0; n < steps; ++n) cloth.operate(dt);
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  return cloth.state;
}

class OneAndTwoThreads : public ::testing::TestWithParam<std::string> {};

TEST_P(OneAndTwoThreads, GiveTheSameClothBitForBit) {
  const State one = clothAfter(GetParam(), 1, 20);
  const State two = clothAfter(GetParam(), 2, 20);
  ASSERT_EQ(one.pos.size(), two.pos.size());
  int differing = 0;
  for (std::size_t i = 0; i < one.pos.size(); ++i) {
    if (one.pos[i] != two.pos[i] || one.vel[i] != two.vel[i]) ++differing;
  }
  EXPECT_EQ(differing, 0) << differing << " of " << one.pos.size() << " masses differ between 1 and 2 threads after 20 "
                          << GetParam() << " steps";
  // The cloth did move: the comparison is not between two resting states.
  EXPECT_GT((one.pos.back() - clothAfter(GetParam(), 1, 0).pos.back()).norm(), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Integrators, OneAndTwoThreads,
                         ::testing::Values("symplectic_euler", "implicit_euler", "implicit_euler_blocks"));

}  // namespace
}  // namespace springlab
