// The soft body system: glue between the framework's Simulation and the exercises. Given.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include <springlab/softbody/softbody.hpp>

namespace springlab::softbody {

SoftBody::SoftBody(int dim, SoftBodyParameters parameters) : Simulation(dim), p_(std::move(parameters)) {
  // Equal masses over the vertices; springs along the edges, plus the extra ones asked for.
  const int n = static_cast<int>(p_.mesh.vertices.size());
  masses.assign(static_cast<size_t>(n), Mass{p_.totalMass / n, false});
  std::vector<Spring>& built = editSprings();
  built = edgeSprings(p_.mesh, p_.springConstant, p_.springFriction);
  if (p_.oppositeSprings) {
    for (const Spring& s : oppositeSprings(p_.mesh, p_.extraSpringConstant, p_.extraSpringFriction)) built.push_back(s);
  }
  if (p_.secondRingSprings) {
    for (const Spring& s : secondRingSprings(p_.mesh, p_.extraSpringConstant, p_.extraSpringFriction)) built.push_back(s);
  }

  // Faces must turn outward for the pressure to push out: turn over a mesh wound inward.
  auto measure = [&](const SurfaceMesh& m) {
    return dim == 3 ? enclosedVolume(m.vertices, m.triangles) : enclosedArea(m.vertices, m.segments);
  };
  if (measure(p_.mesh) < 0.0) p_.mesh = reversed(p_.mesh);
  restVolume_ = measure(p_.mesh);
  triangles = p_.mesh.triangles;
  gravitation = p_.gravitation;

  // At rest in the mesh's shape, moving as one.
  state.pos = p_.mesh.vertices;
  state.vel.assign(static_cast<size_t>(n), p_.velocity);
  initialObstacles_ = p_.obstacles;
  drags_.assign(p_.obstacles.size(), ColliderDrag{});
  markInitialState();
}

double SoftBody::volume(const State& s) const {
  return dimension == 3 ? enclosedVolume(s.pos, triangles) : enclosedArea(s.pos, p_.mesh.segments);
}

double SoftBody::gas(double time) const { return inflatedGas(p_.gas, time, p_.inflationTime); }
double SoftBody::gas() const { return gas(state.time); }

double SoftBody::pressure(const State& s) const { return p_.gas != 0.0 ? gasPressure(gas(s.time), volume(s)) : 0.0; }

Penetration SoftBody::penetration(const Vec3& x, const Obstacle& o) const {
  switch (o.type) {
    case ShapeType::Plane: return planePenetration(x, o.center, o.normal);
    case ShapeType::Sphere: return spherePenetration(x, o.center, o.radius);
    case ShapeType::Box: return boxPenetration(x, o.center, o.halfExtents);
    case ShapeType::Arrow: break;
  }
  return {};
}

std::optional<double> SoftBody::sourcePower(const State& s) const {
  if (p_.gas > 0.0 && s.time < p_.inflationTime) return std::nullopt;
  if (!(p_.windDrag > 0.0 && p_.wind.squaredNorm() > 0.0)) return 0.0;
  std::vector<Vec3>& f = sourceForces_;  // scratch: a step allocates nothing
  f.assign(s.pos.size(), Vec3::Zero());
  addWindForces(s.pos, s.vel, triangles, p_.mesh.segments, p_.wind, p_.windDrag, f);
  double power = 0.0;
  for (int i = 0; i < numOfMasses(); ++i) {
    if (inverseMass(i) != 0.0) power += f[i].dot(s.vel[i]);
  }
  return power;
}

std::vector<std::string> SoftBody::forceTermNames() const {
  return {"spring forces (exercise 3.1, addSpringForces)", "gravity and air friction",
          "gas pressure (exercises 3.3 to 3.5: the volume, addPressureForces, the gas pumped in)",
          "wind (exercise 3.9, addWindForces)", "penalty contact (exercises 3.6 and 3.7)"};
}

void SoftBody::accumulateForces(const State& s, std::vector<Vec3>& f) {
  // Springs along the surface and across it (exercise 3.1).
  if (forceTermOn(kSprings)) addSpringForces(s.pos, s.vel, springs(), f);

  // Weight and air drag on each mass.
  if (forceTermOn(kGravityAndAir)) {
    for (int i = 0; i < numOfMasses(); ++i) f[i] += masses[i].m * gravitation - p_.airFriction * s.vel[i];
  }

  // The gas pushes every face outward (exercises 3.3 to 3.5); a non-finite amount of gas is
  // not skipped, so the blow-up check can name it.
  if (p_.gas != 0.0 && forceTermOn(kPressure)) addPressureForces(s.pos, triangles, p_.mesh.segments, pressure(s), f);

  // Wind on the faces (exercise 3.9).
  if (p_.windDrag > 0.0 && forceTermOn(kWind)) {
    addWindForces(s.pos, s.vel, triangles, p_.mesh.segments, p_.wind, p_.windDrag, f);
  }

  // Penalty contact with every obstacle (exercises 3.6 and 3.7); projection acts in afterStep.
  if (p_.contactMethod == ContactMethod::Penalty && forceTermOn(kContact)) {
    const PhaseProfile::Scope phase(profile, Phase::kCollisions);
    for (int i = 0; i < numOfMasses(); ++i) {
      for (const Obstacle& o : p_.obstacles) {
        const Penetration pen = penetration(s.pos[i], o);
        if (pen.touching) f[i] += penaltyContactForce(pen, s.vel[i] - o.velocity, p_.contact);
      }
    }
  }
}

double SoftBody::otherPotentialEnergy(const State& s) const {
  // The gas's energy, and the energy stored in the penalty springs of the contacts.
  double e = p_.gas > 0.0 ? gasEnergy(gas(s.time), volume(s), restVolume_) : 0.0;
  if (p_.contactMethod == ContactMethod::Penalty) {
    for (const Vec3& x : s.pos) {
      for (const Obstacle& o : p_.obstacles) {
        const Penetration pen = penetration(x, o);
        if (pen.touching) e += 0.5 * p_.contact.stiffness * pen.depth * pen.depth;
      }
    }
  }
  return e;
}

void SoftBody::afterStep(double dt) {
  // Dragged obstacles move to where the user holds them, at the velocity that takes (the
  // contacts of the next step see it); the others stand still.
  for (size_t k = 0; k < p_.obstacles.size(); ++k) {
    drags_[k].finishStep(p_.obstacles[k].center, p_.obstacles[k].velocity, dt);
  }

  // Projection: push each mass out of every obstacle and fix its velocity (exercise 3.8).
  if (p_.contactMethod != ContactMethod::Projection) return;
  const PhaseProfile::Scope phase(profile, Phase::kCollisions);
  for (int i = 0; i < numOfMasses(); ++i) {
    if (inverseMass(i) == 0.0) continue;
    for (const Obstacle& o : p_.obstacles) {
      const Penetration pen = penetration(state.pos[i], o);
      if (!pen.touching) continue;
      const PhasePoint out = projectContact({state.pos[i], state.vel[i]}, pen, o.velocity, p_.contact);
      state.pos[i] = out.pos;
      state.vel[i] = out.vel;
    }
  }
}

void SoftBody::onReset() {
  p_.obstacles = initialObstacles_;
  drags_.assign(p_.obstacles.size(), ColliderDrag{});
}

// The obstacles where the user has dragged them.
std::any SoftBody::saveLabData() const { return std::pair(p_.obstacles, drags_); }

void SoftBody::restoreLabData(const std::any& data) {
  std::tie(p_.obstacles, drags_) = std::any_cast<std::pair<std::vector<Obstacle>, std::vector<ColliderDrag>>>(data);
}

std::optional<GroundPlane> SoftBody::floor() const {
  return findGroundPlane(p_.obstacles, [](const Obstacle& o) {
    return o.type == ShapeType::Plane ? std::optional<PlaneGeometry>(PlaneGeometry{o.center, o.normal}) : std::nullopt;
  });
}

std::optional<double> SoftBody::groundHeight() const {
  if (const std::optional<GroundPlane> g = floor()) return g->height;
  return std::nullopt;
}

std::vector<int> SoftBody::drawnObstacles() const {
  // The floor is drawn by the viewer as its ground; every other obstacle as a shape.
  std::vector<int> drawn;
  const std::optional<GroundPlane> g = floor();
  for (int k = 0; k < static_cast<int>(p_.obstacles.size()); ++k) {
    if (!g || g->index != k) drawn.push_back(k);
  }
  return drawn;
}

std::vector<Shape> SoftBody::shapes() const {
  std::vector<Shape> out;
  for (int k : drawnObstacles()) {
    const Obstacle& o = p_.obstacles[static_cast<size_t>(k)];
    switch (o.type) {
      case ShapeType::Plane: out.push_back(Shape::plane(o.center, o.normal)); break;
      case ShapeType::Sphere: out.push_back(Shape::sphere(o.center, o.radius, o.movable)); break;
      case ShapeType::Box: out.push_back(Shape::box(o.center, o.halfExtents, o.movable)); break;
      case ShapeType::Arrow: break;
    }
  }
  // The wind: an arrow above the body, half as long as the body is wide at 10 m/s.
  if (p_.windDrag > 0.0) {
    if (const std::optional<Shape> arrow = windArrow(Simulation::reach(), p_.wind, 0.05 * p_.wind.norm())) {
      out.push_back(*arrow);
    }
  }
  return out;
}

void SoftBody::moveShape(int index, const Vec3& center) {
  const std::vector<int> drawn = drawnObstacles();
  if (index < 0 || index >= static_cast<int>(drawn.size())) return;
  const size_t k = static_cast<size_t>(drawn[static_cast<size_t>(index)]);
  if (!p_.obstacles[k].movable) return;
  // The drag's velocity pushes the body as the contact sees it; its energy is the user's.
  Vec3 target = center;
  if (dimension == 2) target.z() = 0.0;
  drags_[k].holdAt(target);
  admitUserEnergy();
}

Bounds SoftBody::reach() const {
  // The body, the obstacles that are not planes, and the floor under them.
  Bounds b = Simulation::reach();
  for (const Obstacle& o : p_.obstacles) {
    const Vec3 half = o.type == ShapeType::Sphere ? Vec3::Constant(o.radius) : o.halfExtents;
    if (o.type == ShapeType::Plane) continue;
    b.lo = b.lo.cwiseMin(o.center - half);
    b.hi = b.hi.cwiseMax(o.center + half);
  }
  if (const auto floor = groundHeight()) b.lo.y() = std::min(b.lo.y(), *floor);
  // In a wind, room downwind for the body to travel and above it for the wind's arrow.
  if (p_.windDrag > 0.0 && p_.wind.norm() > 0.0) {
    const double size = (b.hi - b.lo).norm();
    const Vec3 downwind = b.lo + 2.0 * size * p_.wind.normalized();
    b.lo = b.lo.cwiseMin(downwind);
    b.hi = b.hi.cwiseMax(b.hi + 2.0 * size * p_.wind.normalized());
    b.hi.y() += 0.5 * size;
  }
  if (dimension == 2) b.lo.z() = b.hi.z() = 0.0;
  return b;
}

std::vector<Observable> SoftBody::observables() const {
  const bool flat = dimension == 2;
  const double v = volume(state);
  // How high the body is (y is up in every scene): its centre of mass, which shows a bounce,
  // and its lowest mass, which shows the contact (0 on the floor, below it while pressed in).
  double weighted = 0.0, total = 0.0, lowest = state.pos.empty() ? 0.0 : state.pos[0].y();
  for (int i = 0; i < numOfMasses(); ++i) {
    weighted += masses[i].m * state.pos[i].y();
    total += masses[i].m;
    lowest = std::min(lowest, state.pos[i].y());
  }
  return {
      {flat ? "area" : "volume", flat ? "m^2" : "m^3", v},
      {"pressure", flat ? "N/m" : "Pa", pressure(state)},
      {"rest_volume_ratio", "", restVolume_ > 0.0 ? v / restVolume_ : 0.0},
      {"gas nRT", "J", p_.gas > 0.0 ? gas() : 0.0},
      {"center_height", "m", total > 0.0 ? weighted / total : 0.0},
      {"lowest_point", "m", lowest},
  };
}

std::vector<Parameter> SoftBody::declareParameters() {
  // The pressure slider reaches four times the scene's pressure, or what would stretch the
  // springs by about a radius when the scene has none.
  const Bounds b = Simulation::reach();
  const double radius = std::max(0.5 * (b.hi - b.lo).maxCoeff(), 1e-3);
  const double top = 4.0 * std::max(p_.gas / std::max(restVolume_, 1e-12), p_.springConstant / radius);
  // The edge springs share the body's constants.
  const auto edgeSprings = [this](double SoftBodyParameters::*constant, double Spring::*field) {
    return [this, constant, field](double value) {
      p_.*constant = value;
      for (Spring& s : editSprings()) {
        if (s.kind == SpringKind::Structural) s.*field = value;
      }
    };
  };
  return {
      // The gas: the pressure it has at the rest volume, P = nRT / V0.
      Parameter{"pressure at rest volume", dimension == 2 ? "N/m" : "Pa",
                [this] { return restVolume_ > 0.0 ? p_.gas / restVolume_ : 0.0; },
                [this](double pressure) { p_.gas = pressure * restVolume_; }, 0.0, top, false},
      Parameter{"spring constant", "N/m", [this] { return p_.springConstant; },
                edgeSprings(&SoftBodyParameters::springConstant, &Spring::springConstant), 1.0, 1.0e6, true},
      Parameter{"spring friction", "N s/m", [this] { return p_.springFriction; },
                edgeSprings(&SoftBodyParameters::springFriction, &Spring::frictionConstant), 0.0, 100.0, false},
      Parameter::field("contact stiffness", "N/m", p_.contact.stiffness, 0.0, 1.0e6),
      Parameter::field("friction (mu)", "", p_.contact.friction, 0.0, 2.0),
      Parameter::field("gravity y", "m/s^2", gravitation.y(), -30.0, 30.0),
  };
}

double SoftBody::angularFrequencyBound() const {
  // Springs by Gershgorin, plus at each mass the penalty contact spring and the stiffness the
  // gas adds: a face's pressure force changes by about P times a neighbour's displacement
  // times the edge it spans, so about P (sum of edge lengths at the mass) / 3 in 3D and 2 P
  // in 2D (the gas's bulk modulus is P).
  const double w = springGershgorinBound(*this);
  const double pressureNow = std::max(p_.gas > 0.0 ? p_.gas / std::max(restVolume_, 1e-12) : 0.0, 0.0);
  std::vector<double> edgeLength(masses.size(), 0.0);
  for (const Spring& s : springs()) {
    if (s.kind != SpringKind::Structural) continue;
    edgeLength[s.mass1] += s.springLength;
    edgeLength[s.mass2] += s.springLength;
  }
  const double contact = p_.contactMethod == ContactMethod::Penalty && !p_.obstacles.empty() ? p_.contact.stiffness : 0.0;
  double extra = 0.0;
  for (int i = 0; i < numOfMasses(); ++i) {
    const double gasStiffness = dimension == 2 ? 2.0 * pressureNow : pressureNow * edgeLength[i] / 3.0;
    extra = std::max(extra, (contact + gasStiffness) / masses[i].m);
  }
  return std::sqrt(w * w + extra);
}

}  // namespace springlab::softbody
