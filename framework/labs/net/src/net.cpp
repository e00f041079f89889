// The net system (given): builds the grid with exercise 2.1, adds the forces of 2.2-2.4,
// linearises them with 2.7 and corrects each step with 2.5, 2.6 and 2.10.
#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <springlab/loop_exceptions.hpp>
#include <springlab/net/net.hpp>

namespace springlab::net {

namespace {
constexpr double kDegrees = 3.14159265358979323846 / 180.0;
// Gauss-Seidel passes of stretch limiting per step, after the tethers: they only fix the
// local strain the tethers leave (a pass moves a correction about one spring, so more passes
// would not reach far either; see handouts/02_net.md, section 2.4).
constexpr int kStretchPasses = 2;
// The tethers hold each mass within (1 + kTetherShare x max stretch) of its rest distance from
// each pin, not the full max stretch: between two pins, the spheres around them let the edge
// run (1 + tether stretch)^2 as long sideways, plus its sag (21 % and more at 10 %), and
// the two passes cannot take that back along the edge. With an eighth of the allowance the
// largest structural strain after 5 s is 0.103 on the thesis cloth at r = 64 (a quarter:
// 0.129, the whole: 0.248; handouts/02_net.md, section 2.4).
constexpr double kTetherShare = 1.0 / 8.0;

}  // namespace

Net::Net(int dim, const NetParameters& p) : Simulation(dim), settings(p) {
  // The grid of exercise 2.1 is the initial state.
  NetLayout layout = buildNet(p);
  masses = std::move(layout.masses);
  springs = std::move(layout.springs);
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

namespace {

// One run of springs (springlab/spring_families.hpp): mass first + t to mass first + d + t.
// Its ends are two contiguous stretches of pos and vel, so this loop vectorises where the
// exercise is inlined (the reference, built as one unit): several springs per sqrt and
// division instruction. Returns false when a spring no longer joins the masses the run says.
// (out is restrict here and in the two functions below, which the compiler vectorises: it
// then knows the forces overwrite no input.)
[[gnu::always_inline]] inline bool runOfSprings(const Spring* springs, const int* index, const Vec3* x1,
                                                const Vec3* x2, const Vec3* v1, const Vec3* v2,
                                                Vec3* __restrict out, int count, int first, int d) {
  int moved = 0;  // nonzero: a spring's ends are not the run's
  for (int t = 0; t < count; ++t) {
    const Spring& sp = springs[index[t]];
    moved |= (sp.mass1 - first - t) | (sp.mass2 - first - d - t);
    // Velocities read here, not only inside the exercise's l != 0 branch: loads every spring
    // makes anyway, so the compiler may turn that branch into a select.
    const Vec3 u1(v1[t].x(), v1[t].y(), v1[t].z()), u2(v2[t].x(), v2[t].y(), v2[t].z());
    out[t] = springDamperForce(x1[t], x2[t], u1, u2, sp.springConstant, sp.springLength, sp.frictionConstant);
  }
  return moved == 0;
}

[[gnu::flatten]] bool runOfSpringsPortable(const Spring* springs, const int* index, const Vec3* x1, const Vec3* x2,
                                           const Vec3* v1, const Vec3* v2, Vec3* __restrict out, int count, int first,
                                           int d) {
  return runOfSprings(springs, index, x1, x2, v1, v2, out, count, first, d);
}

#if SPRINGLAB_AVX2_VARIANT
[[gnu::flatten]] SPRINGLAB_TARGET_AVX2 bool runOfSpringsAvx2(const Spring* springs, const int* index, const Vec3* x1,
                                                             const Vec3* x2, const Vec3* v1, const Vec3* v2,
                                                             Vec3* __restrict out, int count, int first, int d) {
  return runOfSprings(springs, index, x1, x2, v1, v2, out, count, first, d);
}
#endif

// The runs [firstRun, lastRun) into their families' buffers.
bool runSpringForces(const Spring* springs, const int* order, const SpringFamilies::Run* runs, int firstRun,
                     int lastRun, const int* offsets, Vec3* const* buffers, const Vec3* pos, const Vec3* vel) {
  bool listed = true;
#if SPRINGLAB_AVX2_VARIANT
  const auto runOf = hasAvx2() ? runOfSpringsAvx2 : runOfSpringsPortable;
#else
  const auto runOf = runOfSpringsPortable;
#endif
  for (int r = firstRun; r < lastRun; ++r) {
    const SpringFamilies::Run& run = runs[r];
    const int d = offsets[run.family];
    listed = runOf(springs, order + run.spring, pos + run.first, pos + run.first + d, vel + run.first,
                   vel + run.first + d, buffers[run.family] + run.first, run.count, run.first, d) &&
             listed;
  }
  return listed;
}

}  // namespace

bool Net::familySpringForces(const State& s) {
  int offsets[SpringFamilies::kMaxFamilies];
  Vec3* buffers[SpringFamilies::kMaxFamilies];
  for (int q = 0; q < families_.families(); ++q) {
    offsets[q] = families_.offset(q);
    buffers[q] = families_.forces(q);
  }
  const std::vector<SpringFamilies::Run>& runs = families_.runs();
  const int count = static_cast<int>(runs.size());
  const int threads = springs.size() >= static_cast<std::size_t>(kParallelSprings) ? threadBudget() : 1;
  if (threads <= 1) {
    return runSpringForces(springs.data(), families_.order().data(), runs.data(), 0, count, offsets, buffers,
                           s.pos.data(), s.vel.data());
  }
  // Each thread a share of the runs; springDamperForce may throw (a missing exercise 2.2):
  // carried out of the parallel region.
  LoopExceptions exceptions;
  int listed = 1;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(&& : listed)
  for (int t = 0; t < threads; ++t) {
    exceptions.run([&] {
      listed = runSpringForces(springs.data(), families_.order().data(), runs.data(), count * t / threads,
                               count * (t + 1) / threads, offsets, buffers, s.pos.data(), s.vel.data()) &&
               listed;
    });
  }
  exceptions.rethrow();
  return listed != 0;
}

// Both loops below run once per spring per step: `flatten` inlines the exercises they call
// where the compiler sees them (the reference is built as one unit). The force pass sorts the
// springs into families (springlab/spring_families.hpp): its sums do not depend on the list's
// order or the thread count; they differ from a plain loop over the list in round-off only.
std::vector<std::string> Net::forceTermNames() const {
  return {"spring forces (exercise 2.2, springDamperForce)", "gravity and air friction",
          "wind (exercises 2.3 and 2.4, vertexNormals and windForce)"};
}

[[gnu::flatten]] void Net::accumulateForces(const State& s, std::vector<Vec3>& f) {
  // Springs: equal and opposite on their ends (exercise 2.2), family by family
  // (springlab/spring_families.hpp), then the springs no family takes.
  if (forceTermOn(kSprings)) {
    if (!families_.fits(springs.size(), numOfMasses()) || !familySpringForces(s)) {
      // A new or edited spring list: sort it again.
      families_ = SpringFamilies(springs, numOfMasses());
      familySpringForces(s);
    }
    families_.gather(f);
    for (const int k : families_.leftovers()) {
      const Spring& sp = springs[static_cast<std::size_t>(k)];
      const Vec3 f1 = springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                        sp.springConstant, sp.springLength, sp.frictionConstant);
      f[sp.mass1] += f1;
      f[sp.mass2] -= f1;
    }
  }
  // Gravity and air friction on each mass.
  const int n = numOfMasses();
  if (forceTermOn(kGravityAndAir)) {
    const int threads = n > kParallelMasses ? threadBudget() : 1;
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
    for (int i = 0; i < n; ++i) {
      f[i] += masses[i].m * (gravitation - settings.airFriction * s.vel[i]);
    }
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

[[gnu::flatten]] bool Net::addForceJacobian(const State& s, ForceJacobian& J) {
  // Springs (exercise 2.7), in the order of `springs`; the wind stays explicit.
  const int count = static_cast<int>(springs.size());
  const int budget = count > kParallelSprings ? threadBudget() : 1;
  // One thread: each pair written once, appended (the vector keeps its capacity across steps).
  // resize() would first write every pair's ends, a pass over all 152 bytes of each (3.6 MB at
  // r = 64, 5 % of the thesis frame).
  if (budget <= 1) {
    J.pairs.reserve(springs.size());
    for (const Spring& sp : springs) {
      const SpringJacobian sj =
          springJacobian(s.pos[sp.mass1], s.pos[sp.mass2], sp.springConstant, sp.springLength, sp.frictionConstant);
      J.pairs.emplace_back(sp.mass1, sp.mass2, sj.dx, sj.dv);
    }
  } else {
    // Threads: each pair's blocks written once (resize leaves them unset), by whichever thread
    // computes it. Each thread takes one contiguous block of springs (as schedule(static)
    // would) inside one try: a missing exercise 2.7 reaches the caller instead of
    // std::terminate, and the loop stays as tight as a plain one (a handler per spring or per
    // chunk cost 35-45 % more instructions in this loop).
    J.pairs.resize(springs.size());
    LoopExceptions exceptions;
#pragma omp parallel num_threads(budget)
    {
      int first = 0, last = count;
#ifdef _OPENMP
      const int threads = omp_get_num_threads(), thread = omp_get_thread_num();
      first = static_cast<int>(static_cast<long>(count) * thread / threads);
      last = static_cast<int>(static_cast<long>(count) * (thread + 1) / threads);
#endif
      try {
        for (int k = first; k < last; ++k) {
          const Spring& sp = springs[static_cast<std::size_t>(k)];
          const SpringJacobian sj = springJacobian(s.pos[sp.mass1], s.pos[sp.mass2], sp.springConstant,
                                                   sp.springLength, sp.frictionConstant);
          J.pairs[static_cast<std::size_t>(k)] = ForceJacobian::Pair(sp.mass1, sp.mass2, sj.dx, sj.dv);
        }
      } catch (...) {
        exceptions.capture();
      }
    }
    exceptions.rethrow();
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
  inverseMass_.resize(masses.size());
  for (int i = 0; i < numOfMasses(); ++i) inverseMass_[static_cast<std::size_t>(i)] = inverseMass(i);
  if (settings.stretchLimiting) {
    const PhaseProfile::Scope phase(profile, Phase::kStretchLimit);
    tethers_.apply(state.pos, state.vel, inverseMass_, kTetherShare * settings.maxStretch, dt);
    limitStretch(state.pos, state.vel, springs, inverseMass_, settings.maxStretch, dt, kStretchPasses);
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
  const bool colliders = !spheres_.empty() || !settings.planes.empty();  // else no pass over the masses
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
  for (const Spring& s : springs) {
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
                       for (Spring& s : springs) {
                         if (s.kind == kind) s.springConstant = k;
                       }
                     },
                     0.1, 1.0e5, true};
  };
  const auto kindDamping = [this](const char* label, SpringKind kind) {
    return Parameter{label, "N s/m", [this, kind] { return settings.springs[kind].damping; },
                     [this, kind](double kd) {
                       settings.springs[kind].damping = kd;
                       for (Spring& s : springs) {
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
