// RockDEM engine: wall control of the virtual press, applied once per step by every
// backend (reference guide "Loading the model"; PHYSICS.md section 4).
//
// Which walls do what follows the load test's stage: every face servo-controlled while
// consolidating (and for good in an isotropic test), the side faces of a triaxial test
// holding the confining stress through shear, the platen advancing at the strain rate
// during shear. SI units: m, m/s, Pa.
#pragma once

#include "dem/Model.h"

#include <algorithm>
#include <array>

namespace dem {

/// The servo law (PHYSICS.md s.4): the velocity (m/s, along the wall's axis) of a
/// servo-controlled wall. The servo controls the elastic push `elasticForce` (N; the
/// viscous part of the wall forces follows the wall's own speed, and feeding it back makes
/// the servo chatter) over the face `area` (m^2): it moves outward at u = G (sigma -
/// targetStress), G = servoAlpha A / (contactStiffness dt) with `contactStiffness` (N/m)
/// the sum over the wall's contacts; without contact it closes in at `maxSpeed` (m/s);
/// |u| <= maxSpeed. `side` 0 is the low face (outward is -axis). GLSL twin:
/// shaders/include/servo_law.glsl.
inline double servoWallVelocity(double elasticForce, double contactStiffness, double area,
                                double targetStress, double servoAlpha, double dt,
                                double maxSpeed, int side)
{
  const double measured = elasticForce / area; // Pa, compression positive
  double outward = -maxSpeed;                  // no contact: close in
  if (contactStiffness > 0.0) {
    const double gain = servoAlpha * area / (contactStiffness * dt);
    outward = gain * (measured - targetStress);
  }
  outward = std::max(-maxSpeed, std::min(maxSpeed, outward));
  return side == 0 ? -outward : outward;
}

/// The specimen's current size along X, Y, Z (m): between the walls where they are active
/// (or driven, as the tension platen); on the unwalled sides of an unconfined test, the
/// starting extent scaled by the spread of the particle centres (centreSpread); else the
/// particles' extent.
std::array<double, 3> specimenLengths(const Model& model);

/// The specimen's cross-section across `axis` (m^2) from its lengths along X, Y, Z (m;
/// specimenLengths): the product of the two other lengths for a box; for a cylinder along
/// `axis` (Domain::cylinderAxis, DEM Specimen's Cylinder and Disc) the ellipse with those
/// lengths as diameters, pi/4 of the product. Across any other axis the section through a
/// cylinder's middle is a rectangle, the product.
double crossSectionArea(const Domain& domain, const std::array<double, 3>& length, int axis);

/// The specimen's volume (m^3) from its lengths (m): their product for a box, pi/4 of it
/// for a cylinder (Domain::cylinderAxis >= 0; a 2D disc: pi/4 D^2 x the slab thickness).
double specimenVolume(const Domain& domain, const std::array<double, 3>& length);

/// Sets every wall's velocity for the coming step (servo law, platen, at rest) and, in a
/// tension test, the velocity of the particles attached to the moving platen. `dt` (s):
/// the timestep; `smallestRadius` (m): bounds a servo wall's speed to 0.2 % of it per step.
void controlWalls(Model& model, double dt, double smallestRadius);

} // namespace dem
