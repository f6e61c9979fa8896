// RockDEM engine: Current Porosity (see dem/Porosity.h). SI units.
#include "dem/Porosity.h"

#include "dem/Overlaps.h"
#include "dem/Pack.h"

#include <algorithm>
#include <cmath>

namespace dem {

int upAxis(const Domain& domain, const Vec3& gravity)
{
  int up = -1;
  double strongest = 0.0; // m/s^2
  for (int a = 0; a < domain.dimension(); ++a) {
    if (std::abs(gravity[a]) > strongest) {
      strongest = std::abs(gravity[a]);
      up = a;
    }
  }
  if (up >= 0 && domain.periodic[up]) {
    return -1; // a periodic pack has no top to measure to
  }
  return up;
}

PorosityMeter::PorosityMeter(const Model& model)
  : domain_(model.domain)
  , up_(upAxis(model.domain, model.gravity))
{
  if (up_ >= 0) {
    upIsPositive_ = model.gravity[up_] < 0.0;
    surface_ = upIsPositive_ ? -INFINITY : INFINITY;
  }
  const Particles& p = model.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    add(p.position[i], p.radius[i]);
  }
}

void PorosityMeter::add(const Vec3& x, double r)
{
  solid_ += particleVolume(domain_, r);
  ++count_;
  if (up_ >= 0) {
    surface_ = upIsPositive_ ? std::max(surface_, x[up_] + r) : std::min(surface_, x[up_] - r);
  }
}

double PorosityMeter::occupiedVolume() const
{
  if (count_ == 0) {
    return 0.0;
  }
  double volume = 1.0; // m^3 (2D: section area times slab thickness)
  for (int a = 0; a < 3; ++a) {
    double extent = domain_.size[a]; // m
    if (a == up_) {
      const double bottom = upIsPositive_ ? domain_.origin[a] : domain_.upper()[a];
      const double top = upIsPositive_ ? std::min(surface_, domain_.upper()[a])
                                       : std::max(surface_, domain_.origin[a]);
      extent = std::max(0.0, upIsPositive_ ? top - bottom : bottom - top);
    }
    volume *= extent;
  }
  return volume;
}

double PorosityMeter::porosity() const
{
  const double occupied = occupiedVolume();
  if (!(occupied > 0.0)) {
    return 1.0;
  }
  return 1.0 - solid_ / occupied;
}

double currentPorosity(const Model& model)
{
  // Overlapping particles share volume: each overlapping pair's lens is counted once
  // (measureOverlaps), not twice. A pack that never overlaps (DEM Pack Source) gives exactly
  // PorosityMeter's value. Where three or more particles overlap at one point, or particles
  // reach outside the box, the solid volume can still exceed the occupied volume: the
  // porosity is then 0, never negative (DEM Model From Points warns about the overlaps).
  return currentPorosity(model, measureOverlaps(model).volume);
}

double currentPorosity(const Model& model, double shared)
{
  const PorosityMeter meter(model);
  const double occupied = meter.occupiedVolume();
  if (!(occupied > 0.0)) {
    return 1.0;
  }
  if (shared == 0.0) {
    return std::max(0.0, meter.porosity());
  }
  return std::max(0.0, 1.0 - (meter.solidVolume() - shared) / occupied);
}

} // namespace dem
