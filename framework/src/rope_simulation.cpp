#include "springlab/rope_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace springlab {

RopeParameters readRopeParameters(SceneReader& r, const Vec3& gravity, int dimension) {
  RopeParameters p;
  p.numOfMasses = r.integer("masses", 2);
  p.mass = r.positive("mass");
  p.springConstant = r.positive("spring_constant");
  p.springLength = r.positive("rest_length");
  p.springFrictionConstant = r.nonNegative("spring_friction");
  p.ropeConnectionPos = r.vec3("connection");
  p.ropeConnectionVel = r.vec3("connection_velocity");
  p.direction = r.vec3("direction");
  if (p.direction.norm() < 1e-12) r.fail("direction", "must not be the zero vector");
  p.direction.normalize();
  p.airFrictionConstant = r.nonNegative("air_friction");
  SceneReader g = r.object("ground");
  p.ground.height = g.number("height");
  p.ground.repulsion = g.nonNegative("repulsion");
  p.ground.friction = g.nonNegative("friction");
  p.ground.absorption = g.nonNegative("absorption");
  g.rejectUnknownKeys();
  p.gravitation = gravity;

  // A 2D rope lives in the plane z = 0 and must stay there.
  if (dimension == 2) {
    if (p.ropeConnectionPos.z() != 0.0) r.fail("connection", "must have z = 0 in a 2D scene");
    if (p.ropeConnectionVel.z() != 0.0) r.fail("connection_velocity", "must have z = 0 in a 2D scene");
    if (p.direction.z() != 0.0) r.fail("direction", "must have z = 0 in a 2D scene");
  }
  return p;
}

ResolutionRule ropeResolutionRule() {
  return {"masses", [](nlohmann::json& rope, int masses) {
    // s: the new segment length over the old; n masses make n - 1 segments.
    const int old = rope.at("masses").get<int>();
    if (masses < 2) throw std::invalid_argument("a rope needs at least 2 masses, got " + std::to_string(masses));
    const double s = static_cast<double>(old - 1) / static_cast<double>(masses - 1);
    auto scale = [](nlohmann::json& value, double factor) { value = value.get<double>() * factor; };
    rope["masses"] = masses;
    scale(rope.at("rest_length"), s);      // the same length
    scale(rope.at("mass"), s);             // the same mass per metre
    scale(rope.at("spring_constant"), 1.0 / s);  // k L0: the same stretch under the same load
    scale(rope.at("spring_friction"), 1.0 / s);  // kd L0: the same material damping
    scale(rope.at("air_friction"), s);     // the same drag per kilogram
    for (const char* key : {"repulsion", "friction", "absorption"}) scale(rope.at("ground").at(key), s);
  }};
}

RopeSimulation::RopeSimulation(int dim, const RopeParameters& p)
    : Simulation(dim),
      ropeConnectionPos(p.ropeConnectionPos),
      ropeConnectionVel(p.ropeConnectionVel),
      springConstant(p.springConstant),
      springFrictionConstant(p.springFrictionConstant),
      airFrictionConstant(p.airFrictionConstant),
      ground(p.ground),
      initialConnectionPos_(p.ropeConnectionPos),
      initialConnectionVel_(p.ropeConnectionVel) {
  gravitation = p.gravitation;
}

void RopeSimulation::finishBuilding() { markInitialState(); }

void RopeSimulation::setControlVelocity(const Vec3& velocity) {
  ropeConnectionVel = velocity;
  if (dimension == 2) ropeConnectionVel.z() = 0.0;
}

std::vector<Parameter> RopeSimulation::declareParameters() {
  // The spring constants go to every spring: all springs of the rope share the rope's.
  return {
      Parameter{"spring constant", "N/m", [this] { return springConstant; },
                [this](double v) {
                  springConstant = v;
                  for (Spring& s : editSprings()) s.springConstant = v;
                },
                1.0, 1.0e6, true},
      Parameter{"spring friction", "N s/m", [this] { return springFrictionConstant; },
                [this](double v) {
                  springFrictionConstant = v;
                  for (Spring& s : editSprings()) s.frictionConstant = v;
                },
                0.0, 10.0, false},
      Parameter::field("air friction", "N s/m", airFrictionConstant, 0.0, 1.0, false),
      Parameter::field("gravity y", "m/s^2", gravitation.y(), -30.0, 30.0, false),
      Parameter::field("ground height", "m", ground.height, -10.0, 10.0, false),
      Parameter::field("ground repulsion", "N/m", ground.repulsion, 0.0, 1.0e4, true),
      Parameter::field("ground friction", "N s/m", ground.friction, 0.0, 10.0, false),
      Parameter::field("ground absorption", "N s/m", ground.absorption, 0.0, 10.0, false),
  };
}

double RopeSimulation::angularFrequencyBound() const {
  // The ground adds a spring of stiffness `repulsion` to any mass below it.
  const double w = springGershgorinBound(*this);
  double minMass = INFINITY;
  for (const Mass& m : masses) minMass = std::min(minMass, m.m);
  if (masses.empty()) return w;
  return std::sqrt(w * w + ground.repulsion / minMass);
}

std::vector<Observable> RopeSimulation::observables() const {
  if (state.pos.empty()) return {};
  double lowest = state.pos.front().y();
  for (const Vec3& x : state.pos) lowest = std::min(lowest, x.y());
  return {{"sag", "m", ropeConnectionPos.y() - lowest}, {"tip_y", "m", state.pos.back().y()}};
}

void RopeSimulation::onReset() {
  ropeConnectionPos = initialConnectionPos_;
  ropeConnectionVel = initialConnectionVel_;
}

// The connection point, where the user's keys have carried it.
std::any RopeSimulation::saveLabData() const { return std::pair(ropeConnectionPos, ropeConnectionVel); }

void RopeSimulation::restoreLabData(const std::any& data) {
  std::tie(ropeConnectionPos, ropeConnectionVel) = std::any_cast<std::pair<Vec3, Vec3>>(data);
}

double RopeSimulation::otherPotentialEnergy(const State& s) const {
  double e = 0.0;
  for (const Vec3& x : s.pos) {
    const double depth = ground.height - x.y();
    if (depth > 0.0) e += 0.5 * ground.repulsion * depth * depth;
  }
  return e;
}

Bounds RopeSimulation::reach() const {
  double length = 0.0;
  for (const Spring& s : springs()) length += s.springLength;
  const double L = std::max(length, 0.1);
  const Vec3& c = ropeConnectionPos;
  // The masses where they start, and where the rope swings: a rope that hangs free (the
  // ground further below than its length) sweeps a circle of its length around the
  // connection point; one the ground catches lies down on the side it fell to. It hangs a
  // little longer than its rest length.
  const double hanging = c.y() - ground.height > L ? L : 0.0;
  Bounds b = Simulation::reach();
  b.include(c);
  b.lo = b.lo.cwiseMin(Vec3(c.x() - hanging, std::max(ground.height, c.y() - 1.2 * L), c.z() - 0.25 * hanging));
  b.hi = b.hi.cwiseMax(Vec3(c.x() + hanging, c.y() + 0.05 * L, c.z() + 0.25 * hanging));
  if (dimension == 2) b.lo.z() = b.hi.z() = c.z();
  return b;
}

}  // namespace springlab
