// RockDEM engine: the flexible membrane (see dem/Membrane.h). SI units.
#include "dem/Membrane.h"

#include "dem/Errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace dem {

namespace {
constexpr double Pi = 3.14159265358979323846;
}

bool membraneActive(const Model& model)
{
  const LoadTestState& t = model.test;
  const LoadTestSettings& s = t.settings;
  return s.confinement == Confinement::Membrane &&
    (s.mode == TestMode::Triaxial || s.mode == TestMode::Isotropic) && t.stage != TestStage::Idle &&
    !model.domain.section2D && model.walls.size() == 6 && !model.particles.empty();
}

MembraneSurface membraneSurface(const Model& model, std::vector<Vec3>* forces)
{
  if (!membraneActive(model)) {
    if (forces) {
      forces->clear();
    }
    return MembraneSurface();
  }
  const LoadTestSettings& s = model.test.settings;
  return lateralSurface(model, s.axis, s.confiningStress, forces);
}

MembraneSurface lateralSurface(const Model& model, int a, double pressure, std::vector<Vec3>* forces)
{
  MembraneSurface out;
  const Particles& p = model.particles;
  const std::size_t n = p.size();
  if (n == 0 || model.walls.size() != 6 || a < 0 || a > 2) {
    if (forces) {
      forces->clear();
    }
    return out;
  }
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  // The axis: through the centroid of the centres across it.
  double cb = 0.0;
  double cc = 0.0;
  double meanRadius = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    cb += p.position[i][b];
    cc += p.position[i][c];
    meanRadius += p.radius[i];
  }
  cb /= static_cast<double>(n);
  cc /= static_cast<double>(n);
  meanRadius /= static_cast<double>(n);
  double meanDistance = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    meanDistance += std::hypot(p.position[i][b] - cb, p.position[i][c] - cc);
  }
  meanDistance /= static_cast<double>(n);
  const double low = model.walls[2 * a].position;  // m, the platens
  const double high = model.walls[2 * a + 1].position;
  const double length = high - low;
  // The number of bins from a radius that one far-flung grain barely moves: the centres of
  // a uniform disc lie 2/3 of its radius from the axis on average.
  const double binEdge = MembraneBinSize * 2.0 * meanRadius;             // m
  const double roughRadius = 1.5 * meanDistance + meanRadius;            // m
  const int sectors = std::max(6, static_cast<int>(std::lround(2.0 * Pi * roughRadius / binEdge)));
  const int slices = std::max(1, static_cast<int>(std::lround(length / binEdge)));
  const std::size_t bins = static_cast<std::size_t>(sectors) * static_cast<std::size_t>(slices);
  std::vector<long> grain(bins, -1);
  std::vector<double> reach(bins, -1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double db = p.position[i][b] - cb;
    const double dc = p.position[i][c] - cc;
    const double distance = std::hypot(db, dc);
    if (!(distance > 0.0)) {
      continue; // on the axis: no outward direction (never the outermost grain of a bin)
    }
    const double theta = std::atan2(dc, db); // [-pi, pi]
    const int sector = std::min(sectors - 1, std::max(0, static_cast<int>(std::floor((theta + Pi) / (2.0 * Pi) * sectors))));
    const int slice = length > 0.0
      ? std::min(slices - 1, std::max(0, static_cast<int>(std::floor((p.position[i][a] - low) / length * slices))))
      : 0;
    const std::size_t bin = static_cast<std::size_t>(slice) * static_cast<std::size_t>(sectors) + static_cast<std::size_t>(sector);
    const double outer = distance + p.radius[i];
    if (outer > reach[bin]) { // strict: a tie keeps the lower slot
      reach[bin] = outer;
      grain[bin] = static_cast<long>(i);
    }
  }
  // An empty bin (no centre in its wedge of the slice: rare, at a gap in the surface) gives
  // its area to the nearest occupied sector of the same slice (the lower one on a tie), so
  // that the membrane leaves no hole.
  std::vector<int> share(bins, 0); // bins whose area each bin's grain carries
  for (int slice = 0; slice < slices; ++slice) {
    const std::size_t row = static_cast<std::size_t>(slice) * static_cast<std::size_t>(sectors);
    for (int sector = 0; sector < sectors; ++sector) {
      if (grain[row + static_cast<std::size_t>(sector)] >= 0) {
        ++share[row + static_cast<std::size_t>(sector)];
        continue;
      }
      for (int step = 1; step <= sectors / 2; ++step) {
        const int below = (sector - step + sectors) % sectors;
        const int above = (sector + step) % sectors;
        if (grain[row + static_cast<std::size_t>(below)] >= 0) {
          ++share[row + static_cast<std::size_t>(below)];
          break;
        }
        if (grain[row + static_cast<std::size_t>(above)] >= 0) {
          ++share[row + static_cast<std::size_t>(above)];
          break;
        }
      }
    }
  }
  if (forces) {
    forces->assign(n, Vec3::Zero());
  }
  out.centre[b] = cb;
  out.centre[c] = cc;
  out.centre[a] = 0.5 * (low + high);
  out.length = length;
  out.sectors = sectors;
  out.slices = slices;
  out.minRadius = std::numeric_limits<double>::max();
  out.maxRadius = 0.0;
  const double arcPerRadius = 2.0 * Pi / static_cast<double>(sectors); // rad
  const double sliceLength = length / static_cast<double>(slices);     // m
  double sumReach = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    if (grain[k] < 0) {
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(grain[k]);
    const double db = p.position[i][b] - cb;
    const double dc = p.position[i][c] - cc;
    const double distance = std::hypot(db, dc);
    // m^2: the bin's surface at the grain's outer radius (and that of empty bins it covers)
    const double area = arcPerRadius * reach[k] * sliceLength * static_cast<double>(share[k]);
    Vec3 f = Vec3::Zero();
    f[b] = -pressure * area * db / distance;
    f[c] = -pressure * area * dc / distance;
    if (forces) {
      (*forces)[i] = f;
    }
    out.force += pressure * area;
    out.netForce += f;
    sumReach += reach[k];
    out.minRadius = std::min(out.minRadius, reach[k]);
    out.maxRadius = std::max(out.maxRadius, reach[k]);
    ++out.surfaceGrains;
  }
  if (out.surfaceGrains == 0) {
    out.minRadius = 0.0;
    return out;
  }
  out.radius = sumReach / static_cast<double>(out.surfaceGrains);
  double variance = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    if (grain[k] >= 0) {
      variance += (reach[k] - out.radius) * (reach[k] - out.radius);
    }
  }
  out.radiusSpread = std::sqrt(variance / static_cast<double>(out.surfaceGrains));
  out.lateralArea = 2.0 * Pi * out.radius * length;
  out.crossSection = Pi * out.radius * out.radius;
  return out;
}

void validateMembraneSpecimen(const Model& model, const LoadTestSettings& settings)
{
  if (settings.confinement != Confinement::Membrane) {
    return;
  }
  if (model.domain.section2D) {
    throw InputError("Confinement = Membrane is out of range for a 2D section: the membrane wraps a 3D "
                     "cylinder (valid values in 2D: Rigid Walls).");
  }
  const Particles& p = model.particles;
  if (p.empty()) {
    return;
  }
  const int a = settings.axis;
  const char* axisName[3] = { "X", "Y", "Z" };
  double halfWidth = std::numeric_limits<double>::max(); // m, half the smaller lateral extent
  double middle[3] = { 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k) {
    if (k == a) {
      continue;
    }
    const auto [lo, hi] = grainExtent(p, k);
    halfWidth = std::min(halfWidth, 0.5 * (hi - lo));
    middle[k] = 0.5 * (lo + hi);
  }
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  double farthest = 0.0; // m, centre distance from the axis through the middle
  for (std::size_t i = 0; i < p.size(); ++i) {
    farthest = std::max(farthest, std::hypot(p.position[i][b] - middle[b], p.position[i][c] - middle[c]));
  }
  if (farthest > halfWidth) {
    throw InputError(std::string("Confinement = Membrane needs a cylindrical specimen along Axis = ") + axisName[a] +
      ", but this one is not round across " + axisName[a] + ": a particle centre lies " + formatValue(farthest) +
      " m from the specimen's axis, beyond its half width " + formatValue(halfWidth) +
      " m (valid: every centre within the half width, as in a cylinder; a box's corners lie up to 1.41 half "
      "widths out). Carve a cylinder along " + axisName[a] + " with DEM Specimen (Shape = Cylinder), or use "
      "Confinement = Rigid Walls.");
  }
}

} // namespace dem
