// The net system (given): builds the grid with exercise 2.1, adds the forces of 2.2-2.4,
// linearises them with 2.7 and corrects each step with 2.5, 2.6 and 2.10.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include <springlab/net/net.hpp>

#include "fast_spring_forces.hpp"

namespace springlab::net {

namespace {
constexpr double kDegrees = 3.14159265358979323846 / 180.0;
// Gauss-Seidel passes of stretch limiting per step, after the tethers: they only fix the
// local strain the tethers leave (a pass moves a correction about one spring, so more passes
// would not reach far either; see handouts/02_net.md, section 2.d).
constexpr int kStretchPasses = 2;
// The tethers hold each mass within (1 + kTetherShare x max stretch) of its rest distance from
// each pin, not the full max stretch: between two pins, the spheres around them let the edge
// run (1 + tether stretch)^2 as long sideways, plus its sag (21 % and more at 10 %), and
// the two passes cannot take that back along the edge. With an eighth of the allowance the
// largest structural strain after 5 s is 0.103 on the thesis cloth at r = 64 (a quarter:
// 0.129, the whole: 0.248; handouts/02_net.md, section 2.d).
constexpr double kTetherShare = 1.0 / 8.0;

}  // namespace

Net::Net(int dim, const NetParameters& p)
    : Simulation(dim), settings(p), fastSprings_(std::make_unique<FastSpringForces>()) {
  // The grid of exercise 2.1 is the initial state.
  NetLayout layout = buildNet(p);
  masses = std::move(layout.masses);
  editSprings() = std::move(layout.springs);
  triangles = std::move(layout.triangles);
  state.pos = std::move(layout.pos);
  state.vel = std::move(layout.vel);
  gravitation = p.gravitation;
  columns_ = p.resolution;
  rows_ = gridRows(p);
  tethers_ = Tethers(state.pos);  // the grid as built is the rest shape
  spheres_ = p.spheres;
  drags_.assign(spheres_.size(), ColliderDrag{});

  // The plane the pinned masses start in, for the bulge.
  int pinned = 0;
  for (int i = 0; i < numOfMasses(); ++i) {
    if (masses[i].pinned) {
      pinnedCentre_ += state.pos[i];
      ++pinned;
    }
  }
  if (pinned > 0) pinnedCentre_ /= pinned;
  markInitialState();
}

Net::~Net() = default;

std::vector<std::string> Net::forceTermNames() const {
  return {"spring forces (exercise 2.2, springDamperForce)", "gravity and air friction",
          "wind (exercises 2.3 and 2.4, vertexNormals and windForce)"};
}

void Net::accumulateForces(const State& s, std::vector<Vec3>& f) {
  // Springs: equal and opposite on their two ends (exercise 2.2). A grid's springs take the
  // framework's fast pass (fast_spring_forces.cpp): the same forces, summed in another order.
  if (forceTermOn(kSprings) && !fastSprings_->addSpringForces(s, springs(), f)) {
    for (const Spring& sp : springs()) {
      const Vec3 f1 = springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                        sp.springConstant, sp.springLength, sp.frictionConstant);
      f[sp.mass1] += f1;
      f[sp.mass2] -= f1;
    }
  }
  // Gravity and air friction on each mass: m (g - c v).
  if (forceTermOn(kGravityAndAir)) {
    for (int i = 0; i < numOfMasses(); ++i) f[i] += masses[i].m * (gravitation - settings.airFriction * s.vel[i]);
  }
  // Wind on the surface, through each mass's normal and area (exercises 2.3 and 2.4).
  const Wind& w = settings.wind;
  const bool windActs = w.model == WindModel::Relative ? w.drag > 0.0 : w.strength > 0.0;
  if (windActs && !triangles.empty() && forceTermOn(kWind)) {
    {
      const PhaseProfile::Scope phase(profile, Phase::kNormals);
      vertexNormals(s.pos, triangles, normals_, areas_);
    }
    for (int i = 0; i < numOfMasses(); ++i) f[i] += windForce(w, s.vel[i], normals_[i], areas_[i]);
  }
}

std::optional<double> Net::sourcePower(const State& s) const {
  if (!suppliesEnergy() || triangles.empty()) return 0.0;
  vertexNormals(s.pos, triangles, sourceNormals_, sourceAreas_);
  double power = 0.0;
  for (int i = 0; i < numOfMasses(); ++i) {
    if (inverseMass(i) == 0.0) continue;  // a pinned or held mass: the wind does no work on it
    power += windForce(settings.wind, s.vel[i], sourceNormals_[i], sourceAreas_[i]).dot(s.vel[i]);
  }
  return power;
}

void Net::onModelEdited() {
  // The fast pass keeps its own copies of the springs: they follow the edit.
  fastSprings_->modelEdited(springs(), numOfMasses());
}

bool Net::addForceJacobian(const State& s, ForceJacobian& J) {
  // Springs (exercise 2.7), in the order of springs(); a large net takes the fast pass's
  // threads. The wind stays explicit.
  if (!fastSprings_->addSpringJacobians(s, springs(), J)) {
    for (const Spring& sp : springs()) {
      const SpringJacobian sj =
          springJacobian(s.pos[sp.mass1], s.pos[sp.mass2], sp.springConstant, sp.springLength, sp.frictionConstant);
      J.pairs.emplace_back(sp.mass1, sp.mass2, sj.dx, sj.dv);
    }
  }
  // Air friction, -c m v on each mass.
  if (settings.airFriction > 0.0) {
    for (int i = 0; i < numOfMasses(); ++i) {
      J.own.push_back({i, Mat3::Zero(), -settings.airFriction * masses[i].m * Mat3::Identity()});
    }
  }
  return true;
}

void Net::afterStep(double dt) {
  // Dragged spheres move to where the user holds them, at the velocity that takes.
  for (std::size_t k = 0; k < spheres_.size(); ++k) drags_[k].finishStep(spheres_[k].center, spheres_[k].velocity, dt);

  // Stretch limiting: the tethers (given) bound each mass's distance from the pins, then
  // exercise 2.6 fixes the springs; then self-collision (2.10). All move masses.
  // (The masses' 1/m only when a correction below moves masses: a bare cloth skips the pass.)
  const bool colliders = !spheres_.empty() || !settings.planes.empty();
  if (settings.stretchLimiting || settings.selfCollision || colliders) {
    inverseMass_.resize(masses.size());
    for (int i = 0; i < numOfMasses(); ++i) inverseMass_[static_cast<std::size_t>(i)] = inverseMass(i);
  }
  if (settings.stretchLimiting) {
    const PhaseProfile::Scope phase(profile, Phase::kStretchLimit);
    tethers_.apply(state.pos, state.vel, inverseMass_, kTetherShare * settings.maxStretch, dt);
    limitStretch(state.pos, state.vel, springs(), inverseMass_, settings.maxStretch, dt, kStretchPasses);
  }
  if (settings.selfCollision) {
    const PhaseProfile::Scope phase(profile, Phase::kCollisions);
    for (const auto& [i, j] : closePairs(state.pos, settings.thickness)) {
      separatePair(state.pos[i], state.pos[j], state.vel[i], state.vel[j], inverseMass_[static_cast<std::size_t>(i)],
                   inverseMass_[static_cast<std::size_t>(j)], settings.thickness);
    }
  }

  // Colliders last, so no mass ends a step inside one (exercise 2.5). They act
  // contactOffset further out than drawn: the cloth's flat triangles between masses on a
  // sphere would otherwise cut into it.
  const PhaseProfile::Scope collisions(profile, Phase::kCollisions);
  const double offset = settings.contactOffset;
  for (int i = 0; colliders && i < numOfMasses(); ++i) {
    if (inverseMass_[static_cast<std::size_t>(i)] == 0.0) continue;
    for (const SphereCollider& sphere : spheres_) {
      const Contact c = sphereContact(state.pos[i], sphere.center, sphere.radius + offset);
      if (!c.touching) continue;
      state.pos[i] = c.pos;
      state.vel[i] = contactVelocity(state.vel[i], sphere.velocity, c.normal, settings.absorption, settings.friction);
    }
    for (const PlaneCollider& plane : settings.planes) {
      const Contact c = planeContact(state.pos[i], plane.point + offset * plane.normal, plane.normal);
      if (!c.touching) continue;
      state.pos[i] = c.pos;
      state.vel[i] = contactVelocity(state.vel[i], Vec3::Zero(), c.normal, settings.absorption, settings.friction);
    }
  }
  // A 2D net stays exactly in its plane.
  if (dimension == 2) {
    for (Vec3& x : state.pos) x.z() = 0.0;
    for (Vec3& v : state.vel) v.z() = 0.0;
  }
}

void Net::onReset() {
  spheres_ = settings.spheres;
  drags_.assign(spheres_.size(), ColliderDrag{});
}

// The spheres where the user has dragged them.
std::any Net::saveLabData() const { return std::pair(spheres_, drags_); }

void Net::restoreLabData(const std::any& data) {
  std::tie(spheres_, drags_) = std::any_cast<std::pair<std::vector<SphereCollider>, std::vector<ColliderDrag>>>(data);
}

void Net::moveSphere(int sphere, const Vec3& center) {
  if (sphere < 0 || sphere >= static_cast<int>(spheres_.size())) return;
  Vec3 c = center;
  if (dimension == 2) c.z() = 0.0;
  drags_[static_cast<std::size_t>(sphere)].holdAt(c);
  // The energy the sphere puts into the cloth is the user's, not a blow-up.
  admitUserEnergy();
}

// ---- what the viewer shows ---------------------------------------------------------------

namespace {
// Colliders are drawn this far (m) behind their surface, so cloth resting on them shows.
constexpr double kDrawInset = 0.004;
}  // namespace

std::optional<GroundPlane> Net::ground() const {
  return findGroundPlane(settings.planes, [](const PlaneCollider& plane) {
    return std::optional<PlaneGeometry>(PlaneGeometry{plane.point, plane.normal});
  });
}

std::optional<double> Net::groundHeight() const {
  // The viewer draws the ground plane, a little below it (see kDrawInset).
  if (const std::optional<GroundPlane> g = ground()) return g->height - kDrawInset;
  return std::nullopt;
}

std::vector<Shape> Net::shapes() const {
  // Spheres first (their indices are the ones moveShape receives), then the slopes, then the wind.
  std::vector<Shape> out;
  for (const SphereCollider& s : spheres_) out.push_back(Shape::sphere(s.center, s.radius, s.movable));
  const std::optional<GroundPlane> g = ground();
  for (int k = 0; k < static_cast<int>(settings.planes.size()); ++k) {
    if (g && g->index == k) continue;  // drawn by the viewer as the ground
    const PlaneCollider& plane = settings.planes[static_cast<std::size_t>(k)];
    out.push_back(Shape::plane(plane.point - kDrawInset * plane.normal, plane.normal));
  }
  if (const std::optional<Shape> arrow = windArrow()) out.push_back(*arrow);
  return out;
}

std::optional<Shape> Net::windArrow() const {
  // Over the cloth, as long as the wind is strong (up to 60 % of the cloth's size).
  const double scale = settings.wind.model == WindModel::Relative ? 0.05 : 0.03;  // per m/s, per N/m^2
  return springlab::windArrow(Simulation::reach(), settings.wind.direction, scale * settings.wind.strength);
}

void Net::moveShape(int index, const Vec3& center) {
  // Only spheres are movable; they come first in shapes().
  if (index >= 0 && index < static_cast<int>(spheres_.size()) && spheres_[static_cast<std::size_t>(index)].movable) {
    moveSphere(index, center);
  }
}

Bounds Net::reach() const {
  // The cloth, its colliders, and the plane points: where the cloth can fall to.
  Bounds b = Simulation::reach();
  for (const SphereCollider& s : settings.spheres) {
    b.lo = b.lo.cwiseMin(s.center - Vec3::Constant(s.radius));
    b.hi = b.hi.cwiseMax(s.center + Vec3::Constant(s.radius));
  }
  for (const PlaneCollider& plane : settings.planes) {
    b.lo = b.lo.cwiseMin(plane.point);
    b.hi = b.hi.cwiseMax(plane.point);
  }
  // And the wind's arrow, so the camera shows it.
  if (const std::optional<Shape> arrow = windArrow()) {
    b.include(arrow->center);
    b.include(arrow->center + arrow->arrow);
  }
  return b;
}

std::vector<Observable> Net::observables() const {
  // drape_height: the lowest point of the cloth; max_strain: the most stretched spring.
  double lowest = INFINITY;
  for (const Vec3& x : state.pos) lowest = std::min(lowest, x.y());
  double strain = 0.0;
  for (const Spring& s : springs()) {
    if (s.springLength > 0.0) {
      strain = std::max(strain, (state.pos[s.mass1] - state.pos[s.mass2]).norm() / s.springLength - 1.0);
    }
  }
  std::vector<Observable> out{{"drape_height", "m", lowest}, {"max_strain", "", strain}};

  // bulge: how far the cloth reaches along the wind beyond where its pinned masses started.
  const bool pinned = std::any_of(masses.begin(), masses.end(), [](const Mass& m) { return m.pinned; });
  if (pinned) {
    double bulge = 0.0;
    for (const Vec3& x : state.pos) bulge = std::max(bulge, (x - pinnedCentre_).dot(settings.wind.direction));
    out.push_back({"bulge", "m", bulge});
  }
  return out;
}

// ---- the panel ------------------------------------------------------------------------------

std::vector<Parameter> Net::declareParameters() {
  // The wind's direction as two angles, read from and written to settings.wind.direction.
  const auto azimuth = [this] {
    const Vec3& d = settings.wind.direction;
    return std::atan2(d.z(), d.x()) / kDegrees;
  };
  const auto elevation = [this] { return std::asin(std::clamp(settings.wind.direction.y(), -1.0, 1.0)) / kDegrees; };
  const auto setWind = [this](double azimuthDegrees, double elevationDegrees) {
    const double a = azimuthDegrees * kDegrees, e = elevationDegrees * kDegrees;
    Vec3 d(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
    if (dimension == 2) {
      d.z() = 0.0;
      if (d.norm() < 1e-9) d = Vec3::UnitX();
      d.normalize();
    }
    settings.wind.direction = d;
  };
  // Each kind's k or kd: the settings and every spring of that kind.
  const auto kindStiffness = [this](const char* label, SpringKind kind) {
    return Parameter{label, "N/m", [this, kind] { return settings.springs[kind].stiffness; },
                     [this, kind](double k) {
                       settings.springs[kind].stiffness = k;
                       for (Spring& s : editSprings()) {
                         if (s.kind == kind) s.springConstant = k;
                       }
                     },
                     0.1, 1.0e5, true};
  };
  const auto kindDamping = [this](const char* label, SpringKind kind) {
    return Parameter{label, "N s/m", [this, kind] { return settings.springs[kind].damping; },
                     [this, kind](double kd) {
                       settings.springs[kind].damping = kd;
                       for (Spring& s : editSprings()) {
                         if (s.kind == kind) s.frictionConstant = kd;
                       }
                     },
                     0.0, 10.0, false};
  };
  return {
      Parameter::field("wind strength", settings.wind.model == WindModel::Relative ? "m/s" : "N/m^2",
                       settings.wind.strength, 0.0, 40.0),
      Parameter{"wind azimuth", "deg", azimuth, [=](double a) { setWind(a, elevation()); }, -180.0, 180.0, false},
      Parameter{"wind elevation", "deg", elevation, [=](double e) { setWind(azimuth(), e); }, -90.0, 90.0, false},
      kindStiffness("structural stiffness", SpringKind::Structural),
      kindStiffness("shear stiffness", SpringKind::Shear),
      kindStiffness("bend stiffness", SpringKind::Bend),
      kindDamping("structural damping", SpringKind::Structural),
      kindDamping("shear damping", SpringKind::Shear),
      kindDamping("bend damping", SpringKind::Bend),
      Parameter::field("gravity y", "m/s^2", gravitation.y(), -30.0, 30.0),
      Parameter::field("air friction", "1/s", settings.airFriction, 0.0, 5.0),
      Parameter::field("contact absorption", "", settings.absorption, 0.0, 2.0),
      Parameter::field("contact friction", "", settings.friction, 0.0, 2.0),
      Parameter::field("max stretch", "", settings.maxStretch, 0.01, 1.0),
  };
}

}  // namespace springlab::net
