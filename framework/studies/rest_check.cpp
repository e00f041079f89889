#include "springlab/studies/rest_check.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "springlab/step_stability.hpp"
#include "springlab/studies/run.hpp"

namespace springlab::studies {

namespace {
constexpr long kFewestRestSteps = 200;  // as a chart's trial: a few steps cannot show a growth
}  // namespace

RestGrowth measureRestGrowth(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                             double stiffnessScale, double dt, double duration, unsigned seed,
                             int directions) {
  LoadedScene loaded = registry.loadScene(scene);
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(registry.makeIntegrator(integrator));
  scaleSprings(sim, stiffnessScale);
  StepStabilityOptions options;
  options.relativePerturbation = kRestDisturbance;
  const long steps = std::max(kFewestRestSteps, std::lround(std::ceil(duration / dt)));
  const StepGrowth g = stepPerturbationGrowth(sim, dt, steps, options, seed, directions);
  RestGrowth out;
  out.growth = g.growth;
  out.growths = g.growths;
  out.finite = g.finite && std::isfinite(g.growth);
  out.dt = dt;
  out.duration = static_cast<double>(steps) * dt;
  return out;
}

bool restCheckApplies(const RestGrowth& baseline) {
  return baseline.finite && baseline.dt > 0.0 && baseline.growth <= kRestBaselineLimit;
}

bool restBroken(const RestGrowth& atDt) { return !atDt.finite || atDt.growth > kRestGrowthLimit; }

std::string describeRestGrowth(const RestGrowth& atDt, const RestGrowth& baseline) {
  std::ostringstream s;
  s << "a disturbance of " << kRestDisturbance << " of the scene's size (the median of " << atDt.growths.size()
    << " directions) ";
  if (atDt.finite) s << "grows " << std::setprecision(2) << atDt.growth << "-fold";
  else s << "grows until the state is not finite";
  s << std::setprecision(6) << " within " << atDt.duration << " s at dt = " << atDt.dt << " s (at half the limit: "
    << std::setprecision(2) << baseline.growth << "-fold)";
  return s.str();
}

}  // namespace springlab::studies
