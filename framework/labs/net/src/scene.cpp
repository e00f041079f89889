// Reading a net scene (given). Every key is required; the errors name the file and key.
#include <algorithm>
#include <cmath>

#include <springlab/net/net.hpp>

namespace springlab::net {

namespace {

Vec3 unitVector(SceneReader& r, const std::string& key) {
  Vec3 v = r.vec3(key);
  if (v.norm() < 1e-12) r.fail(key, "must not be the zero vector");
  return v.normalized();
}

SpringKindParameters readKind(SceneReader& springs, const std::string& key) {
  SceneReader k = springs.object(key);
  SpringKindParameters p;
  p.enabled = k.boolean("enabled");
  p.stiffness = k.positive("stiffness");
  p.damping = k.nonNegative("damping");
  k.rejectUnknownKeys();
  return p;
}

Pin readPin(SceneReader& r, const std::string& name) {
  static const std::pair<const char*, Pin> names[] = {
      {"corner_00", Pin::Corner00}, {"corner_10", Pin::Corner10}, {"corner_01", Pin::Corner01},
      {"corner_11", Pin::Corner11}, {"edge_u0", Pin::EdgeU0},     {"edge_u1", Pin::EdgeU1},
      {"edge_v0", Pin::EdgeV0},     {"edge_v1", Pin::EdgeV1}};
  for (const auto& [text, pin] : names) {
    if (name == text) return pin;
  }
  r.fail("pinned", "unknown pin \"" + name +
                       "\"; known: corner_00, corner_10, corner_01, corner_11, edge_u0, edge_u1, edge_v0, edge_v1");
}

}  // namespace

NetParameters readNetParameters(SceneReader& r, const SceneSettings& settings) {
  NetParameters p;
  p.gravitation = settings.gravity;

  // The grid.
  p.width = r.positive("width");
  p.height = r.positive("height");
  p.resolution = r.integer("resolution", 2);
  if (p.resolution > 1024) r.fail("resolution", "must be <= 1024");
  p.origin = r.vec3("origin");
  p.uAxis = unitVector(r, "u_axis");
  p.vAxis = unitVector(r, "v_axis");
  if (std::abs(p.uAxis.dot(p.vAxis)) > 1e-9) r.fail("v_axis", "must be orthogonal to u_axis");

  // Mass: exactly one of particle_mass and areal_density.
  if (r.has("particle_mass") == r.has("areal_density")) {
    r.fail("particle_mass", "give exactly one of particle_mass (kg per mass) and areal_density (kg/m^2)");
  }
  if (r.has("particle_mass")) {
    p.massModel = MassModel::Constant;
    p.particleMass = r.positive("particle_mass");
  } else {
    p.massModel = MassModel::Density;
    p.arealDensity = r.positive("areal_density");
  }

  // Springs by kind, pins, air.
  SceneReader springs = r.object("springs");
  p.springs[SpringKind::Structural] = readKind(springs, "structural");
  p.springs[SpringKind::Shear] = readKind(springs, "shear");
  p.springs[SpringKind::Bend] = readKind(springs, "bend");
  springs.rejectUnknownKeys();
  for (const std::string& name : r.strings("pinned")) p.pins.push_back(readPin(r, name));
  p.airFriction = r.nonNegative("air_friction");

  // Wind.
  SceneReader w = r.object("wind");
  const std::string model = w.string("model");
  if (model == "relative") {
    p.wind.model = WindModel::Relative;
  } else if (model == "thesis") {
    p.wind.model = WindModel::Thesis;
  } else {
    w.fail("model", "must be \"relative\" or \"thesis\", got \"" + model + "\"");
  }
  p.wind.direction = unitVector(w, "direction");
  p.wind.strength = w.nonNegative("strength");
  p.wind.drag = w.nonNegative("drag");
  w.rejectUnknownKeys();

  // Colliders.
  SceneReader c = r.object("colliders");
  p.absorption = c.nonNegative("absorption");
  if (p.absorption > 2.0) c.fail("absorption", "must be <= 2 (2 is an elastic bounce)");
  p.friction = c.nonNegative("friction");
  for (SceneReader& sphere : c.objects("spheres")) {
    SphereCollider collider;
    collider.center = sphere.vec3("center");
    collider.radius = sphere.positive("radius");
    collider.movable = sphere.boolean("movable");
    sphere.rejectUnknownKeys();
    p.spheres.push_back(collider);
  }
  for (SceneReader& plane : c.objects("planes")) {
    PlaneCollider collider;
    collider.point = plane.vec3("point");
    collider.normal = unitVector(plane, "normal");
    plane.rejectUnknownKeys();
    p.planes.push_back(collider);
  }
  // Optional: how far out of their surface the colliders hold the masses (m). The flat
  // triangles between masses resting on a sphere of radius R dip into it by about h^2 / (4 R)
  // (h the grid spacing), more where cells stretch: by default a quarter of the spacing, which
  // keeps the drawn cloth outside any sphere down to about one spacing in radius.
  if (c.has("contact_offset")) {
    p.contactOffset = c.nonNegative("contact_offset");
  } else {
    const double spacing = std::max(p.width / (p.resolution - 1), p.height / std::max(gridRows(p) - 1, 1));
    p.contactOffset = 0.25 * spacing;
  }
  c.rejectUnknownKeys();

  // Corrections after each step.
  SceneReader s = r.object("stretch_limit");
  p.stretchLimiting = s.boolean("enabled");
  p.maxStretch = s.positive("max_stretch");
  s.rejectUnknownKeys();
  SceneReader sc = r.object("self_collision");
  p.selfCollision = sc.boolean("enabled");
  p.thickness = sc.positive("thickness");
  sc.rejectUnknownKeys();

  // A 2D net lies in the plane z = 0 and stays there.
  if (settings.dimension == 2) {
    if (p.origin.z() != 0.0) r.fail("origin", "must have z = 0 in a 2D scene");
    if (p.uAxis.z() != 0.0 || p.vAxis.z() != 0.0) r.fail("u_axis", "u_axis and v_axis must have z = 0 in a 2D scene");
    if (p.wind.direction.z() != 0.0) w.fail("direction", "must have z = 0 in a 2D scene");
  }
  return p;
}

int gridRows(const NetParameters& p) {
  // Spacing along the height as close as possible to the spacing along the width.
  const double rows = std::round(p.height / p.width * (p.resolution - 1)) + 1.0;
  return std::max(2, static_cast<int>(rows));
}

bool pinnedAt(const std::vector<Pin>& pins, int i, int j, int columns, int rows) {
  const bool u0 = i == 0, u1 = i == columns - 1, v0 = j == 0, v1 = j == rows - 1;
  for (Pin pin : pins) {
    switch (pin) {
      case Pin::Corner00: if (u0 && v0) return true; break;
      case Pin::Corner10: if (u1 && v0) return true; break;
      case Pin::Corner01: if (u0 && v1) return true; break;
      case Pin::Corner11: if (u1 && v1) return true; break;
      case Pin::EdgeU0: if (u0) return true; break;
      case Pin::EdgeU1: if (u1) return true; break;
      case Pin::EdgeV0: if (v0) return true; break;
      case Pin::EdgeV1: if (v1) return true; break;
    }
  }
  return false;
}

}  // namespace springlab::net
