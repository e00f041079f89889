#pragma once
// Lab 2: the elastic net (cloth, flag, trampoline), the exercises. Each function declared
// under an "Exercise" heading is one exercise (see handouts/02_net.md): you write its body
// in labs/02_net/, one file per exercise. The framework's given code (springlab/net/net.hpp:
// the Net system, its scene reader and integrators; springlab/solvers/: the implicit step's
// linear system and its solver) calls them through these declarations. This header is the
// framework's: edit your .cpp files, not this one (the grader compiles your exercise files
// against its own copy).
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include <springlab/force_jacobian.hpp>
#include <springlab/simulation.hpp>
#include <springlab/solvers/block_system.hpp>

namespace springlab::net {

// ---- What a net scene sets (keys and units in README's scene reference) ---------------

enum class MassModel { Constant, Density };  // every mass the same, or from an areal density
enum class WindModel { Relative, Thesis };    // ((w - v).n) n per area, or i_w w_hat |w_hat.n| per area

// One kind of spring (structural, shear or bend).
struct SpringKindParameters {
  bool enabled = true;     // false: the net has no springs of this kind
  double stiffness = 0.0;  // k, N/m
  double damping = 0.0;    // kd, N s/m, along the spring
};

// The settings of each kind of net spring, indexed by SpringKind (Structural, Shear, Bend;
// a net has no Extra springs) or by position 0, 1, 2.
struct SpringKindTable : std::array<SpringKindParameters, 3> {
  using std::array<SpringKindParameters, 3>::operator[];
  SpringKindParameters& operator[](SpringKind kind) { return at(static_cast<std::size_t>(kind)); }
  const SpringKindParameters& operator[](SpringKind kind) const { return at(static_cast<std::size_t>(kind)); }
};

// Masses pinned by the scene: a corner or a whole edge of the grid. u runs along the
// width (column i), v along the height (row j); 0 is the start of an axis, 1 its end.
enum class Pin { Corner00, Corner10, Corner01, Corner11, EdgeU0, EdgeU1, EdgeV0, EdgeV1 };

struct Wind {
  WindModel model = WindModel::Relative;
  Vec3 direction = Vec3::UnitX();  // unit vector the wind blows along
  double strength = 0.0;           // relative: wind speed |w|, m/s; thesis: i_w, N/m^2
  double drag = 1.0;               // relative only: N s/m^3, force per area per m/s of normal speed
};

struct SphereCollider {
  Vec3 center = Vec3::Zero();    // m
  double radius = 1.0;           // m
  bool movable = false;          // the user may drag it (Ctrl + drag in the viewer)
  Vec3 velocity = Vec3::Zero();  // m/s, while it is being moved
};

struct PlaneCollider {
  Vec3 point = Vec3::Zero();     // m, any point of the plane
  Vec3 normal = Vec3::UnitY();   // unit normal, pointing to the free side
};

struct NetParameters {
  // The grid: `resolution` masses along the width; rows follow from the aspect ratio, so
  // changing the resolution alone keeps the physical cloth (size, total mass) the same.
  double width = 1.0;             // m, along uAxis
  double height = 1.0;            // m, along vAxis
  int resolution = 16;            // masses along the width, >= 2
  Vec3 origin = Vec3::Zero();     // m, position of mass (0, 0)
  Vec3 uAxis = Vec3::UnitX();     // unit vector along the width
  Vec3 vAxis = -Vec3::UnitY();    // unit vector along the height, orthogonal to uAxis
  MassModel massModel = MassModel::Density;
  double particleMass = 1.0;      // kg per mass (Constant)
  double arealDensity = 1.0;      // kg/m^2 (Density)
  SpringKindTable springs{};      // indexed by SpringKind: structural, shear, bend
  std::vector<Pin> pins;
  Vec3 gravitation = Vec3(0.0, -9.81, 0.0);  // m/s^2
  double airFriction = 0.0;       // 1/s: F = -c m v on each mass
  Wind wind;
  std::vector<SphereCollider> spheres;
  std::vector<PlaneCollider> planes;
  double absorption = 1.0;        // share of the approaching normal velocity a contact removes
  double friction = 0.0;          // Coulomb friction coefficient of the colliders
  double contactOffset = 0.0;     // m, colliders hold masses this far out of their surface
  bool stretchLimiting = true;
  double maxStretch = 0.1;        // springs stay below (1 + maxStretch) L0
  bool selfCollision = false;
  double thickness = 0.0;         // m, masses of the net keep at least this distance
};

// ---- Given helpers you may call ------------------------------------------------------
// Rows of the grid for the parameters' width, height and resolution.
int gridRows(const NetParameters& p);
// Whether the mass in column i, row j of a columns x rows grid is pinned.
bool pinnedAt(const std::vector<Pin>& pins, int i, int j, int columns, int rows);

// ---- Exercise 2.1: building the net ----------------------------------------------------
// A grid of columns = p.resolution by rows = gridRows(p) masses; mass (i, j) has index
// j * columns + i and sits at origin + (i / (columns - 1)) width uAxis
// + (j / (rows - 1)) height vAxis, at rest, pinned when pinnedAt(...) says so.
// Springs of each enabled kind (Spring::kind set, the kind's k and kd, rest length = the
// distance at the start): structural between grid neighbours (i,j)-(i+1,j) and (i,j)-(i,j+1);
// shear on both diagonals of each cell; bend between masses two apart along i and along j.
// Triangles: each cell a = (i,j), b = (i+1,j), c = (i+1,j+1), d = (i,j+1) gives (a, b, c) and
// (a, c, d), counter-clockwise seen from uAxis x vAxis.
// Mass: p.particleMass each (Constant), or arealDensity times a third of the area of the
// triangles around the mass (Density), so the net weighs arealDensity * width * height.
struct NetLayout {
  std::vector<Mass> masses;         // [n]
  std::vector<Spring> springs;      // [s]
  std::vector<Triangle> triangles;  // [t]
  std::vector<Vec3> pos;            // [n] m
  std::vector<Vec3> vel;            // [n] m/s
};
NetLayout buildNet(const NetParameters& p);

// ---- Exercise 2.2: spring-damper force (as in Lab 1) ------------------------------------
// F1 = -k (l - L0) e - kd ((v1 - v2) . e) e,  e = (x1 - x2) / l; zero when l == 0.
Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant);

// ---- Exercise 2.3: vertex normals and areas ---------------------------------------------
// For every mass: normals[i] = the unit vector along the sum of (b - a) x (c - a) over the
// triangles (a, b, c) around it (zero when that sum is zero), and areas[i] = a third of the
// area of those triangles (m^2). Both arrays are resized to pos.size().
void vertexNormals(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                   std::vector<Vec3>& normals, std::vector<double>& areas);

// ---- Exercise 2.4: wind ----------------------------------------------------------------
// Force of the wind on a mass with velocity vel, unit normal n and area A:
//   Relative: F = A drag ((w - vel) . n) n,  w = strength * direction
//   Thesis:   F = A strength direction |direction . n|
Vec3 windForce(const Wind& wind, const Vec3& vel, const Vec3& normal, double area);

// ---- Exercise 2.5: collisions -----------------------------------------------------------
// Where a mass at x touches a collider: touching is true when x is inside (strictly);
// then pos is x moved to the nearest surface point and normal the outward unit normal there
// (for the sphere's centre itself, +y). Otherwise touching is false and pos = x.
struct Contact {
  bool touching = false;
  Vec3 pos = Vec3::Zero();     // m
  Vec3 normal = Vec3::Zero();  // unit, out of the collider
};
Contact sphereContact(const Vec3& x, const Vec3& center, double radius);
Contact planeContact(const Vec3& x, const Vec3& point, const Vec3& normal);
// Velocity after a contact with a collider moving at colliderVelocity: with u = v - v_c and
// u_n = u . n, nothing changes when u_n >= 0 (separating). Otherwise the normal part loses
// absorption * u_n (1: stops, 2: elastic bounce) and the tangential part u_t loses
// friction * absorption * |u_n| of its length, never more than all of it (Coulomb).
Vec3 contactVelocity(const Vec3& vel, const Vec3& colliderVelocity, const Vec3& normal,
                     double absorption, double friction);

// ---- Exercise 2.6: stretch limiting ---------------------------------------------------
// Gauss-Seidel passes over the springs: a spring longer than (1 + maxStretch) L0 is
// shortened to exactly that length, its ends moving along the spring in proportion to
// their inverse masses (w1 d / (w1 + w2) and w2 d / (w1 + w2)); each end's velocity changes
// by its move / dt. Passes stop when no spring was longer than the limit by more than a
// relative 1e-9, or after maxPasses. Returns the number of passes made.
int limitStretch(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                 const std::vector<double>& inverseMass, double maxStretch, double dt, int maxPasses);

// ---- Exercise 2.7: spring force Jacobians -----------------------------------------------
// For a spring from mass 1 to mass 2: dx = dF1/dx1 = -k [ c (I - e e^T) + e e^T ] with
// c = max(0, 1 - L0 / l) (the clamp keeps the implicit system positive definite when the
// spring is compressed), and dv = dF1/dv1 = -kd e e^T. Both zero when l == 0.
struct SpringJacobian {
  Mat3 dx = Mat3::Zero();  // N/m
  Mat3 dv = Mat3::Zero();  // N s/m
};
SpringJacobian springJacobian(const Vec3& x1, const Vec3& x2, double springConstant, double springLength,
                              double frictionConstant);

// ---- Exercise 2.8: implicit Euler, the sparse system --------------------------------
// Add the linearised backward Euler system of sim (masses, velocities sim.state.vel) at
// forces `force` and Jacobians J into a prepared, zeroed BlockSystem:
//   (M - dt dF/dv - dt^2 dF/dx) dv = dt (F + dt dF/dx v)
// Pairs and own terms of J give the blocks as ForceJacobian explains.
void assembleImplicitEuler(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                           double dt, BlockSystem& system);

// ---- Exercise 2.9: implicit Euler with per-particle blocks ----------------------------
// The same system, keeping only each mass's own 3x3 block of the matrix (the right side
// stays whole): dv_i = A_ii^-1 b_i for a free mass, 0 for a mass the scene moves.
// `diagonal` is a workspace of any size (resize it to n). dv arrives with size n.
void implicitEulerBlocks(const Simulation& sim, const std::vector<Vec3>& force, const ForceJacobian& J,
                         double dt, std::vector<Mat3>& diagonal, std::vector<Vec3>& dv);

// ---- Exercise 2.10: self-collision (advanced) -------------------------------------------
// Every pair (i, j), i < j, of points closer than `distance`, found with a spatial hash
// (cells of size `distance`, each point checks its own and the 26 neighbouring cells),
// sorted by i then j, each pair once.
std::vector<std::pair<int, int>> closePairs(const std::vector<Vec3>& pos, double distance);
// Push two masses (inverse masses w1, w2) apart along x1 - x2 to `thickness` when closer,
// in proportion to their inverse masses, and remove their approaching relative velocity
// along that line so that momentum is kept. Nothing when w1 + w2 == 0 or they are apart.
void separatePair(Vec3& x1, Vec3& x2, Vec3& v1, Vec3& v2, double w1, double w2, double thickness);

// ==== Position-based and projective methods (XPBD, projective dynamics) ====================
// The framework gives both loops (framework/labs/net/src/xpbd.cpp, projective_dynamics.cpp):
// predicted positions, the iterations, the global solve and the velocity update. You write the
// physics of one spring in each. They run as the integrators "xpbd" and "projective_dynamics"
// on every scene (handouts/02_net.md, "Position-based and projective methods").

// ---- Exercise 2.11: XPBD distance constraint ------------------------------------------
// One projection of the constraint C = |x1 - x2| - L0 of a spring, with e = (x1 - x2) / l:
//   dlambda = (-C - alphaTilde lambda - gamma e.((x1 - prev1) - (x2 - prev2)))
//             / ((1 + gamma) (w1 + w2) + alphaTilde)
//   dx1 = w1 dlambda e,  dx2 = -w2 dlambda e
// w1, w2 inverse masses (0: pinned); alphaTilde = compliance / h^2 (compliance = 1/k);
// gamma = alphaTilde beta~ / h, the constraint damping (0: none); lambda the multiplier so far
// in this substep; prev1, prev2 the positions at the start of the substep. All zero when
// l == 0 or the denominator is 0.
struct DistanceCorrection {
  Vec3 dx1 = Vec3::Zero();  // m, add to x1
  Vec3 dx2 = Vec3::Zero();  // m, add to x2
  double dlambda = 0.0;     // add to the constraint's lambda (N s^2)
};
DistanceCorrection xpbdDistanceConstraint(const Vec3& x1, const Vec3& x2, const Vec3& prev1, const Vec3& prev2,
                                          double w1, double w2, double restLength, double alphaTilde, double gamma,
                                          double lambda);

// ---- Exercise 2.12: projective dynamics, the local step --------------------------------
// The spring's rest shape nearest to its current one: d = L0 (x1 - x2) / |x1 - x2|
// (zero when x1 == x2). The global step then solves (M/h^2 + L) x = M y / h^2 + sum k A^T d.
Vec3 projectSpring(const Vec3& x1, const Vec3& x2, double restLength);

}  // namespace springlab::net
