// RockDEM engine: the memory a model will take (dem/MemoryEstimate.h).
#include "dem/MemoryEstimate.h"

#include "dem/Model.h"
#include "dem/Pack.h"

#include <algorithm>
#include <cmath>

namespace dem {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Mean grain volume (3D: sphere; 2D: disc area) for radii uniform in [a, b].
double meanGrainSize(double a, double b, bool planar)
{
  if (planar) {
    return kPi * (a * a + a * b + b * b) / 3.0; // pi E[r^2]
  }
  return kPi * (a + b) * (a * a + b * b) / 3.0; // 4/3 pi E[r^3]
}

/// The overlap of the fine zone with the box (m^3, 2D: m^2 in the XY plane).
double fineZoneExtent(const FineZone& z, const Domain& d, bool planar)
{
  double extent = 1.0;
  for (int k = 0; k < (planar ? 2 : 3); ++k) {
    const double lo = std::max(z.origin[k], d.origin[k]);
    const double hi = std::min(z.origin[k] + z.size[k], d.origin[k] + d.size[k]);
    extent *= std::max(0.0, hi - lo);
  }
  return extent;
}

} // namespace

double estimateMemory(double particles, double bonds)
{
  return std::max(0.0, particles) * (ModelBytesPerParticle + SolverBytesPerParticle) +
    std::max(0.0, bonds) * BytesPerBond;
}

double expectedParticleCount(const PackParameters& params, const Domain& domain, bool addsToPorosity)
{
  const double initial = static_cast<double>(std::max<std::int64_t>(0, params.initialElements));
  if (!addsToPorosity) {
    return initial;
  }
  const bool planar = domain.section2D;
  const double box = planar ? domain.size.x() * domain.size.y() : domain.size.x() * domain.size.y() * domain.size.z();
  const double solid = std::max(0.0, 1.0 - params.targetPorosity);
  double fine = 0.0;
  double count = 0.0;
  if (params.fineZone.enabled) {
    fine = fineZoneExtent(params.fineZone, domain, planar);
    const double g = meanGrainSize(params.fineZone.minimumSize, params.fineZone.maximumSize, planar);
    count += g > 0.0 ? fine * solid / g : 0.0;
  }
  const double g = meanGrainSize(params.minimumSize, params.maximumSize, planar);
  count += g > 0.0 ? std::max(0.0, box - fine) * solid / g : 0.0;
  return std::max(initial, std::floor(count));
}

} // namespace dem
