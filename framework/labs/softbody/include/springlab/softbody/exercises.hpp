#pragma once
// Lab 3: the pressure soft body, the exercises. A closed surface of masses and springs with a
// gas inside, meeting a floor, obstacles, wind and a sphere the user moves. Each function
// below is one exercise (see handouts/03_softbody.md): you write its body in labs/03_softbody/,
// one file per exercise. The framework's given code (springlab/softbody/softbody.hpp: the
// SoftBody system and its scene reader; springlab/mesh.hpp: the meshes) calls them through
// these declarations. This header is the framework's: edit your .cpp files, not this one
// (the grader compiles your exercise files against its own copy).
//
// Sign convention: forces are F = -dU/dx for a potential energy U (we write U, not V, for
// energies here, because V is the volume).
#include <vector>

#include <springlab/mesh.hpp>
#include <springlab/simulation.hpp>

namespace springlab::softbody {

// A point in phase space: position and velocity of one mass.
struct PhasePoint {
  Vec3 pos;  // m
  Vec3 vel;  // m/s
};

// ---- Exercise 3.1: spring forces --------------------------------------------------------
// Add the force of every spring to f, as in Lab 1: on mass1
//   F1 = -k (l - L0) e - kd ((v1 - v2) . e) e,  e = (x1 - x2) / l,  l = |x1 - x2|,
// and -F1 on mass2; a spring of zero length exerts no force.
void addSpringForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel,
                     const std::vector<Spring>& springs, std::vector<Vec3>& f);

// ---- Exercise 3.2: springs from the mesh ------------------------------------------------
// One spring along every edge of the surface, at rest at the mesh's shape: each edge once
// although two triangles share it (in 2D: one per segment). Kind SpringKind::Structural.
std::vector<Spring> edgeSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant);
// Extra springs across the body: each vertex to the vertex farthest from it, each pair
// once. Kind SpringKind::Extra.
std::vector<Spring> oppositeSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant);
// Extra springs of the second ring: across every edge, between the two corners opposite it
// (3D: the third corners of the two triangles that share the edge; 2D: every vertex and the
// vertex two segments further along the loop). Each pair once. Kind SpringKind::Bend.
std::vector<Spring> secondRingSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant);

// ---- Exercise 3.3: the enclosed volume ---------------------------------------------------
// Signed volume inside a closed triangle surface by the divergence theorem,
//   V = sum over faces (1/6) a . (b x c),
// positive when the faces turn counter-clockwise seen from outside (m^3).
double enclosedVolume(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles);
// Signed area inside closed 2D loops (shoelace), A = 1/2 sum over segments (x_a y_b - x_b y_a),
// positive when the loop runs counter-clockwise (m^2).
double enclosedArea(const std::vector<Vec3>& pos, const std::vector<Segment>& segments);

// ---- Exercise 3.4: the pressure force ---------------------------------------------------
// Ideal gas at constant temperature: P = nRT / V. A body with no volume or turned inside
// out (V <= 0) holds no pressure: 0.
double gasPressure(double nRT, double volume);
// Add the force of pressure P on every face to f: P A n_hat outward, a third to each corner
// (3D); in 2D each segment gets P L n_hat, half to each end, n_hat pointing to its right.
void addPressureForces(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                       const std::vector<Segment>& segments, double pressure, std::vector<Vec3>& f);

// ---- Exercise 3.5: pumping the gas in ---------------------------------------------------
// The gas nRT (J) after pumping for `time` seconds of simulated time: rising linearly from 0
// to `target` over `inflationTime` seconds, then `target` (at once when inflationTime is 0).
// Simulated time, not steps: a run at another dt pumps the same gas history.
double inflatedGas(double target, double time, double inflationTime);
// Potential energy of the gas at constant temperature, zero at the rest volume V0:
//   U = -nRT ln(V / V0), so that -dU/dV = P. Zero when V <= 0 (no pressure there).
double gasEnergy(double nRT, double volume, double restVolume);

// ---- Exercise 3.6: where a point touches an obstacle -----------------------------------
struct Penetration {
  bool touching = false;       // the point is inside the obstacle
  double depth = 0.0;          // m, how far it must move along normal to get out (>= 0)
  Vec3 normal = Vec3::UnitY(); // unit vector out of the obstacle at the nearest surface
};
// Half space behind a plane through `point` with unit normal `normal` (s = (x - p) . n < 0).
Penetration planePenetration(const Vec3& x, const Vec3& point, const Vec3& normal);
// Inside a sphere; at the very centre the way out is +y.
Penetration spherePenetration(const Vec3& x, const Vec3& center, double radius);
// Inside an axis-aligned box: out through the nearest face (ties: the lower axis, x first).
Penetration boxPenetration(const Vec3& x, const Vec3& center, const Vec3& halfExtents);

// How contacts behave; each method uses the fields it names.
struct ContactMaterial {
  double stiffness = 0.0;    // N/m, penalty: the virtual spring pushing out per metre of depth
  double damping = 0.0;      // N s/m, penalty: resists the velocity relative to the obstacle
  double friction = 0.0;     // Coulomb's mu (both methods): tangential at most mu times normal
  double restitution = 0.0;  // projection: outgoing over incoming normal speed, in [0, 1]
};

// ---- Exercise 3.7: contact by a penalty spring ------------------------------------------
// Force on a touching point moving at `relativeVelocity` against the obstacle (zero when not
// touching): normal part k depth - damping (v . n), never pulling (clamped at 0), along n;
// tangential part -damping v_t, at most mu times the normal part in magnitude.
Vec3 penaltyContactForce(const Penetration& p, const Vec3& relativeVelocity, const ContactMaterial& c);

// ---- Exercise 3.8: contact by projection ------------------------------------------------
// A touching point moves out along n by the depth. If it approaches the obstacle
// ((v - w) . n < 0, w the obstacle's velocity) its normal relative velocity is reversed
// and scaled by the restitution, and its tangential relative velocity shrinks by mu times
// the change of the normal one, down to zero but never reversed. Not touching: unchanged.
PhasePoint projectContact(const PhasePoint& point, const Penetration& p, const Vec3& obstacleVelocity,
                          const ContactMaterial& c);

// ---- Exercise 3.9: wind on the faces ----------------------------------------------------
// Add the wind's force on every face to f: F = drag A ((w - v_face) . n_hat) n_hat, with
// v_face the mean velocity of its corners, a third to each corner (3D); in 2D per segment
// with its length for A, half to each end.
void addWindForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel, const std::vector<Triangle>& triangles,
                   const std::vector<Segment>& segments, const Vec3& wind, double drag, std::vector<Vec3>& f);

}  // namespace springlab::softbody
