// RockDEM engine: the specimen's width in grains and the resolution advice
// (dem/ResolutionAdvice.h, Documentation/SpeedAccuracy.md "Resolution").
#include "dem/ResolutionAdvice.h"

#include "dem/Errors.h"
#include "dem/Fractures.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dem {

namespace {

/// The resolution sweep's means over three seeds (Settling Damping 0.7 during the test, the
/// default): the difference from the finest size, in percent, of each property.
struct MeasuredWidth {
  double across;
  double ucs;     ///< %, UCS against the finest size's
  double modulus; ///< %, Young's modulus
  double tension; ///< %, direct tensile strength
};
constexpr std::array<MeasuredWidth, 4> Measured = { {
  { 5.1, -58.4, -33.3, -19.8 },
  { 7.0, -40.5, -19.0, -15.7 },
  { 9.0, -32.9, -13.1, -10.2 },
  { 11.9, -16.7, -4.7, -5.5 },
} };
/// The finest sizes the differences are against.
constexpr const char* MeasuredReference = "20 across (three seeds)";

std::string pct(double v)
{
  return formatValue(std::fabs(v)) + " %";
}

} // namespace

double grainsAcross(const Model& model, int axis)
{
  const Particles& p = model.particles;
  const double diameter = meanParticleDiameter(model);
  if (p.empty() || !(diameter > 0.0) || axis < 0 || axis > 2) {
    return 0.0;
  }
  double narrowest = std::numeric_limits<double>::infinity();
  for (int a = 0; a < (model.domain.section2D ? 2 : 3); ++a) {
    if (a == axis) {
      continue;
    }
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (std::size_t i = 0; i < p.size(); ++i) {
      lo = std::min(lo, p.position[i][a] - p.radius[i]);
      hi = std::max(hi, p.position[i][a] + p.radius[i]);
    }
    narrowest = std::min(narrowest, hi - lo);
  }
  return std::isfinite(narrowest) ? narrowest / diameter : 0.0;
}

std::string resolutionAdvice(double across, const Model& model, const LoadTestSettings& settings)
{
  const TestMode mode = settings.mode;
  if (model.domain.section2D || !(across > 0.0) ||
      (mode != TestMode::Compression && mode != TestMode::Triaxial && mode != TestMode::Tension)) {
    return "";
  }
  bool cemented = false;
  for (std::size_t k = 0; k < model.bonds.size() && !cemented; ++k) {
    cemented = !model.bonds.broken(k);
  }
  if (!cemented) {
    return "";
  }
  const std::string width = "The specimen is " + formatValue(std::round(10.0 * across) / 10.0) +
    " mean grain diameters across";
  if (across < ResolutionRiskyAcross) {
    // The nearest measured width.
    const MeasuredWidth* near = &Measured.front();
    for (const MeasuredWidth& w : Measured) {
      if (std::fabs(w.across - across) < std::fabs(near->across - across)) {
        near = &w;
      }
    }
    return width + ": on the atlas's cemented rock (3D boxes, Documentation/SpeedAccuracy.md, \"Resolution\") a "
      "specimen " + formatValue(near->across) + " across measured the UCS " + pct(near->ucs) + ", Young's modulus " +
      pct(near->modulus) + " and the direct tensile strength " + pct(near->tension) + " below those at " +
      MeasuredReference + ", and below 12 across one seed's UCS lay 10-25 % from its size's mean: the strength is "
      "this specimen's, not the rock's. Advised: at least " + formatValue(ResolutionRiskyAcross) +
      " across for Young's modulus, " + formatValue(TensionConvergedAcross) +
      " for the tensile strength, more for the UCS (it still rose beyond 20 across), and calibrate at the size "
      "you will run.";
  }
  const double wasteful = ResolutionWastefulFactor * TensionConvergedAcross;
  if (mode == TestMode::Tension && across > wasteful) {
    const double cost = std::pow(across / TensionConvergedAcross, 3.0);
    return width + ": the atlas measured the direct tensile strength within 5 % of its finest size's from " +
      formatValue(TensionConvergedAcross) + " across (every seed; Documentation/SpeedAccuracy.md, \"Resolution\"), "
      "so this specimen costs about " + formatValue(cost) + " x the particle-steps of one " +
      formatValue(TensionConvergedAcross) + " across for a tensile strength no closer to the converged one. "
      "Advised: " + formatValue(TensionConvergedAcross) + " to " + formatValue(wasteful) + " across for a tensile "
      "strength.";
  }
  return "";
}

} // namespace dem
