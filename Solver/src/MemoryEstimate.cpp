// RockDEM engine: the memory a model will take (dem/MemoryEstimate.h).
#include "dem/MemoryEstimate.h"

#include "dem/Model.h"
#include "dem/Pack.h"

#include <algorithm>
#include <cmath>

namespace dem {

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
  const double solid = std::max(0.0, 1.0 - params.targetPorosity);
  const double mean = meanPlacedVolume(domain, params);
  const double count = mean > 0.0 ? solid * boxVolume(domain) / mean : 0.0;
  return std::max(initial, std::floor(count));
}

} // namespace dem
