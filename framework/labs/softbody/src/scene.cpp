// Reading the "softbody" section of a scene file (keys and units in README's scene reference).
#include <filesystem>

#include <springlab/softbody/softbody.hpp>

namespace springlab::softbody {

namespace {

// The body's rest shape from the "mesh" object: generated, or read from a file found
// relative to the scene file.
SurfaceMesh readMesh(SceneReader& m, const SceneSettings& settings) {
  if (m.has("generate") == m.has("file")) {
    m.fail("generate", "give either \"generate\" (icosphere, uv_sphere, box, ring) or \"file\" (.obj or .asc)");
  }
  SurfaceMesh mesh;
  if (m.has("file")) {
    const std::string file = m.string("file");
    const std::filesystem::path path = std::filesystem::path(settings.file).parent_path() / file;
    const double scale = m.positive("scale");
    try {
      mesh = loadMesh(path.string());
    } catch (const MeshError& e) {
      m.fail("file", e.what());
    }
    for (Vec3& v : mesh.vertices) v *= scale;
    if (settings.dimension != 3) m.fail("file", "a mesh file makes a 3D body; this scene has dimension 2");
    return mesh;
  }
  const std::string kind = m.string("generate");
  if (kind == "icosphere") {
    const double radius = m.positive("radius");
    const int subdivisions = m.integer("subdivisions", 0);
    if (subdivisions > 6) m.fail("subdivisions", "must be <= 6 (81922 vertices)");
    mesh = icosphere(radius, subdivisions);
  } else if (kind == "uv_sphere") {
    const double radius = m.positive("radius");
    mesh = uvSphere(radius, m.integer("rings", 2), m.integer("sectors", 3));
  } else if (kind == "box") {
    const Vec3 half = m.vec3("half_extents");
    if (!(half.minCoeff() > 0.0)) m.fail("half_extents", "must all be > 0");
    mesh = boxMesh(half, m.integer("divisions", 1));
  } else if (kind == "ring") {
    const double radius = m.positive("radius");
    mesh = ringMesh(m.integer("points", 3), radius);
  } else {
    m.fail("generate", "unknown mesh \"" + kind + "\"; known: icosphere, uv_sphere, box, ring");
  }
  if ((kind == "ring") != (settings.dimension == 2)) {
    m.fail("generate", settings.dimension == 2 ? "a 2D scene needs a \"ring\"" : "\"ring\" is for 2D scenes (dimension 2)");
  }
  checkClosedSurface(mesh, settings.file + ": generated " + kind);
  return mesh;
}

Obstacle readObstacle(SceneReader& r, int dimension) {
  Obstacle o;
  const std::string type = r.string("type");
  if (type == "plane") {
    o.type = ShapeType::Plane;
    o.center = r.vec3("point");
    o.normal = r.vec3("normal");
    if (o.normal.norm() < 1e-12) r.fail("normal", "must not be the zero vector");
    o.normal.normalize();
    if (dimension == 2 && o.normal.z() != 0.0) r.fail("normal", "must have z = 0 in a 2D scene");
  } else if (type == "sphere") {
    o.type = ShapeType::Sphere;
    o.center = r.vec3("center");
    o.radius = r.positive("radius");
    o.movable = r.boolean("movable");
  } else if (type == "box") {
    o.type = ShapeType::Box;
    o.center = r.vec3("center");
    o.halfExtents = r.vec3("half_extents");
    if (!(o.halfExtents.minCoeff() > 0.0)) r.fail("half_extents", "must all be > 0");
    o.movable = r.boolean("movable");
  } else {
    r.fail("type", "unknown obstacle \"" + type + "\"; known: plane, sphere, box");
  }
  if (dimension == 2 && o.center.z() != 0.0) r.fail(type == "plane" ? "point" : "center", "must have z = 0 in a 2D scene");
  r.rejectUnknownKeys();
  return o;
}

}  // namespace

SoftBodyParameters readSoftBodyParameters(SceneReader& r, const SceneSettings& settings) {
  const int dim = settings.dimension;
  SoftBodyParameters p;

  // The rest shape, placed at the centre.
  SceneReader m = r.object("mesh");
  p.mesh = readMesh(m, settings);
  m.rejectUnknownKeys();
  const Vec3 center = r.vec3("center");
  for (Vec3& v : p.mesh.vertices) v += center;
  p.velocity = r.vec3("velocity");
  if (dim == 2 && center.z() != 0.0) r.fail("center", "must have z = 0 in a 2D scene");
  if (dim == 2 && p.velocity.z() != 0.0) r.fail("velocity", "must have z = 0 in a 2D scene");

  // Masses and springs.
  p.totalMass = r.positive("total_mass");
  p.springConstant = r.positive("spring_constant");
  p.springFriction = r.nonNegative("spring_friction");
  SceneReader extra = r.object("extra_springs");
  p.oppositeSprings = extra.boolean("opposite");
  p.secondRingSprings = extra.boolean("second_ring");
  p.extraSpringConstant = extra.nonNegative("spring_constant");
  p.extraSpringFriction = extra.nonNegative("spring_friction");
  extra.rejectUnknownKeys();

  // The gas and the air.
  SceneReader gas = r.object("gas");
  p.gas = gas.nonNegative("nRT");
  p.inflationTime = gas.nonNegative("inflation_time");
  gas.rejectUnknownKeys();
  p.airFriction = r.nonNegative("air_friction");
  SceneReader wind = r.object("wind");
  p.wind = wind.vec3("velocity");
  p.windDrag = wind.nonNegative("drag");
  if (dim == 2 && p.wind.z() != 0.0) wind.fail("velocity", "must have z = 0 in a 2D scene");
  wind.rejectUnknownKeys();

  // Contacts and what the body meets.
  SceneReader contact = r.object("contact");
  const std::string method = contact.string("method");
  if (method == "penalty") {
    p.contactMethod = ContactMethod::Penalty;
  } else if (method == "projection") {
    p.contactMethod = ContactMethod::Projection;
  } else {
    contact.fail("method", "unknown contact method \"" + method + "\"; known: penalty, projection");
  }
  p.contact.stiffness = contact.nonNegative("stiffness");
  p.contact.damping = contact.nonNegative("damping");
  p.contact.friction = contact.nonNegative("friction");
  p.contact.restitution = contact.nonNegative("restitution");
  if (p.contact.restitution > 1.0) contact.fail("restitution", "must be in [0, 1]");
  contact.rejectUnknownKeys();
  for (SceneReader& o : r.objects("obstacles")) p.obstacles.push_back(readObstacle(o, dim));

  p.gravitation = settings.gravity;
  return p;
}

}  // namespace springlab::softbody
