// RockDEM engine: input validation errors (see dem/Errors.h).
#include "dem/Errors.h"

#include <cmath>
#include <cstdio>

namespace dem {

std::string formatValue(double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

namespace {

/// "1.2" or "0.002 m": a value as the user reads it, with its unit when it has one.
std::string withUnit(const std::string& number, const std::string& unit)
{
  return unit.empty() ? number : number + " " + unit;
}

[[noreturn]] void throwOutOfRange(const std::string& parameter, double value,
                                  const std::string& range, const std::string& unit)
{
  throw InputError(parameter + " = " + withUnit(formatValue(value), unit) +
                   " is out of range: valid range is " + withUnit(range, unit) + ".");
}

} // namespace

void requireInRange(const std::string& parameter, double value, double lo, double hi,
                    const std::string& unit)
{
  // Written so that NaN fails every comparison and is rejected.
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    throwOutOfRange(parameter, value, "[" + formatValue(lo) + ", " + formatValue(hi) + "]", unit);
  }
}

void requireInOpenRange(const std::string& parameter, double value, double lo, double hi,
                        const std::string& unit)
{
  if (!(std::isfinite(value) && value > lo && value < hi)) {
    throwOutOfRange(parameter, value, "(" + formatValue(lo) + ", " + formatValue(hi) + ")", unit);
  }
}

void requirePositive(const std::string& parameter, double value, const std::string& unit)
{
  if (!(std::isfinite(value) && value > 0.0)) {
    throwOutOfRange(parameter, value, "(0, inf)", unit);
  }
}

void requireNonNegative(const std::string& parameter, double value, const std::string& unit)
{
  if (!(std::isfinite(value) && value >= 0.0)) {
    throwOutOfRange(parameter, value, "[0, inf)", unit);
  }
}

void requireFinite(const std::string& parameter, double value, const std::string& unit)
{
  if (!std::isfinite(value)) {
    throw InputError(parameter + " = " + withUnit(formatValue(value), unit) +
                     " is not a number: it must be finite.");
  }
}

} // namespace dem
