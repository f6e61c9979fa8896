// Small hand-built models for the dynamics tests (the Solver-level equivalent of
// DEMModelFromPoints): spheres placed by hand in a box, SI units.
#pragma once

#include "dem/Model.h"
#include "dem/Simulation.h"

#include <cmath>

namespace dem {
namespace testing {

/// A model with no particles: box [-L/2, L/2]^3, no gravity, no damping, no friction.
inline Model emptyModel(double E, double nu, double rho, double e, double box = 2.0)
{
  Model m;
  m.domain.origin = Vec3(-0.5 * box, -0.5 * box, -0.5 * box);
  m.domain.size = Vec3(box, box, box);
  m.material.youngsModulus = E;
  m.material.poissonsRatio = nu;
  m.material.density = rho;
  m.material.restitution = e;
  m.material.friction = 0.0;
  m.gravity.setZero();
  m.solver.settlingDamping = 0.0;
  return m;
}

inline void addSphere(Model& m, const Vec3& x, double r, const Vec3& v = Vec3::Zero())
{
  const std::size_t slot = m.particles.size();
  m.particles.append(x, r, m.nextId++);
  m.particles.velocity[slot] = v;
  updateMassProperties(m);
}

/// Result of following one collision.
struct Collision {
  double maxOverlap = 0.0;   ///< m
  double maxForce = 0.0;     ///< N
  double duration = 0.0;     ///< s, contact start and end interpolated within a step
  bool ended = false;
};

/// Steps until the overlap returned by `overlapOf` has gone positive and back to zero
/// (or `maxSteps`). The contact times are interpolated linearly between steps.
template <class Overlap, class Force>
Collision followCollision(Model& m, Simulation& sim, Overlap overlapOf, Force forceOf,
                          long maxSteps = 2000000)
{
  Collision c;
  double previous = overlapOf(m);
  double previousTime = m.clock.time;
  double start = -1.0;
  for (long k = 0; k < maxSteps; ++k) {
    sim.advance(1);
    const double overlap = overlapOf(m);
    const double time = m.clock.time;
    if (overlap > 0.0 && previous <= 0.0) {
      start = previousTime + (time - previousTime) * (-previous) / (overlap - previous);
    }
    if (overlap > 0.0) {
      c.maxOverlap = std::max(c.maxOverlap, overlap);
      c.maxForce = std::max(c.maxForce, forceOf(m));
    }
    if (overlap <= 0.0 && previous > 0.0 && start >= 0.0) {
      const double end = previousTime + (time - previousTime) * previous / (previous - overlap);
      c.duration = end - start;
      c.ended = true;
      // A few more steps so that no force acts any more on the receding bodies.
      sim.advance(2);
      return c;
    }
    previous = overlap;
    previousTime = time;
  }
  return c;
}

/// Hertz closed forms (PHYSICS.md s.1) for a head-on elastic impact at relative speed v.
struct HertzImpact {
  double maxOverlap, maxForce, duration;
};
inline HertzImpact hertzImpact(double Estar, double Rstar, double mstar, double v)
{
  const double dmax = std::pow(15.0 * mstar * v * v / (16.0 * Estar * std::sqrt(Rstar)), 0.4);
  return { dmax, 4.0 / 3.0 * Estar * std::sqrt(Rstar) * std::pow(dmax, 1.5), 2.94328 * dmax / v };
}

} // namespace testing
} // namespace dem
