// RockDEM engine: Current Porosity, kept up to date as particles are added.
//
// Porosity = 1 - (solid volume) / (occupied volume), SI units (m^3).
// Solid volume: sum of particle volumes (spheres 4/3 pi r^3; 2D discs pi r^2 t, so in 2D
// the ratio is disc areas over section area).
// Occupied volume: the box, except along the "up" axis when that axis has walls. Up is
// opposite to gravity along the moving axis (x, y in 2D; x, y, z in 3D) with the largest
// |gravity| component. Along it, the occupied region runs from the bottom face (the face
// gravity points at) to the particle surface furthest from it, capped at the opposite
// face. Zero gravity, or a periodic up axis: the whole box. An empty model has porosity 1.
#pragma once

#include "dem/Model.h"

#include <cstddef>

namespace dem {

/// The up axis (0, 1, 2) for this domain and gravity, or -1 when the whole box counts.
int upAxis(const Domain& domain, const Vec3& gravity);

/// Solid and occupied volume of a pack; add() is O(1), so insertion loops can test the
/// porosity after every particle. Sums in slot order, like currentPorosity().
class PorosityMeter {
public:
  /// Measures the model's current particles.
  explicit PorosityMeter(const Model& model);

  /// Accounts for one more particle (centre x in m, radius r in m).
  void add(const Vec3& x, double r);

  double solidVolume() const { return solid_; }  ///< m^3
  double occupiedVolume() const;                 ///< m^3
  double porosity() const;

private:
  Domain domain_;
  int up_ = -1;              ///< up axis, -1: whole box
  bool upIsPositive_ = true; ///< gravity points to -up: bottom face at the origin side
  double surface_ = 0.0;     ///< m, furthest particle surface from the bottom face, along up
  double solid_ = 0.0;       ///< m^3
  std::size_t count_ = 0;
};

} // namespace dem
