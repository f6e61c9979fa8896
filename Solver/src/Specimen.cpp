// RockDEM engine: laboratory specimens carved out of a dense pack (see dem/Specimen.h).
#include "dem/Specimen.h"

#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dem {

namespace {
constexpr double kPi = 3.14159265358979323846;
const char* const kAxisName[3] = { "X", "Y", "Z" };

/// Half the specimen's extent along each axis (m); a 2D section's z is the half slab.
Vec3 halfExtent(const SpecimenSettings& s, const Domain& d)
{
  Vec3 half;
  if (s.shape == SpecimenShape::Box) {
    half = 0.5 * s.size;
  } else {
    half = Vec3::Constant(0.5 * s.diameter);
    half[s.axis] = 0.5 * s.length;
  }
  if (d.section2D) {
    half.z() = 0.5 * d.slabThickness();
  }
  return half;
}

/// The parameter that sets the extent along axis k, for error messages.
std::string extentParameter(const SpecimenSettings& s, int k)
{
  if (s.shape == SpecimenShape::Box) {
    return std::string("Size ") + kAxisName[k];
  }
  return k == s.axis ? "Length" : "Diameter";
}

double extentValue(const SpecimenSettings& s, int k)
{
  if (s.shape == SpecimenShape::Box) {
    return s.size[k];
  }
  return k == s.axis ? s.length : s.diameter;
}
} // namespace

const char* specimenShapeName(SpecimenShape shape)
{
  switch (shape) {
    case SpecimenShape::Box: return "Box";
    case SpecimenShape::Cylinder: return "Cylinder";
    case SpecimenShape::Disc: return "Disc";
  }
  return "?";
}

SpecimenShape specimenShape(int value)
{
  if (value < 0 || value > 2) {
    throw InputError("Shape = " + std::to_string(value) +
                     " is out of range: valid values are 0 (Box), 1 (Cylinder), 2 (Disc).");
  }
  return static_cast<SpecimenShape>(value);
}

Vec3 specimenCenter(const SpecimenSettings& s, const Domain& d)
{
  Vec3 c = s.centerOnModel ? Vec3(d.origin + 0.5 * d.size) : s.center;
  if (d.section2D) {
    c.z() = d.midPlaneZ();
  }
  return c;
}

void validate(const SpecimenSettings& s, const Domain& d)
{
  validate(d);
  if (s.axis < 0 || s.axis > 2) {
    throw InputError("Axis = " + std::to_string(s.axis) + " is out of range: valid values are X, Y, Z.");
  }
  if (d.section2D && s.shape == SpecimenShape::Cylinder) {
    throw InputError("Shape = Cylinder needs a 3D pack: in a 2D section a cylinder is a rectangle "
                     "(use Shape = Box) or, seen along its axis, a disc (use Shape = Disc).");
  }
  if (d.section2D && s.shape == SpecimenShape::Disc && s.axis != 2) {
    throw InputError(std::string("Axis = ") + kAxisName[s.axis] + " is out of range for Shape = Disc in a 2D "
                     "section: the disc lies in the section plane, so its axis is Z (valid values: Z).");
  }
  if (!s.centerOnModel) {
    for (int k = 0; k < 3; ++k) {
      requireFinite(std::string("Center ") + kAxisName[k], s.center[k], "m");
    }
  }
  if (s.shape == SpecimenShape::Box) {
    for (int k = 0; k < (d.section2D ? 2 : 3); ++k) {
      requirePositive(std::string("Size ") + kAxisName[k], s.size[k], "m");
    }
  } else {
    requirePositive("Diameter", s.diameter, "m");
    if (!d.section2D) {
      requirePositive("Length", s.length, "m");
    }
    if (s.shape == SpecimenShape::Disc && !d.section2D && s.length > s.diameter) {
      throw InputError("Length = " + formatValue(s.length) + " m is out of range for Shape = Disc: a disc is "
        "no thicker than its diameter, valid range is (0, " + formatValue(s.diameter) +
        "] m (Diameter). Use Shape = Cylinder for a longer specimen.");
    }
  }
  // The shape must fit in the model box at its centre.
  const Vec3 c = specimenCenter(s, d);
  const Vec3 half = halfExtent(s, d);
  for (int k = 0; k < (d.section2D ? 2 : 3); ++k) {
    const double room = std::min(c[k] - d.origin[k], d.origin[k] + d.size[k] - c[k]); // m
    if (!(room > 0.0)) {
      throw InputError(std::string("Center ") + kAxisName[k] + " = " + formatValue(c[k]) +
        " m is out of range: the specimen's centre must lie inside the model box, valid range is (" +
        formatValue(d.origin[k]) + ", " + formatValue(d.origin[k] + d.size[k]) + ") m.");
    }
    if (half[k] > room * (1.0 + 1e-12)) {
      throw InputError(extentParameter(s, k) + " = " + formatValue(extentValue(s, k)) +
        " m is out of range: the " + specimenShapeName(s.shape) + " does not fit in the pack along " +
        kAxisName[k] + " (model box " + formatValue(d.origin[k]) + " to " + formatValue(d.origin[k] + d.size[k]) +
        " m, specimen centre " + formatValue(c[k]) + " m); valid range is (0, " + formatValue(2.0 * room) + "] m.");
    }
  }
}

bool insideSpecimen(const SpecimenSettings& s, const Domain& d, const Vec3& x)
{
  const Vec3 c = specimenCenter(s, d);
  const Vec3 half = halfExtent(s, d);
  const Vec3 r = x - c;
  if (s.shape == SpecimenShape::Box) {
    for (int k = 0; k < (d.section2D ? 2 : 3); ++k) {
      if (std::abs(r[k]) > half[k]) {
        return false;
      }
    }
    return true;
  }
  const int a = d.section2D ? 2 : s.axis;
  if (!d.section2D && std::abs(r[a]) > half[a]) {
    return false;
  }
  const int b = (a + 1) % 3;
  const int e = (a + 2) % 3;
  const double radius = 0.5 * s.diameter;
  return r[b] * r[b] + r[e] * r[e] <= radius * radius;
}

std::string SpecimenReport::summary() const
{
  std::string text = "Kept " + std::to_string(kept) + " particle(s) in the specimen (porosity " +
    formatValue(porosity) + "); model box now " + formatValue(size.x()) + " x " + formatValue(size.y()) +
    " x " + formatValue(size.z()) + " m.";
  const std::string gone = removed.summary("outside the specimen");
  return gone.empty() ? text : text + " " + gone;
}

SpecimenReport carveSpecimen(Model& model, const SpecimenSettings& s)
{
  validate(s, model.domain);
  Domain& d = model.domain;
  Particles& p = model.particles;
  std::vector<std::uint8_t> outside(p.size(), 0);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    outside[i] = insideSpecimen(s, d, p.position[i]) ? 0 : 1;
    kept += outside[i] ? 0 : 1;
  }
  if (kept == 0) {
    throw InputError(std::string("The ") + specimenShapeName(s.shape) +
      " holds no particle centre: the pack is empty there. Move Center or enlarge the specimen.");
  }
  const Vec3 half = halfExtent(s, d);
  const double rmax = *std::max_element(p.radius.begin(), p.radius.end());
  for (int k = 0; k < 3; ++k) {
    // Two kept particles must not touch (or stay bonded) across a periodic face once the
    // axis stops being periodic: the specimen leaves a gap of two largest diameters.
    if (d.periodic[k] && 2.0 * half[k] > d.size[k] - 4.0 * rmax) {
      throw InputError(extentParameter(s, k) + " = " + formatValue(extentValue(s, k)) +
        " m is out of range: axis " + kAxisName[k] + " of this pack is periodic, and a specimen that spans it "
        "would keep grains joined across the periodic face; valid range is (0, " +
        formatValue(d.size[k] - 4.0 * rmax) + "] m (the box less two largest diameters).");
    }
  }
  SpecimenReport report;
  report.removed = removeParticles(model, outside);
  report.kept = p.size();
  // The model box: the kept particles' bounding box (their surfaces, so that no wall
  // overlaps a grain); a 2D section keeps its slab.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 hi = -lo;
  double solid = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    lo = lo.cwiseMin(p.position[i] - Vec3::Constant(p.radius[i]));
    hi = hi.cwiseMax(p.position[i] + Vec3::Constant(p.radius[i]));
    solid += particleVolume(d, p.radius[i]);
  }
  if (d.section2D) {
    lo.z() = d.origin.z();
    hi.z() = d.origin.z() + d.size.z();
  }
  d.origin = lo;
  d.size = hi - lo;
  d.periodic = { { false, false, false } };
  // The outline the press measures areas with: a cylinder (a disc is a short one; in a
  // 2D section a disc about Z) or the box itself.
  d.cylinderAxis = s.shape == SpecimenShape::Box ? -1 : s.axis;
  double shapeVolume = 0.0; // m^3
  if (s.shape == SpecimenShape::Box) {
    shapeVolume = 8.0 * half.x() * half.y() * half.z();
  } else {
    shapeVolume = kPi * 0.25 * s.diameter * s.diameter * (d.section2D ? d.slabThickness() : s.length);
  }
  report.porosity = 1.0 - solid / shapeVolume;
  report.origin = d.origin;
  report.size = d.size;
  // Any test ends; the walls stand at the new box.
  model.test = LoadTestState();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.flags[i] &= ~static_cast<std::uint32_t>(FlagAttachedLow | FlagAttachedHigh);
  }
  resetWalls(model);
  return report;
}

} // namespace dem
