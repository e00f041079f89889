#pragma once
// Lab 1: the rope, the exercises. Each function below is one exercise (see
// handouts/01_rope.md): you write its body in labs/01_rope/, one file per exercise. The
// framework's given code (springlab/rope/rope.hpp: the Rope system, its integrators) calls
// them through these declarations. This header is the framework's: edit your .cpp files,
// not this one (the grader compiles your exercise files against its own copy).
#include <vector>

#include <springlab/rope_simulation.hpp>

namespace springlab::rope {

// A point in phase space: position and velocity of one mass.
struct PhasePoint {
  Vec3 pos;  // m
  Vec3 vel;  // m/s
};

// ---- Exercise 1.1: spring-damper force ------------------------------------------------
// Force on mass 1 of a spring from x1 to x2 (mass 2 feels the negative):
//   F1 = -k (l - L0) e - kd ((v1 - v2) . e) e,  with e = (x1 - x2) / l, l = |x1 - x2|.
// Zero when l == 0 (the direction is undefined; never return NaN).
Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant);

// ---- Exercise 1.2: gravity and air friction --------------------------------------------
// Force of gravity (m g) plus air friction (-airFrictionConstant v) on one mass.
Vec3 gravityAndAirFriction(double m, const Vec3& vel, const Vec3& gravitation,
                           double airFrictionConstant);

// ---- Exercise 1.3: ground contact ------------------------------------------------------
// Force of the ground on a mass at x with velocity v: zero above the ground; below it,
// friction against the horizontal velocity, absorption of a downward vertical velocity,
// and repulsion proportional to the depth below the ground.
Vec3 groundContactForce(const Vec3& x, const Vec3& vel, const Ground& ground);

// ---- Exercise 1.4: explicit Euler ------------------------------------------------------
// One explicit (forward) Euler step for one mass with acceleration a at the start:
//   x' = x + v dt,  v' = v + a dt  (both from the old state).
PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt);

// ---- Exercise 1.5: position Verlet -----------------------------------------------------
// First step from the initial state: x1 = x0 + v0 dt + a0 dt^2 / 2, v1 = (x1 - x0) / dt.
PhasePoint positionVerletFirstStep(const PhasePoint& s, const Vec3& a, double dt);
// Later steps: x' = 2 x - xPrevious + a dt^2, v' = (x' - x) / dt.
PhasePoint positionVerletStep(const Vec3& pos, const Vec3& previousPos, const Vec3& a, double dt);

// ---- Exercise 1.6: velocity Verlet -----------------------------------------------------
// Drift with the old acceleration: x' = x + v dt + a dt^2 / 2.
Vec3 velocityVerletPosition(const PhasePoint& s, const Vec3& a, double dt);
// Kick with the mean of the old and new accelerations: v' = v + (a + a') dt / 2.
Vec3 velocityVerletVelocity(const Vec3& vel, const Vec3& a, const Vec3& nextA, double dt);

// ---- Exercise 1.7: building the rope ---------------------------------------------------
// The rope at rest: numOfMasses masses of `mass` kg, the first pinned at the connection
// point, mass i at connection + i * springLength * direction, all at rest; a spring
// between each neighbouring pair with the rope's constants.
struct RopeLayout {
  std::vector<Mass> masses;    // [n]
  std::vector<Spring> springs; // [n - 1]
  std::vector<Vec3> pos;       // [n] m
  std::vector<Vec3> vel;       // [n] m/s
};
RopeLayout buildRope(const RopeParameters& p);

// ---- Exercise 1.8: the fixed end follows the connection point --------------------------
// Move the connection point by its velocity over dt; it may not go below the ground
// (there it stops at the ground height and loses its vertical velocity). Returns the new
// position and velocity of the connection point, which the fixed mass then copies.
PhasePoint moveConnection(const PhasePoint& connection, double dt, double groundHeight);

}  // namespace springlab::rope
