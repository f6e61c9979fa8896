// RockDEM engine: Grow Elements (see dem/Pack.h). SI units: metres.
#include "dem/Pack.h"

#include "dem/SizeClassGrids.h"

#include <algorithm>

namespace dem {

namespace {

/// Relative margin that keeps "touching" from rounding into overlap (see Pack.h).
constexpr double kTouchTolerance = 1.0e-12;
/// A gap below this fraction of the radius counts as touching: no growth is recorded.
constexpr double kNegligibleGrowth = 1.0e-9;

} // namespace

GrowReport growElements(Model& model)
{
  GrowReport report;
  Particles& p = model.particles;
  const Domain& domain = model.domain;
  validate(domain);
  validate(p);
  report.particles = p.size();
  report.porosityBefore = currentPorosity(model);
  if (p.empty()) {
    report.porosityAfter = report.porosityBefore;
    return report;
  }

  const auto [smallest, largest] = std::minmax_element(p.radius.begin(), p.radius.end());
  SizeClassGrids grids(domain, *smallest, *largest,
                       std::max(SizeClassGrids::kDefaultMaxCellsPerClass, p.size()));
  grids.insertAll(p);

  double totalGain = 0.0; // m
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.flags[i] & FlagFixed) {
      continue;
    }
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    // Rounding scale: the magnitude of the coordinates the gaps are computed from.
    const double scale = x.cwiseAbs().maxCoeff() + r;

    double growth = r; // at most double the radius per call
    for (int a = 0; a < domain.dimension(); ++a) {
      if (domain.periodic[a]) {
        growth = std::min(growth, 0.25 * domain.size[a] - r); // keep r <= L/4
      } else {
        const double wallGap = std::min(x[a] - r - domain.origin[a], domain.upper()[a] - x[a] - r);
        growth = std::min(growth, wallGap - kTouchTolerance * (scale + wallGap));
      }
    }
    if (!(growth > 0.0)) {
      continue;
    }
    const SizeClassGrids::Nearest near = grids.nearest(x, r, growth, i);
    if (near.key != SizeClassGrids::npos) {
      growth = near.gap - kTouchTolerance * (scale + near.radius + near.gap);
    }
    if (!(growth > kNegligibleGrowth * r)) {
      continue; // already touching
    }
    p.radius[i] = r + growth;
    grids.setRadius(i, p.radius[i]);
    totalGain += growth;
    ++report.grown;
  }

  updateMassProperties(model);
  report.meanRadiusGain = totalGain / static_cast<double>(p.size());
  report.porosityAfter = currentPorosity(model);
  return report;
}

} // namespace dem
