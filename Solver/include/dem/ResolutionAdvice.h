// RockDEM engine: how many grains across a cemented specimen needs, from the atlas's
// resolution sweep (Documentation/SpeedAccuracy.md, "Resolution"): the same stiff-bond rock
// in 3D boxes of 5 to 40 mean grain diameters across, three pack seeds per size up to 20
// across. DEM Load Test prints this advice in Output Messages when a strength test starts
// on a specimen narrower than the sizes where the measured properties converge (risky: the
// strength is the specimen's, not the rock's), or a tension test on one far wider than where
// the tensile strength converged (wasteful). SI units; widths in mean grain diameters.
#pragma once

#include <string>

namespace dem {

struct Model;
struct LoadTestSettings;

/// The specimen's width in mean grain diameters: the grains' extent (centre +- radius) along
/// the narrowest axis perpendicular to the loading axis `axis` (0 X, 1 Y, 2 Z; a 2D section:
/// the in-plane one), over the mean grain diameter (meanParticleDiameter). 0 without grains.
double grainsAcross(const Model& model, int axis);

/// Below this many grains across, the atlas measured Young's modulus more than 5 % below the
/// finest size's (mean of three seeds), the UCS 17 % or more below and one seed's UCS up to
/// 10-25 % from its size's mean: a strength test there is risky.
constexpr double ResolutionRiskyAcross = 11.9;
/// The direct tensile strength was within 5 % of the finest size's from 15.6 across (every seed).
constexpr double TensionConvergedAcross = 15.6;
/// Undamped (Settling Damping 0), the UCS's mean was within 5 % of that at 20 across from 15.6
/// across (-2.9 %; 11.9 across: -14.4 %), though 28 across gave 6 % more again (one seed): the width
/// from which an undamped UCS is within 5 % of the 20-across one. Under Settling Damping 0.7 the
/// UCS rose further (+9.6 % from 15.6 to 20 across) and on at 28 and 40 across; it was about 2 x
/// the undamped one from 12 across on.
constexpr double UndampedUcsConvergedAcross = 15.6;
/// A tension test wider than this multiple of TensionConvergedAcross is wasteful: it costs the
/// cube of the ratio in particle-steps for a tensile strength no closer to the converged one.
constexpr double ResolutionWastefulFactor = 2.0;

/// One line of advice for the test `settings` on `model` whose specimen is `across` mean grain
/// diameters wide (grainsAcross): "" unless the model is a 3D cemented one (intact bonds) under a
/// Compression, Triaxial or Tension test (the tests the sweep ran) and the width is below
/// ResolutionRiskyAcross (an undamped Compression or Triaxial test: UndampedUcsConvergedAcross):
/// what the atlas measured at the nearest measured width under the model's damping (Settling
/// Damping above 0: the damped sweep, at 0.7; 0: the undamped one) and the advised widths; or, for
/// Tension, above ResolutionWastefulFactor x TensionConvergedAcross.
std::string resolutionAdvice(double across, const Model& model, const LoadTestSettings& settings);

} // namespace dem
