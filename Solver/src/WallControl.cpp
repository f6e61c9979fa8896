// RockDEM engine: wall control of the virtual press (see dem/WallControl.h). SI units.
#include "dem/WallControl.h"

#include "dem/LoadTest.h"
#include "dem/Membrane.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem {

namespace {
constexpr double Pi = 3.14159265358979323846;
} // namespace

std::array<double, 3> specimenLengths(const Model& model)
{
  // Between the walls where they are active (or driven, as the tension platen); on the
  // unwalled sides of an unconfined test, the starting extent scaled by the spread of the
  // particle centres (centreSpread: robust to grains that fly off); else the extent.
  const Particles& p = model.particles;
  const LoadTestState& t = model.test;
  std::array<double, 3> length{ { 0.0, 0.0, 0.0 } };
  // A membrane cylinder: its diameter across the axis (twice the membrane's radius).
  const double membraneDiameter = membraneActive(model) ? 2.0 * membraneSurface(model).radius : 0.0;
  for (int k = 0; k < 3; ++k) {
    const Wall& low = model.walls[2 * k];
    const Wall& high = model.walls[2 * k + 1];
    const bool platenAxis = t.settings.mode != TestMode::Off && k == t.settings.axis;
    if (low.active || high.active || platenAxis) {
      length[k] = high.position - low.position;
    } else if (membraneDiameter > 0.0) {
      length[k] = membraneDiameter;
    } else if (model.domain.section2D && k == 2) {
      length[k] = model.domain.slabThickness();
    } else if (t.initialSpread[k] > 0.0) {
      // An unconfined side: the starting extent scaled as the spread of the centres.
      length[k] = t.initialLength[k] * centreSpread(p, k) / t.initialSpread[k];
    } else {
      double lo = std::numeric_limits<double>::max();
      double hi = -lo;
      for (std::size_t i = 0; i < p.size(); ++i) {
        lo = std::min(lo, p.position[i][k] - p.radius[i]);
        hi = std::max(hi, p.position[i][k] + p.radius[i]);
      }
      length[k] = p.empty() ? model.domain.size[k] : hi - lo;
    }
  }
  return length;
}

double crossSectionArea(const Domain& domain, const std::array<double, 3>& length, int axis)
{
  const double product = length[(axis + 1) % 3] * length[(axis + 2) % 3];
  return domain.cylinderAxis == axis ? 0.25 * Pi * product : product;
}

double specimenVolume(const Domain& domain, const std::array<double, 3>& length)
{
  const double product = length[0] * length[1] * length[2];
  return domain.cylinderAxis >= 0 ? 0.25 * Pi * product : product;
}

void controlWalls(Model& model, double dt, double smallestRadius)
{
  LoadTestState& t = model.test;
  const LoadTestSettings& s = t.settings;
  if (s.mode == TestMode::Off || t.stage == TestStage::Idle) {
    return;
  }
  const int a = s.axis;
  // Which faces do what: every face servo-controlled while consolidating (and, for an
  // isotropic test, for good: it holds the stress once settled); the side faces of a
  // triaxial test keep the stress through shear and after; the platen advances only
  // during shear and stops when Max Strain is reached.
  const bool servoAll = t.stage == TestStage::Consolidate || s.mode == TestMode::Isotropic;
  const bool servoSides = s.mode == TestMode::Triaxial && t.stage != TestStage::Consolidate;
  const bool platenMoving = t.stage == TestStage::Shear;
  const double platenSpeed = s.strainRate * t.initialLength[a]; // m/s
  const double platenVelocity = s.mode == TestMode::Tension ? platenSpeed : -platenSpeed;
  Particles& p = model.particles;
  const double rmin = smallestRadius;
  // The specimen's size (a pass over the particles on an axis without walls): only for
  // the servo.
  std::array<double, 3> length{ { 0.0, 0.0, 0.0 } };
  bool lengthKnown = false;
  // A servo wall never moves more than 0.2 % of the smallest radius per step: fast enough
  // to close a gap of a radius in a few hundred steps, slow enough that the viscous part
  // of the contact forces does not dominate what the servo measures.
  const double maxSpeed = 0.002 * rmin / dt;
  // In a membrane cylinder the platens' area is the membrane's cross-section, pi R^2.
  const double membraneSection = membraneActive(model) ? membraneSurface(model).crossSection : 0.0;
  for (Wall& w : model.walls) {
    const bool servo = w.active && (servoAll || (servoSides && w.axis != a));
    if (servo) {
      if (!lengthKnown && !(membraneSection > 0.0 && w.axis == a)) {
        length = specimenLengths(model);
        lengthKnown = true;
      }
      const double area = membraneSection > 0.0 && w.axis == a ? membraneSection
                                                                 : crossSectionArea(model.domain, length, w.axis);
      w.velocity = servoWallVelocity(w.elasticForce, w.contactStiffness, area, s.confiningStress,
                                     s.servoAlpha, dt, maxSpeed, w.side);
    } else if (platenMoving && w.axis == a && w.side == 1) {
      w.velocity = platenVelocity;
    } else {
      w.velocity = 0.0;
    }
  }
  if (s.mode == TestMode::Tension) {
    // The particles attached to the high platen move with it.
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.flags[i] & FlagAttachedHigh) {
        p.velocity[i].setZero();
        p.velocity[i][a] = platenMoving ? platenVelocity : 0.0;
      }
    }
  }
}

} // namespace dem
