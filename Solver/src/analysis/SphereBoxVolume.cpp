// RockDEM engine: exact sphere-box volumes and disc-rectangle areas (see dem/SphereBoxVolume.h).
#include "dem/SphereBoxVolume.h"

#include <algorithm>
#include <cmath>

namespace dem {
namespace {

constexpr double Pi = 3.14159265358979323846;

/// Area of the unit disc with y > h.
double discSegment(double h)
{
  if (h >= 1.0) {
    return 0.0;
  }
  if (h <= -1.0) {
    return Pi;
  }
  return std::acos(h) - h * std::sqrt(1.0 - h * h);
}

/// Volume of the unit ball with z > h: a cap of height 1 - h.
double ballCap(double h)
{
  if (h >= 1.0) {
    return 0.0;
  }
  if (h <= -1.0) {
    return 4.0 * Pi / 3.0;
  }
  return Pi * (1.0 - h) * (1.0 - h) * (2.0 + h) / 3.0;
}

/// Area of the disc of radius squared r2 with y > b and z > c (b, c >= 0, b^2 + c^2 < r2),
/// given phi = pi/2 - asin(b / r) - asin(c / r), the angle its arc spans.
double discCorner(double r2, double b, double c, double phi)
{
  return b * c - 0.5 * b * std::sqrt(std::max(0.0, r2 - b * b)) -
    0.5 * c * std::sqrt(std::max(0.0, r2 - c * c)) + 0.5 * r2 * phi;
}

double clampedAsin(double x) { return std::asin(std::min(1.0, std::max(-1.0, x))); }
double clampedAcos(double x) { return std::acos(std::min(1.0, std::max(-1.0, x))); }

/// The ball corner for a, b, c >= 0 (the divergence theorem, dem/SphereBoxVolume.h).
double ballCornerNonNegative(double a, double b, double c)
{
  if (a * a + b * b + c * c >= 1.0) {
    return 0.0;
  }
  const double ra2 = 1.0 - a * a;
  const double rb2 = 1.0 - b * b;
  const double rc2 = 1.0 - c * c;
  const double ra = std::sqrt(ra2);
  const double rb = std::sqrt(rb2);
  const double rc = std::sqrt(rc2);
  // Angles spanned by the three arcs of the spherical face, each in its circle's plane.
  const double phiX = 0.5 * Pi - clampedAsin(b / ra) - clampedAsin(c / ra);
  const double phiY = 0.5 * Pi - clampedAsin(a / rb) - clampedAsin(c / rb);
  const double phiZ = 0.5 * Pi - clampedAsin(a / rc) - clampedAsin(b / rc);
  // Turning angles at the three vertices, between the inward normals of the two circles.
  const double turnXY = clampedAcos(-a * b / (ra * rb));
  const double turnYZ = clampedAcos(-b * c / (rb * rc));
  const double turnXZ = clampedAcos(-a * c / (ra * rc));
  // Gauss-Bonnet: the geodesic curvature of the circle x = a is a / ra, its arc ra phiX.
  const double solidAngle = 2.0 * Pi - turnXY - turnYZ - turnXZ - a * phiX - b * phiY - c * phiZ;
  const double faceX = discCorner(ra2, b, c, phiX);
  const double faceY = discCorner(rb2, a, c, phiY);
  const double faceZ = discCorner(rc2, a, b, phiZ);
  return std::max(0.0, (solidAngle - a * faceX - b * faceY - c * faceZ) / 3.0);
}

/// Volume of the unit ball with y > p and z > q.
double ballWedge(double p, double q)
{
  if (p >= 1.0 || q >= 1.0) {
    return 0.0;
  }
  p = std::max(p, -1.0);
  q = std::max(q, -1.0);
  if (p < 0.0) {
    return ballCap(q) - ballWedge(-p, q);
  }
  if (q < 0.0) {
    return ballCap(p) - ballWedge(p, -q);
  }
  return 2.0 * ballCornerNonNegative(0.0, p, q);
}

} // namespace

double unitDiscCornerArea(double a, double b)
{
  if (a >= 1.0 || b >= 1.0) {
    return 0.0;
  }
  a = std::max(a, -1.0);
  b = std::max(b, -1.0);
  // x > a with a < 0 is everything but the mirror image of x > -a.
  if (a < 0.0) {
    return discSegment(b) - unitDiscCornerArea(-a, b);
  }
  if (b < 0.0) {
    return discSegment(a) - unitDiscCornerArea(a, -b);
  }
  if (a * a + b * b >= 1.0) {
    return 0.0;
  }
  return std::max(0.0, discCorner(1.0, a, b, 0.5 * Pi - clampedAsin(a) - clampedAsin(b)));
}

double unitBallCornerVolume(double a, double b, double c)
{
  if (a >= 1.0 || b >= 1.0 || c >= 1.0) {
    return 0.0;
  }
  a = std::max(a, -1.0);
  b = std::max(b, -1.0);
  c = std::max(c, -1.0);
  if (a < 0.0) {
    return ballWedge(b, c) - unitBallCornerVolume(-a, b, c);
  }
  if (b < 0.0) {
    return ballWedge(a, c) - unitBallCornerVolume(a, -b, c);
  }
  if (c < 0.0) {
    return ballWedge(a, b) - unitBallCornerVolume(a, b, -c);
  }
  return ballCornerNonNegative(a, b, c);
}

double sphereBoxVolume(const Vec3& centre, double radius, const Vec3& lo, const Vec3& hi)
{
  if (!(radius > 0.0)) {
    return 0.0;
  }
  for (int k = 0; k < 3; ++k) {
    if (!(hi[k] > lo[k]) || lo[k] >= centre[k] + radius || hi[k] <= centre[k] - radius) {
      return 0.0;
    }
  }
  const Vec3 a = (lo - centre) / radius;
  const Vec3 b = (hi - centre) / radius;
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const double x = (corner & 1) ? b.x() : a.x();
    const double y = (corner & 2) ? b.y() : a.y();
    const double z = (corner & 4) ? b.z() : a.z();
    const int ones = ((corner & 1) ? 1 : 0) + ((corner & 2) ? 1 : 0) + ((corner & 4) ? 1 : 0);
    sum += (ones % 2 ? -1.0 : 1.0) * unitBallCornerVolume(x, y, z);
  }
  return std::max(0.0, sum) * radius * radius * radius;
}

double discRectangleArea(double cx, double cy, double radius, double x0, double y0, double x1,
                         double y1)
{
  if (!(radius > 0.0) || !(x1 > x0) || !(y1 > y0) || x0 >= cx + radius || x1 <= cx - radius ||
      y0 >= cy + radius || y1 <= cy - radius) {
    return 0.0;
  }
  const double ax = (x0 - cx) / radius;
  const double bx = (x1 - cx) / radius;
  const double ay = (y0 - cy) / radius;
  const double by = (y1 - cy) / radius;
  const double sum = unitDiscCornerArea(ax, ay) - unitDiscCornerArea(bx, ay) -
    unitDiscCornerArea(ax, by) + unitDiscCornerArea(bx, by);
  return std::max(0.0, sum) * radius * radius;
}

} // namespace dem
