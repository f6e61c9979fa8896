// RockDEM shaders: the servo law of the virtual press (PHYSICS.md section 4), the GLSL
// mirror of dem::servoWallVelocity (dem/WallControl.h). SI units: N, N/m, m^2, Pa, s, m/s.
#ifndef ROCKDEM_SERVO_LAW_GLSL
#define ROCKDEM_SERVO_LAW_GLSL

#include "vec.glsl"

/// Velocity (m/s along the wall's axis) of a servo-controlled wall: u = G (sigma -
/// sigma_target) outward, G = alpha A / (kn_wall dt), closing in at the largest speed
/// without contact, bounded by +-maxSpeed; side 0 (low face) moves the other way.
double servoWallVelocity(double elasticForce, double contactStiffness, double area,
                         double targetStress, double servoAlpha, double dt, double maxSpeed, int side)
{
  const double measured = elasticForce / area;
  double outward = -maxSpeed;
  if (contactStiffness > 0.0LF) {
    const double gain = servoAlpha * area / (contactStiffness * dt);
    outward = gain * (measured - targetStress);
  }
  outward = stdMax(-maxSpeed, stdMin(maxSpeed, outward));
  return side == 0 ? -outward : outward;
}

#endif
