// Laboratory specimens shared by the press, state-file and fracture tests: a grown pack
// in a cube without gravity (as under the press), its isotropic consolidation, and the
// cement the tests use. SI units.
#pragma once

#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"

#include <cmath>
#include <cstdint>

namespace dem {
namespace testing {

/// n grains with radii in [rmin, rmax] m placed (not grown) in a box of the given size (m;
/// a 2D section when section2D, size.z the slab), without gravity; grain modulus 1e8 Pa.
inline Model placedPack(const Vec3& size, bool section2D, int n, double rmin, double rmax, std::uint64_t seed)
{
  Model m;
  m.domain.size = size;
  m.domain.section2D = section2D;
  m.material.youngsModulus = 1e8;
  m.gravity.setZero();
  PackParameters p;
  p.initialElements = n;
  p.minimumSize = rmin;
  p.maximumSize = rmax;
  p.randomSeed = seed;
  buildPack(m, p);
  return m;
}

/// n grains with radii in [rmin, rmax] m placed and grown in a cube of the given side (m),
/// without gravity; grain modulus 1e8 Pa.
inline Model specimen(int n, double side, double rmin, double rmax, std::uint64_t seed = 1)
{
  Model m = placedPack(Vec3(side, side, side), false, n, rmin, rmax, seed);
  growElements(m);
  return m;
}

/// Isotropic consolidation to `stress` (Pa) until Stage done (at most 100 x 200 steps), so
/// that the cement finds a dense contact network. Returns the Suggested Strain Rate (1/s)
/// at the end; the caller checks m.test.stage.
inline double consolidate(Model& m, double stress)
{
  LoadTestSettings iso;
  iso.mode = TestMode::Isotropic;
  iso.confiningStress = stress;
  startLoadTest(m, iso);
  Simulation sim(m);
  for (int k = 0; k < 100 && m.test.stage != TestStage::Done; ++k) {
    sim.advance(200);
  }
  return sim.measurements().suggestedStrainRate;
}

/// A violent start for the energy-balance tests: every grain of m moving at up to `speed`
/// m/s in a fixed pattern (no random generator: the same model on every platform).
inline void shake(Model& m, double speed)
{
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const double x = static_cast<double>(i);
    m.particles.velocity[i] = speed * Vec3(std::sin(1.3 * x), std::cos(1.7 * x), std::sin(2.3 * x + 0.5));
  }
}

/// The cement of the test specimens: bond modulus 2e7 Pa, tensile strength 2e5 Pa,
/// cohesion 4e5 Pa, strength scatter 0.2, gap tolerance 0.1.
inline CementParameters testCement()
{
  CementParameters c;
  c.bondModulus = 2e7;
  c.tensileStrength = 2e5;
  c.cohesion = 4e5;
  c.strengthScatter = 0.2;
  c.gapTolerance = 0.1;
  return c;
}

} // namespace testing
} // namespace dem
