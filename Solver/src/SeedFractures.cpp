// RockDEM engine: seeding a model with mapped fractures (see dem/SeedFractures.h).
#include "dem/SeedFractures.h"

#include "dem/Errors.h"

#include <algorithm>
#include <cmath>

namespace dem {

namespace {

/// A polygon prepared for crossing tests.
struct Prepared {
  Vec3 center{ 0, 0, 0 };
  Vec3 normal{ 0, 0, 1 };
  Vec3 lower{ 0, 0, 0 };
  Vec3 upper{ 0, 0, 0 };
  int u = 0; ///< the two coordinates the polygon is projected onto
  int v = 1;
  std::vector<double> x, y;
};

/// Newell's normal (twice the vector area) of a polygon.
Vec3 newell(const FracturePolygon& poly)
{
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0, m = poly.size(); i < m; ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % m];
    n.x() += (a.y() - b.y()) * (a.z() + b.z());
    n.y() += (a.z() - b.z()) * (a.x() + b.x());
    n.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return n;
}

Prepared prepare(const FracturePolygon& poly)
{
  Prepared p;
  p.center = Vec3::Zero();
  for (const Vec3& a : poly) {
    p.center += a;
  }
  p.center /= static_cast<double>(poly.size());
  p.normal = newell(poly).normalized();
  int drop = 0;
  p.normal.cwiseAbs().maxCoeff(&drop);
  p.u = (drop + 1) % 3;
  p.v = (drop + 2) % 3;
  p.x.reserve(poly.size());
  p.y.reserve(poly.size());
  for (const Vec3& a : poly) {
    // Vertices projected onto the plane first, so that a slightly non-planar polygon
    // is tested as its best-fit planar version.
    const Vec3 onPlane = a - p.normal.dot(a - p.center) * p.normal;
    p.lower = p.x.empty() ? onPlane : Vec3(p.lower.cwiseMin(onPlane));
    p.upper = p.x.empty() ? onPlane : Vec3(p.upper.cwiseMax(onPlane));
    p.x.push_back(onPlane[p.u]);
    p.y.push_back(onPlane[p.v]);
  }
  return p;
}

bool crosses(const Vec3& p, const Vec3& q, const Prepared& poly)
{
  // Quick rejection: the crossing point lies on the segment and inside the polygon's box.
  const double slack = 1e-9 * (poly.upper - poly.lower).norm();
  for (int k = 0; k < 3; ++k) {
    if (std::max(p[k], q[k]) < poly.lower[k] - slack || std::min(p[k], q[k]) > poly.upper[k] + slack) {
      return false;
    }
  }
  const double sp = poly.normal.dot(p - poly.center);
  const double sq = poly.normal.dot(q - poly.center);
  if ((sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) || (sp == 0.0 && sq == 0.0)) {
    return false;
  }
  const double t = sp / (sp - sq);
  const Vec3 x = p + t * (q - p);
  const double px = x[poly.u];
  const double py = x[poly.v];
  bool inside = false;
  const std::size_t m = poly.x.size();
  for (std::size_t i = 0, j = m - 1; i < m; j = i++) {
    const double yi = poly.y[i];
    const double yj = poly.y[j];
    if ((yi > py) != (yj > py)) {
      const double xCross = poly.x[i] + (py - yi) / (yj - yi) * (poly.x[j] - poly.x[i]);
      if (px < xCross) {
        inside = !inside;
      }
    }
  }
  return inside;
}

} // namespace

void validate(const std::vector<FracturePolygon>& polygons)
{
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const FracturePolygon& poly = polygons[k];
    const std::string name = "Fracture polygon " + std::to_string(k);
    if (poly.size() < 3) {
      throw InputError(name + " has " + std::to_string(poly.size()) +
        " vertices: a fracture polygon needs at least 3.");
    }
    double perimeter = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      if (!poly[i].allFinite()) {
        throw InputError(name + " has a non-finite vertex (vertex " + std::to_string(i) + ").");
      }
      perimeter += (poly[(i + 1) % poly.size()] - poly[i]).norm();
    }
    const double area = 0.5 * newell(poly).norm();
    if (!(area > 1e-12 * perimeter * perimeter)) {
      throw InputError(name + " has no area (" + formatValue(area) +
        " m^2): its vertices are collinear or repeated.");
    }
  }
}

bool segmentCrossesPolygon(const Vec3& p, const Vec3& q, const FracturePolygon& polygon)
{
  validate(std::vector<FracturePolygon>{ polygon });
  return crosses(p, q, prepare(polygon));
}

std::string SeedReport::summary() const
{
  std::string s = std::to_string(seeded) + (seeded == 1 ? " bond" : " bonds") + " of " +
    std::to_string(bonds) + " broken (mode Inherited) where they cross " + std::to_string(polygons) +
    (polygons == 1 ? " fracture polygon" : " fracture polygons");
  if (alreadyBroken) {
    s += "; " + std::to_string(alreadyBroken) + " crossing bonds were already broken and kept their mode";
  }
  if (bonds == 0) {
    s += "; the model has no bonds (cement it first)";
  }
  return s + ".";
}

SeedReport seedFractures(Model& model, const std::vector<FracturePolygon>& polygons)
{
  validate(polygons);
  SeedReport report;
  report.polygons = polygons.size();
  Bonds& b = model.bonds;
  report.bonds = b.size();
  std::vector<Prepared> prepared;
  prepared.reserve(polygons.size());
  for (const auto& poly : polygons) {
    prepared.push_back(prepare(poly));
  }
  const Particles& p = model.particles;
  std::vector<std::size_t> slot;
  {
    // Bonds name particles by id; find their slots.
    std::vector<std::pair<std::int64_t, std::size_t>> ids(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      ids[i] = { p.id[i], i };
    }
    std::sort(ids.begin(), ids.end());
    auto find = [&](std::int64_t id) {
      const auto it = std::lower_bound(ids.begin(), ids.end(), std::make_pair(id, std::size_t{ 0 }));
      if (it == ids.end() || it->first != id) {
        throw InputError("A bond joins particle id " + std::to_string(id) + ", which is not in the model.");
      }
      return it->second;
    };
    slot.resize(2 * b.size());
    for (std::size_t k = 0; k < b.size(); ++k) {
      slot[2 * k] = find(b.idA[k]);
      slot[2 * k + 1] = find(b.idB[k]);
    }
  }
  for (std::size_t k = 0; k < b.size(); ++k) {
    const std::size_t i = slot[2 * k];
    const std::size_t j = slot[2 * k + 1];
    const Vec3& a = p.position[i];
    const Vec3& c = p.position[j];
    const Vec3 branch = minimumImage(model.domain, a, c);
    const bool wrapped = !(branch - (c - a)).isZero(0.0);
    bool hit = false;
    for (const Prepared& poly : prepared) {
      if (crosses(a, a + branch, poly) || (wrapped && crosses(c - branch, c, poly))) {
        hit = true;
        break;
      }
    }
    if (!hit) {
      continue;
    }
    if (b.broken(k)) {
      ++report.alreadyBroken;
      continue;
    }
    const double distance = branch.norm();
    const Vec3 normal = distance > 0.0 ? Vec3(branch / distance) : Vec3(Vec3::UnitZ());
    const double armI = distance * p.radius[i] / (p.radius[i] + p.radius[j]);
    b.markBroken(k, BondFailure::Inherited, model.clock.time, a + armI * normal, normal);
    ++report.seeded;
  }
  return report;
}

} // namespace dem
