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

/// The resolution sweeps' means over three seeds: the difference from those at 20 across (three
/// seeds), in percent, of each property.
struct MeasuredWidth {
  double across;
  double ucs;     ///< %, UCS against the finest size's
  double modulus; ///< %, Young's modulus
  double tension; ///< %, direct tensile strength
};
/// Settling Damping 0.7 during the test (the default).
constexpr std::array<MeasuredWidth, 5> MeasuredDamped = { {
  { 5.1, -58.4, -33.3, -19.8 },
  { 7.0, -40.5, -19.0, -15.7 },
  { 9.0, -32.9, -13.1, -10.2 },
  { 11.9, -16.7, -4.7, -5.5 },
  { 15.6, -8.8, -1.6, -0.9 },
} };
/// Undamped (Settling Damping 0).
constexpr std::array<MeasuredWidth, 5> MeasuredUndamped = { {
  { 5.1, -46.6, -51.4, -16.6 },
  { 7.0, -25.2, -42.7, -11.4 },
  { 9.0, -19.1, -24.0, -7.1 },
  { 11.9, -14.4, -7.6, -3.9 },
  { 15.6, -2.9, -2.4, -1.6 },
} };

const MeasuredWidth& nearest(const std::array<MeasuredWidth, 5>& table, double across)
{
  const MeasuredWidth* near = &table.front();
  for (const MeasuredWidth& w : table) {
    if (std::fabs(w.across - across) < std::fabs(near->across - across)) {
      near = &w;
    }
  }
  return *near;
}

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
    const auto [lo, hi] = grainExtent(p, a);
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
  const bool damped = model.solver.settlingDamping > 0.0;
  const bool compressed = mode != TestMode::Tension;
  const double risky = compressed && !damped ? UndampedUcsConvergedAcross : ResolutionRiskyAcross;
  if (across < risky) {
    const MeasuredWidth& near = nearest(damped ? MeasuredDamped : MeasuredUndamped, across);
    const std::string ucs = std::string("more for the UCS: it rose with the width up to the widest measured "
      "(40 across damped, 28 undamped; the pack grows denser with the width), ") +
      (damped ? "and Settling Damping (the sweep's 0.7) made it about 2 x the undamped UCS from 12 across on"
              : "though undamped it was within 5 % of 20 across from " + formatValue(UndampedUcsConvergedAcross) +
                " across");
    return width + ": on the atlas's cemented rock (3D boxes, " + (damped ? "Settling Damping 0.7" : "undamped") +
      ", Documentation/SpeedAccuracy.md, \"Resolution\") a specimen " + formatValue(near.across) +
      " across measured the UCS " + pct(near.ucs) + ", Young's modulus " + pct(near.modulus) +
      " and the direct tensile strength " + pct(near.tension) + " below those at 20 across (three seeds), and "
      "below 12 across one seed's UCS lay 10-25 % from its size's mean: the strength is this specimen's, not the "
      "rock's. Advised: at least " + formatValue(ResolutionRiskyAcross) + " across for Young's modulus, " +
      formatValue(TensionConvergedAcross) + " for the tensile strength, " + ucs +
      "; calibrate at the size you will run.";
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
