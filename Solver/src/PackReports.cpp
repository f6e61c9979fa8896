// RockDEM engine: the one-line reports of the pack commands (see dem/Pack.h).
#include "dem/Errors.h"
#include "dem/Pack.h"

#include <cstdio>
#include <string>

namespace dem {

namespace {

/// Porosities are reported to three decimals.
std::string fixed3(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", value);
  return text;
}

} // namespace

std::string PackReport::summary() const
{
  const std::string counts = std::to_string(placed) + " particles in " +
    std::to_string(attempts) + " attempts";
  if (command == "Add Elements") {
    if (targetReached) {
      return "Add Elements: placed " + counts + "; target porosity " + fixed3(targetPorosity) +
        " reached (porosity " + fixed3(porosity) + ").";
    }
    return "Add Elements: placed " + counts + "; placement saturated at porosity " +
      fixed3(porosity) + " before reaching target " + fixed3(targetPorosity) + ".";
  }
  if (saturated) {
    return command + ": placed " + std::to_string(placed) + " of " + std::to_string(requested) +
      " particles in " + std::to_string(attempts) + " attempts; placement saturated at porosity " +
      fixed3(porosity) + ".";
  }
  return command + ": placed " + counts + "; porosity " + fixed3(porosity) + ".";
}

std::string GrowReport::summary() const
{
  return "Grow Elements: grew " + std::to_string(grown) + " of " + std::to_string(particles) +
    " particles, mean radius gain " + formatValue(meanRadiusGain) + " m; porosity " +
    fixed3(porosityBefore) + " -> " + fixed3(porosityAfter) + ".";
}

std::string CompactReport::summary() const
{
  char overlap[32];
  std::snprintf(overlap, sizeof(overlap), "%.3g", 100.0 * largestOverlap);
  std::string s = "Compact Elements: porosity " + fixed3(porosityBefore) + " -> " + fixed3(porosity);
  if (targetReached) {
    s += " (target " + fixed3(targetPorosity) + " reached)";
  } else if (jammed) {
    s += " (target " + fixed3(targetPorosity) + " not reached: the pack jammed, and going further would lock in more than the Maximum Locked-In Stress " + formatValue(stressCeiling) + " Pa)";
  } else {
    s += " (target " + fixed3(targetPorosity) + " not reached)";
  }
  s += "; locked-in isotropic stress " + formatValue(lockedInStress) + " Pa (ceiling " +
    formatValue(stressCeiling) + " Pa); largest overlap " + overlap + " % of the smaller radius; " +
    std::to_string(particles) + " particles, " + std::to_string(stages) + " stages, " +
    std::to_string(steps) + " steps.";
  return s;
}

} // namespace dem
