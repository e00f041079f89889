// The net's fast spring pass (see fast_spring_forces.hpp): the loops of net.cpp over the
// springs, vectorised and threaded. Built into the lab, so the compiler inlines the
// exercises (springDamperForce, springJacobian) into these loops where it sees them (the
// reference is built as one unit).
#include "fast_spring_forces.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <springlab/net/exercises.hpp>

#include "fast/avx2.hpp"
#include "fast/loop_exceptions.hpp"
#include "fast/spring_batches.hpp"
#include "fast/thread_budget.hpp"

namespace springlab::net {

namespace {

// One run of springs (fast/spring_families.hpp): mass t to mass t + d of the arrays given,
// which start at the run's first mass, with the spring's k, L0 and kd at t. Its ends,
// velocities and parameters are contiguous arrays of doubles, so this loop vectorises where
// the exercise is inlined: four springs per sqrt and division instruction with AVX2, every
// operand one load. (Each operand is read into a local before the call: without it, GCC 12
// does not vectorise it.)
[[gnu::always_inline]] inline void runOfSprings(const double* __restrict x, const double* __restrict y,
                                                const double* __restrict z, const double* __restrict vx,
                                                const double* __restrict vy, const double* __restrict vz,
                                                const double* __restrict k, const double* __restrict restLength,
                                                const double* __restrict kd, Vec3* __restrict out, int count, int d) {
  for (int t = 0; t < count; ++t) {
    const double x1 = x[t], y1 = y[t], z1 = z[t], x2 = x[t + d], y2 = y[t + d], z2 = z[t + d];
    const double u1 = vx[t], v1 = vy[t], w1 = vz[t], u2 = vx[t + d], v2 = vy[t + d], w2 = vz[t + d];
    const double stiffness = k[t], length = restLength[t], damping = kd[t];
    out[t] = springDamperForce(Vec3(x1, y1, z1), Vec3(x2, y2, z2), Vec3(u1, v1, w1), Vec3(u2, v2, w2), stiffness,
                               length, damping);
  }
}

SPRINGLAB_AVX2_TWINS(runOfSprings,
                     (const double* __restrict x, const double* __restrict y, const double* __restrict z,
                      const double* __restrict vx, const double* __restrict vy, const double* __restrict vz,
                      const double* __restrict k, const double* __restrict restLength,
                      const double* __restrict kd, Vec3* __restrict out, int count, int d),
                     (x, y, z, vx, vy, vz, k, restLength, kd, out, count, d))

// The runs [firstRun, lastRun) of the families (their load()ed state) into their buffers.
void runSpringForces(const SpringFamilies& families, int firstRun, int lastRun, Vec3* const* buffers) {
  const auto runOf = runOfSpringsForThisCpu();
  const double* x[6];
  for (int c = 0; c < 6; ++c) x[c] = families.loaded(c);
  const SpringFamilies::Run* runs = families.runs().data();
  for (int r = firstRun; r < lastRun; ++r) {
    const SpringFamilies::Run& run = runs[r];
    const int i = run.first, at = run.spring;
    runOf(x[0] + i, x[1] + i, x[2] + i, x[3] + i, x[4] + i, x[5] + i, families.stiffness() + at,
          families.restLength() + at, families.damping() + at, buffers[run.family] + i, run.count,
          families.offset(run.family));
  }
}

}  // namespace

void FastSpringForces::modelEdited(const std::vector<Spring>& springs, int masses) {
  if (!families_.refresh(springs, masses)) families_ = SpringFamilies(springs, masses);
}

void FastSpringForces::familyForces(const State& s, int springCount) {
  families_.load(s.pos, s.vel);
  Vec3* buffers[SpringFamilies::kMaxFamilies];
  for (int q = 0; q < families_.families(); ++q) buffers[q] = families_.forces(q);
  const int count = static_cast<int>(families_.runs().size());
  const int threads = springCount >= kParallelSprings ? threadBudget() : 1;
  if (threads <= 1) {
    runSpringForces(families_, 0, count, buffers);
    return;
  }
  // Each thread a share of the runs; springDamperForce may throw (a missing exercise 2.2):
  // carried out of the parallel region.
  LoopExceptions exceptions;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    exceptions.run([&] { runSpringForces(families_, count * t / threads, count * (t + 1) / threads, buffers); });
  }
  exceptions.rethrow();
}

[[gnu::flatten]] bool FastSpringForces::addSpringForces(const State& s, const std::vector<Spring>& springs,
                                                        std::vector<Vec3>& f) {
  if (families_.families() == 0) return false;
  // Family by family into their buffers, summed into f; then the springs no family takes.
  familyForces(s, static_cast<int>(springs.size()));
  families_.gather(f);
  for (const int k : families_.leftovers()) {
    const Spring& sp = springs[static_cast<std::size_t>(k)];
    const Vec3 f1 = springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                      sp.springConstant, sp.springLength, sp.frictionConstant);
    f[sp.mass1] += f1;
    f[sp.mass2] -= f1;
  }
  return true;
}

[[gnu::flatten]] bool FastSpringForces::addSpringJacobians(const State& s, const std::vector<Spring>& springs,
                                                           ForceJacobian& J) {
  const int count = static_cast<int>(springs.size());
  const int threads = count > kParallelSprings ? threadBudget() : 1;
  if (threads <= 1) return false;
  // Each pair's blocks written once (resize leaves them unset), by whichever thread computes
  // it. Each thread takes one contiguous block of springs (as schedule(static) would) inside
  // one try: a missing exercise 2.7 reaches the caller instead of std::terminate, and the loop
  // stays as tight as a plain one (a handler per spring or per chunk cost 35-45 % more
  // instructions in this loop).
  const std::size_t first = J.pairs.size();
  J.pairs.resize(first + springs.size());
  LoopExceptions exceptions;
#pragma omp parallel num_threads(threads)
  {
    int begin = 0, end = count;
#ifdef _OPENMP
    const int team = omp_get_num_threads(), thread = omp_get_thread_num();
    begin = static_cast<int>(static_cast<long>(count) * thread / team);
    end = static_cast<int>(static_cast<long>(count) * (thread + 1) / team);
#endif
    try {
      for (int k = begin; k < end; ++k) {
        const Spring& sp = springs[static_cast<std::size_t>(k)];
        const SpringJacobian sj =
            springJacobian(s.pos[sp.mass1], s.pos[sp.mass2], sp.springConstant, sp.springLength, sp.frictionConstant);
        J.pairs[first + static_cast<std::size_t>(k)] = ForceJacobian::Pair(sp.mass1, sp.mass2, sj.dx, sj.dv);
      }
    } catch (...) {
      exceptions.capture();
    }
  }
  exceptions.rethrow();
  return true;
}

}  // namespace springlab::net
