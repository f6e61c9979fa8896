// RockDEM engine: wall control of the virtual press, applied once per step by every
// backend (reference guide "Loading the model"; PHYSICS.md section 4).
//
// Which walls do what follows the load test's stage: every face servo-controlled while
// consolidating (and for good in an isotropic test), the side faces of a triaxial test
// holding the confining stress through shear, the platen advancing at the strain rate
// during shear. SI units: m, m/s, Pa.
#pragma once

#include "dem/Model.h"

#include <array>

namespace dem {

/// The specimen's current size along X, Y, Z (m): between the walls where they are active
/// (or driven, as the tension platen); on the unwalled sides of an unconfined test, the
/// starting extent scaled by the spread of the particle centres (centreSpread); else the
/// particles' extent.
std::array<double, 3> specimenLengths(const Model& model);

/// Sets every wall's velocity for the coming step (servo law, platen, at rest) and, in a
/// tension test, the velocity of the particles attached to the moving platen. `dt` (s):
/// the timestep; `smallestRadius` (m): bounds a servo wall's speed to 0.2 % of it per step.
void controlWalls(Model& model, double dt, double smallestRadius);

} // namespace dem
