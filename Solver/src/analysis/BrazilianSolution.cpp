// RockDEM engine: the elastic stress field of a disc under a diametral load (see
// dem/BrazilianSolution.h).
#include "dem/BrazilianSolution.h"

#include "dem/Errors.h"
#include "dem/LoadTest.h"

namespace dem {

namespace {

void validateDisc(double load, double diameter, double thickness)
{
  requirePositive("Diameter", diameter, "m");
  requirePositive("Thickness", thickness, "m");
  requireNonNegative("Load", load, "N");
}

} // namespace

StressTensor brazilianElasticStress(double x, double y, double load, double diameter, double thickness)
{
  validateDisc(load, diameter, thickness);
  requireFinite("x", x, "m");
  requireFinite("y", y, "m");
  const double R = 0.5 * diameter;
  const double r1 = x * x + (R - y) * (R - y); // squared distances to the two load points
  const double r2 = x * x + (R + y) * (R + y);
  if (x * x + y * y > R * R || !(r1 > 0.0) || !(r2 > 0.0)) {
    throw InputError("The point (" + formatValue(x) + ", " + formatValue(y) +
      ") m is out of range: valid range is the disc of radius " + formatValue(R) +
      " m about its centre, without its two load points (0, +-" + formatValue(R) + ") m.");
  }
  const double s0 = brazilianStress(load, diameter, thickness);
  const double q1 = 1.0 / (r1 * r1);
  const double q2 = 1.0 / (r2 * r2);
  // Tension positive (dem/BrazilianSolution.h), then turned to compression positive.
  const double sxx = s0 * (1.0 - diameter * x * x * ((R - y) * q1 + (R + y) * q2));
  const double syy = s0 * (1.0 - diameter * ((R - y) * (R - y) * (R - y) * q1 + (R + y) * (R + y) * (R + y) * q2));
  const double sxy = s0 * diameter * x * ((R - y) * (R - y) * q1 - (R + y) * (R + y) * q2);
  return { { -sxx, -syy, 0.0, -sxy, 0.0, 0.0 } };
}

StressTensor brazilianElasticMean(double radius, double load, double diameter, double thickness)
{
  validateDisc(load, diameter, thickness);
  requireInRange("Radius", radius, 0.0, 0.5 * diameter, "m");
  const double s0 = brazilianStress(load, diameter, thickness);
  const double f = 4.0 * radius * radius / (diameter * diameter); // a^2 / R^2
  return { { -s0 * (1.0 - f), s0 * (3.0 - f), 0.0, 0.0, 0.0, 0.0 } };
}

} // namespace dem
