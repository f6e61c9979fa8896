// RockDEM engine: the voxel model (see dem/Voxelize.h). SI units.
#include "dem/Voxelize.h"

#include "dem/BondGeometry.h"
#include "dem/Errors.h"
#include "dem/SphereBoxVolume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace dem {
namespace {

constexpr double MiB = 1024.0 * 1024.0;
const char* const AxisName[3] = { "X", "Y", "Z" };

/// Index of the voxel containing coordinate x on an axis (may lie outside [0, n)).
long cellIndex(double x, double origin, double spacing)
{
  return static_cast<long>(std::floor((x - origin) / spacing));
}

/// Wraps an index on a periodic axis; -1 when it lies outside a non-periodic axis.
long wrapIndex(long i, int n, bool wraps)
{
  if (wraps) {
    const long m = i % n;
    return m < 0 ? m + n : m;
  }
  return (i >= 0 && i < n) ? i : -1;
}

/// The part of a polygon on the side x[axis] >= bound (keepAbove) or <= bound.
FracturePolygon clipPolygon(const FracturePolygon& in, int axis, double bound, bool keepAbove)
{
  FracturePolygon out;
  const std::size_t n = in.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = in[k];
    const Vec3& b = in[(k + 1) % n];
    const double da = keepAbove ? a[axis] - bound : bound - a[axis];
    const double db = keepAbove ? b[axis] - bound : bound - b[axis];
    if (da >= 0.0) {
      out.push_back(a);
    }
    if ((da >= 0.0) != (db >= 0.0)) {
      Vec3 x = a + da / (da - db) * (b - a);
      x[axis] = bound;
      out.push_back(x);
    }
  }
  return out;
}

double polygonArea(const FracturePolygon& poly)
{
  Vec3 twice = Vec3::Zero();
  for (std::size_t k = 0; k < poly.size(); ++k) {
    twice += poly[k].cross(poly[(k + 1) % poly.size()]);
  }
  return 0.5 * twice.norm();
}

std::string gridText(const VoxelGrid& g)
{
  std::ostringstream s;
  s << g.dimensions[0] << " x " << g.dimensions[1] << " x " << g.dimensions[2];
  return s.str();
}

} // namespace

VoxelSizing voxelSizing(int value)
{
  if (value < 0 || value > 1) {
    throw InputError("Size By = " + std::to_string(value) +
                     " is out of range: valid values are 0 (Voxel Size) and 1 (Number Of Voxels).");
  }
  return static_cast<VoxelSizing>(value);
}

void validate(const VoxelParameters& params)
{
  voxelSizing(static_cast<int>(params.sizing));
  if (params.sizing == VoxelSizing::VoxelSize) {
    requirePositive("Voxel Size", params.voxelSize, "m");
  } else if (params.numberOfVoxels < 1) {
    throw InputError("Number Of Voxels = " + std::to_string(params.numberOfVoxels) +
                     " is out of range: valid range is 1 or more (voxels along the longest axis).");
  }
  requireNonNegative("Margin", params.margin);
  requirePositive("Memory Limit", params.memoryLimit, "MiB");
}

std::size_t voxelBytes(bool withFractures)
{
  // Solid fraction, damage, density, mean, deviatoric (8 each), stress (48), displacement
  // (24), bonds and broken bonds (4 each); with a DFN the intensity (8), the set (4) and
  // the largest area so far (8). Twice: the engine's arrays and their VTK copy.
  const std::size_t engine = 5 * 8 + 48 + 24 + 2 * 4 + (withFractures ? 8 + 4 + 8 : 0);
  return 2 * engine;
}

VoxelGrid planVoxelGrid(const Model& model, const VoxelParameters& params, bool withFractures)
{
  validate(params);
  const Particles& p = model.particles;
  const Domain& d = model.domain;
  if (p.empty()) {
    throw InputError("The model has no particles: there is nothing to voxelize.");
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 r = Vec3::Constant(p.radius[i]);
    lo = lo.cwiseMin(p.position[i] - r);
    hi = hi.cwiseMax(p.position[i] + r);
  }
  const int axes = d.section2D ? 2 : 3; // axes the voxel size applies to
  std::array<bool, 3> periodic = d.periodic;
  for (int k = 0; k < axes; ++k) {
    if (periodic[k]) {
      lo[k] = d.origin[k];
      hi[k] = d.origin[k] + d.size[k];
    }
  }
  double longest = 0.0;
  for (int k = 0; k < axes; ++k) {
    longest = std::max(longest, hi[k] - lo[k]);
  }
  const double size = params.sizing == VoxelSizing::NumberOfVoxels ? longest / params.numberOfVoxels
                                                                   : params.voxelSize;
  for (int k = 0; k < axes; ++k) {
    if (!periodic[k]) {
      lo[k] -= params.margin * longest;
      hi[k] += params.margin * longest;
    }
  }
  VoxelGrid g;
  std::array<double, 3> count{};
  for (int k = 0; k < axes; ++k) {
    const double extent = hi[k] - lo[k];
    if (periodic[k]) {
      count[k] = std::max(1.0, std::round(extent / size));
      g.spacing[k] = extent / count[k];
      g.origin[k] = lo[k];
      g.wraps[k] = true;
    } else {
      // Cubes of the voxel size, centred on the extent (1e-9: an exact multiple stays one).
      count[k] = std::max(1.0, std::ceil(extent / size * (1.0 - 1e-9)));
      g.spacing[k] = size;
      g.origin[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * count[k] * size;
    }
  }
  if (d.section2D) { // one layer through the slab
    count[2] = 1.0;
    g.spacing[2] = d.slabThickness();
    g.origin[2] = d.origin.z();
  }
  const double voxels = count[0] * count[1] * count[2];
  const double needed = voxels * static_cast<double>(voxelBytes(withFractures)) / MiB; // MiB
  const double available = static_cast<double>(availableMemoryBytes()) / MiB;
  if (needed > params.memoryLimit || needed > available ||
      std::max({ count[0], count[1], count[2] }) > std::numeric_limits<int>::max()) {
    std::ostringstream msg;
    msg << (params.sizing == VoxelSizing::VoxelSize ? "Voxel Size = " + formatValue(size) + " m"
                                                    : "Number Of Voxels = " + std::to_string(params.numberOfVoxels) +
                                                        " (voxels of " + formatValue(size) + " m)")
        << " gives a grid of " << formatValue(count[0]) << " x " << formatValue(count[1]) << " x "
        << formatValue(count[2]) << " = " << formatValue(voxels) << " voxels, which needs "
        << formatValue(needed) << " MiB (" << voxelBytes(withFractures) << " bytes per voxel); ";
    if (needed > params.memoryLimit) {
      msg << "the Memory Limit is " << formatValue(params.memoryLimit)
          << " MiB: use a larger voxel size or raise the Memory Limit.";
    } else {
      msg << "only " << formatValue(available) << " MiB of memory is available: use a larger voxel size.";
    }
    throw InputError(msg.str());
  }
  for (int k = 0; k < 3; ++k) {
    g.dimensions[k] = static_cast<int>(count[k]);
  }
  return g;
}

double polygonBoxArea(const FracturePolygon& polygon, const Vec3& lo, const Vec3& hi)
{
  FracturePolygon clipped = polygon;
  for (int axis = 0; axis < 3 && clipped.size() >= 3; ++axis) {
    clipped = clipPolygon(clipped, axis, lo[axis], true);
    if (clipped.size() >= 3) {
      clipped = clipPolygon(clipped, axis, hi[axis], false);
    }
  }
  return clipped.size() >= 3 ? polygonArea(clipped) : 0.0;
}

VoxelModel voxelize(const Model& model, const VoxelParameters& params,
                    const std::vector<StressTensor>& stresses, const FractureSetPolygons* fractures)
{
  return voxelize(model, planVoxelGrid(model, params, fractures != nullptr), stresses, fractures);
}

VoxelModel voxelize(const Model& model, const VoxelGrid& grid, const std::vector<StressTensor>& stresses,
                    const FractureSetPolygons* fractures)
{
  if (grid.count() == 0 || !(grid.voxelVolume() > 0.0)) {
    throw InputError("The voxel grid has no voxels.");
  }
  if (fractures) {
    validate(fractures->polygons);
    if (fractures->sets.size() != fractures->polygons.size()) {
      throw InputError("The fracture network has " + std::to_string(fractures->polygons.size()) +
                       " polygons but " + std::to_string(fractures->sets.size()) + " set values.");
    }
  }
  VoxelModel out;
  out.grid = grid;
  const Particles& p = model.particles;
  if (stresses.size() != p.size()) {
    throw InputError("The particle stresses have " + std::to_string(stresses.size()) + " entries for " +
                     std::to_string(p.size()) + " particles.");
  }
  const VoxelGrid& g = out.grid;
  const std::array<int, 3>& n = g.dimensions;
  const std::size_t count = g.count();
  const double voxelVolume = g.voxelVolume();
  const bool planar = model.domain.section2D;
  out.solidFraction.assign(count, 0.0); // holds the solid volume until the end
  out.stress.assign(count, StressTensor{ { 0, 0, 0, 0, 0, 0 } }); // holds sum V sigma
  out.displacement.assign(count, Vec3::Zero());                   // holds sum V u

  // Spheres (discs through the slab): the corner volume at each grid node of the sphere's
  // range, then each voxel's volume by inclusion-exclusion over its eight nodes.
  std::vector<double> nodes;
  std::array<std::vector<double>, 3> t;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const Vec3& x = p.position[i];
    std::array<long, 3> first{};
    std::array<long, 3> span{}; // voxels of the range per axis
    for (int k = 0; k < 3; ++k) {
      if (planar && k == 2) {
        first[k] = 0;
        span[k] = 1;
        continue;
      }
      first[k] = cellIndex(x[k] - r, g.origin[k], g.spacing[k]);
      span[k] = cellIndex(x[k] + r, g.origin[k], g.spacing[k]) - first[k] + 1;
      t[k].resize(static_cast<std::size_t>(span[k] + 1));
      for (long c = 0; c <= span[k]; ++c) {
        t[k][static_cast<std::size_t>(c)] = (g.origin[k] + (first[k] + c) * g.spacing[k] - x[k]) / r;
      }
    }
    const std::size_t nx = static_cast<std::size_t>(span[0] + 1);
    const std::size_t ny = static_cast<std::size_t>(span[1] + 1);
    const std::size_t nz = planar ? 1 : static_cast<std::size_t>(span[2] + 1);
    nodes.resize(nx * ny * nz);
    for (std::size_t c = 0; c < nz; ++c) {
      for (std::size_t b = 0; b < ny; ++b) {
        for (std::size_t a = 0; a < nx; ++a) {
          nodes[a + nx * (b + ny * c)] =
            planar ? unitDiscCornerArea(t[0][a], t[1][b]) : unitBallCornerVolume(t[0][a], t[1][b], t[2][c]);
        }
      }
    }
    const double scale = planar ? r * r * model.domain.slabThickness() : r * r * r;
    auto node = [&](long a, long b, long c) {
      return nodes[static_cast<std::size_t>(a) + nx * (static_cast<std::size_t>(b) + ny * static_cast<std::size_t>(c))];
    };
    for (long c = 0; c < span[2]; ++c) {
      const long kz = planar ? 0 : wrapIndex(first[2] + c, n[2], g.wraps[2]);
      for (long b = 0; b < span[1]; ++b) {
        const long ky = wrapIndex(first[1] + b, n[1], g.wraps[1]);
        for (long a = 0; a < span[0]; ++a) {
          const long kx = wrapIndex(first[0] + a, n[0], g.wraps[0]);
          double v = 0.0;
          if (planar) {
            v = node(a, b, 0) - node(a + 1, b, 0) - node(a, b + 1, 0) + node(a + 1, b + 1, 0);
          } else {
            v = node(a, b, c) - node(a + 1, b, c) - node(a, b + 1, c) - node(a, b, c + 1) +
              node(a + 1, b + 1, c) + node(a + 1, b, c + 1) + node(a, b + 1, c + 1) - node(a + 1, b + 1, c + 1);
          }
          v *= scale;
          if (!(v > 0.0) || kx < 0 || ky < 0 || kz < 0) {
            continue; // outside the grid (fitted to another state of the run): not counted
          }
          const std::size_t vox = static_cast<std::size_t>(kx + n[0] * (ky + static_cast<long>(n[1]) * kz));
          out.solidFraction[vox] += v;
          for (int q = 0; q < 6; ++q) {
            out.stress[vox][q] += v * stresses[i][q];
          }
          out.displacement[vox] += v * p.displacement[i];
        }
      }
    }
    out.particleVolume += particleVolume(model.domain, r);
  }

  // Bonds by their midpoint.
  out.bonds.assign(count, 0);
  out.brokenBonds.assign(count, 0);
  const BondGeometry geometry = bondGeometry(model);
  for (std::size_t b = 0; b < geometry.size(); ++b) {
    const Vec3 mid = geometry.midpoint(b);
    std::array<long, 3> index{};
    for (int k = 0; k < 3; ++k) {
      index[k] = (planar && k == 2) ? 0 : wrapIndex(cellIndex(mid[k], g.origin[k], g.spacing[k]), n[k], g.wraps[k]);
    }
    if (index[0] < 0 || index[1] < 0 || index[2] < 0) {
      ++out.bondsOutside; // outside a grid fitted to another state of the run
      continue;
    }
    const std::size_t vox = static_cast<std::size_t>(index[0] + n[0] * (index[1] + static_cast<long>(n[1]) * index[2]));
    ++out.bonds[vox];
    if (model.bonds.broken(b)) {
      ++out.brokenBonds[vox];
    }
  }

  // Fractures: the area of each polygon inside each voxel of its bounding box.
  if (fractures) {
    out.fractureIntensity.assign(count, 0.0);
    out.fractureSet.assign(count, -1);
    std::vector<double> largest(count, 0.0);
    for (std::size_t f = 0; f < fractures->polygons.size(); ++f) {
      const FracturePolygon& poly = fractures->polygons[f];
      Vec3 lo = poly.front();
      Vec3 hi = poly.front();
      for (const Vec3& v : poly) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      std::array<long, 3> from{};
      std::array<long, 3> to{};
      for (int k = 0; k < 3; ++k) {
        from[k] = std::max(0L, cellIndex(lo[k], g.origin[k], g.spacing[k]));
        to[k] = std::min(static_cast<long>(n[k]) - 1, cellIndex(hi[k], g.origin[k], g.spacing[k]));
      }
      for (long kz = from[2]; kz <= to[2]; ++kz) {
        for (long ky = from[1]; ky <= to[1]; ++ky) {
          for (long kx = from[0]; kx <= to[0]; ++kx) {
            const Vec3 corner = g.origin + Vec3(kx * g.spacing.x(), ky * g.spacing.y(), kz * g.spacing.z());
            const double area = polygonBoxArea(poly, corner, corner + g.spacing);
            if (area <= 0.0) {
              continue;
            }
            const std::size_t vox = static_cast<std::size_t>(kx + n[0] * (ky + static_cast<long>(n[1]) * kz));
            out.fractureIntensity[vox] += area / voxelVolume;
            out.fractureArea += area;
            if (area > largest[vox]) {
              largest[vox] = area;
              out.fractureSet[vox] = fractures->sets[f];
            }
          }
        }
      }
    }
  }

  // From sums to values.
  out.damage.assign(count, 0.0);
  out.brokenBondDensity.assign(count, 0.0);
  out.meanStress.assign(count, 0.0);
  out.deviatoricStress.assign(count, 0.0);
  for (std::size_t v = 0; v < count; ++v) {
    const double solid = out.solidFraction[v];
    out.solidVolume += solid;
    out.solidFraction[v] = solid / voxelVolume;
    for (double& s : out.stress[v]) {
      s /= voxelVolume;
    }
    out.meanStress[v] = dem::meanStress(out.stress[v], planar);
    out.deviatoricStress[v] = vonMisesStress(out.stress[v], planar);
    if (solid > 0.0) {
      out.displacement[v] /= solid;
    }
    if (out.bonds[v] > 0) {
      out.damage[v] = static_cast<double>(out.brokenBonds[v]) / out.bonds[v];
    }
    out.brokenBondDensity[v] = out.brokenBonds[v] / voxelVolume;
  }

  std::ostringstream msg;
  msg << "Voxel model: " << gridText(g) << " voxels of " << formatValue(g.spacing.x()) << " x "
      << formatValue(g.spacing.y()) << " x " << formatValue(g.spacing.z()) << " m ("
      << formatValue(static_cast<double>(count) * voxelBytes(fractures != nullptr) / MiB)
      << " MiB); solid volume " << formatValue(out.solidVolume) << " m^3 of "
      << formatValue(out.particleVolume) << " m^3 of particles; " << geometry.size() << " bonds";
  if (fractures) {
    msg << "; " << fractures->polygons.size() << " fracture polygons, " << formatValue(out.fractureArea)
        << " m^2 of them inside the grid";
  }
  msg << ".";
  const double outside = out.particleVolume - out.solidVolume;
  if (outside > 1e-9 * out.particleVolume || out.bondsOutside > 0) {
    msg << " Outside the grid (fitted to another state of the run): " << formatValue(outside) << " m^3 ("
        << formatValue(100.0 * outside / out.particleVolume) << " %) of the particles' volume and "
        << out.bondsOutside << " bonds, not counted.";
  }
  for (int k = 0; k < 3; ++k) {
    if (g.wraps[k]) {
      msg << " Periodic " << AxisName[k] << ": the voxels divide the model box.";
    }
  }
  out.message = msg.str();
  return out;
}

} // namespace dem
