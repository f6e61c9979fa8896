// RockDEM engine: a plane section through a model (see dem/Section.h). SI units.
#include "dem/Section.h"

#include "dem/BondGeometry.h"
#include "dem/Errors.h"
#include "dem/Fractures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace dem {

const char* sectionOrientationName(SectionOrientation orientation)
{
  switch (orientation) {
    case SectionOrientation::XY:
      return "XY";
    case SectionOrientation::XZ:
      return "XZ";
    case SectionOrientation::YZ:
      return "YZ";
    case SectionOrientation::Custom:
      return "Custom";
  }
  return "?";
}

SectionOrientation sectionOrientation(int value)
{
  if (value < 0 || value > 3) {
    throw InputError("Section = " + std::to_string(value) +
                     " is out of range: valid values are 0 (XY), 1 (XZ), 2 (YZ) and 3 (Custom).");
  }
  return static_cast<SectionOrientation>(value);
}

Vec3 SectionParameters::unitNormal() const
{
  switch (orientation) {
    case SectionOrientation::XY:
      return Vec3::UnitZ();
    case SectionOrientation::XZ:
      return Vec3::UnitY();
    case SectionOrientation::YZ:
      return Vec3::UnitX();
    case SectionOrientation::Custom:
      break;
  }
  return normal.normalized();
}

void validate(const SectionParameters& params)
{
  sectionOrientation(static_cast<int>(params.orientation));
  for (int k = 0; k < 3; ++k) {
    requireFinite("Origin", params.origin[k], "m");
  }
  if (params.orientation == SectionOrientation::Custom) {
    const double length = params.normal.norm();
    if (!std::isfinite(length) || length == 0.0) {
      std::ostringstream msg;
      msg << "Normal = (" << formatValue(params.normal.x()) << ", " << formatValue(params.normal.y())
          << ", " << formatValue(params.normal.z())
          << ") is not a direction: valid normals are finite and not zero.";
      throw InputError(msg.str());
    }
  }
  requireNonNegative("Trace Distance", params.traceDistance, "m");
  if (params.circleSides < 3) {
    throw InputError("Circle Sides = " + std::to_string(params.circleSides) +
                     " is out of range: valid range is 3 or more.");
  }
}

Vec3 ellipseVertex(const Vec3& centre, const Vec3& a, const Vec3& b, int k, int n)
{
  const double angle = 2.0 * 3.14159265358979323846 * k / n;
  return centre + std::cos(angle) * a + std::sin(angle) * b;
}

ModelSection sectionModel(const Model& model, const SectionParameters& params)
{
  validate(params);
  const Particles& p = model.particles;
  const Bonds& bonds = model.bonds;
  ModelSection s;
  s.modelPlane = model.domain.section2D;
  if (s.modelPlane) {
    s.origin = Vec3(model.domain.origin.x(), model.domain.origin.y(), model.domain.midPlaneZ());
    s.normal = Vec3::UnitZ();
  } else {
    s.origin = params.origin;
    s.normal = params.unitNormal();
  }
  // In-plane axes: the coordinate axis least aligned with the normal, made perpendicular
  // (X and Y for an XY section).
  const Vec3& n = s.normal;
  int least = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(n[k]) < std::abs(n[least])) {
      least = k;
    }
  }
  const Vec3 axis = Vec3::Unit(least);
  s.u = (axis - axis.dot(n) * n).normalized();
  s.v = n.cross(s.u);
  s.traceDistance = params.traceDistance > 0.0 ? params.traceDistance : 0.5 * meanParticleDiameter(model);

  // Circles.
  double nearest = std::numeric_limits<double>::infinity(); // smallest gap |d| - R
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    if (s.modelPlane) {
      s.circles.push_back({ i, p.position[i], r, 0.0 });
      continue;
    }
    const double d = n.dot(p.position[i] - s.origin);
    nearest = std::min(nearest, std::abs(d) - r);
    if (std::abs(d) < r) {
      s.circles.push_back({ i, p.position[i] - d * n, std::sqrt((r - d) * (r + d)), d });
    }
  }

  // Bonds: intact ones crossing the plane, broken ones near it.
  const BondGeometry g = bondGeometry(model);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const Vec3 branch = g.branch[k];
    const double length = branch.norm();
    if (!bonds.broken(k)) {
      if (s.modelPlane) {
        s.crossings.push_back({ k, g.contact[k] });
        continue;
      }
      const double sa = n.dot(g.start[k] - s.origin);
      const double sb = n.dot(g.end(k) - s.origin);
      if ((sa > 0.0 && sb > 0.0) || (sa < 0.0 && sb < 0.0) || (sa == 0.0 && sb == 0.0)) {
        continue;
      }
      s.crossings.push_back({ k, g.start[k] + sa / (sa - sb) * branch });
      continue;
    }
    const double d = s.modelPlane ? 0.0 : n.dot(g.contact[k] - s.origin);
    if (std::abs(d) > s.traceDistance || length == 0.0) {
      continue;
    }
    // The crack disc (radius Rb, normal m along the bond) projected onto the plane.
    const Vec3 m = branch / length;
    const double rb = bonds.radius[k];
    CrackTrace t;
    t.bond = k;
    t.centre = g.contact[k] - d * n;
    t.distance = d;
    const Vec3 w = n.cross(m); // in the plane and in the crack
    if (w.norm() > 1e-12) {
      const Vec3 e = w.normalized();
      t.major = rb * e;
      t.minor = rb * std::abs(m.dot(n)) * n.cross(e);
    } else { // the crack lies parallel to the plane: a circle
      t.major = rb * s.u;
      t.minor = rb * s.v;
    }
    s.traces.push_back(t);
  }

  std::ostringstream msg;
  if (p.empty()) {
    msg << "The model has no particles: the section is empty.";
  } else if (s.modelPlane) {
    msg << "A 2D section model is its own section: " << s.circles.size() << " discs in the model plane z = "
        << formatValue(s.origin.z()) << " m, " << s.crossings.size() << " intact bonds, "
        << s.traces.size() << " broken-bond traces (the Section, Origin and Normal settings apply to 3D models).";
  } else if (s.circles.empty() && s.crossings.empty() && s.traces.empty()) {
    msg << "The plane through (" << formatValue(s.origin.x()) << ", " << formatValue(s.origin.y()) << ", "
        << formatValue(s.origin.z()) << ") m with normal (" << formatValue(n.x()) << ", " << formatValue(n.y())
        << ", " << formatValue(n.z()) << ") misses the model: it cuts no particle (the nearest particle surface is "
        << formatValue(nearest) << " m from it) and no bond; the section is empty.";
  } else {
    msg << "Section " << sectionOrientationName(params.orientation) << ": " << s.circles.size()
        << " particles cut, " << s.crossings.size() << " intact bonds crossing, " << s.traces.size()
        << " broken-bond traces within " << formatValue(s.traceDistance) << " m.";
  }
  s.message = msg.str();
  return s;
}

} // namespace dem
