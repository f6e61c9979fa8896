// RockDEM engine: one cell grid per size class (see dem/SizeClassGrids.h). SI units.
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dem {

namespace {
constexpr std::uint32_t kEmpty = 0xffffffffu;
/// Cell spans are computed in double and clamped to this many cells before conversion.
constexpr double kSpanLimit = 1.0e12;
} // namespace

SizeClassGrids::SizeClassGrids(const Domain& domain, double smallestRadius, double largestRadius,
                               std::size_t maxCellsPerClass)
  : origin_(domain.origin)
  , length_(domain.size)
  , periodic_(domain.periodic)
  , planar_(domain.section2D)
  , smallestRadius_(smallestRadius)
{
  if (!(smallestRadius > 0.0) || !std::isfinite(smallestRadius) || !std::isfinite(largestRadius)) {
    throw std::invalid_argument("SizeClassGrids: the smallest radius must be positive and finite");
  }
  if (planar_) {
    periodic_[2] = false;
  }
  const int dimension = planar_ ? 2 : 3;
  const double cellCap = static_cast<double>(std::max<std::size_t>(maxCellsPerClass, 1));

  for (int k = 0; k < kMaxClasses; ++k) {
    ClassGrid& g = classes_[k];
    // Class k holds radii below rmin 2^(k+1); the last class holds everything larger.
    g.nominalMaxRadius = (k + 1 < kMaxClasses)
      ? smallestRadius * std::ldexp(1.0, k + 1)
      : std::max(largestRadius, smallestRadius * std::ldexp(1.0, k + 1));

    // Cell edge about one diameter of the class's largest particle; grow it until the cell
    // count is under the cap. Cells tile the box exactly (edge = length / cells).
    double targetEdge = 2.0 * g.nominalMaxRadius;
    std::array<double, 3> n{ { 1.0, 1.0, 1.0 } };
    for (;;) {
      double total = 1.0;
      for (int a = 0; a < dimension; ++a) {
        n[a] = std::max(1.0, std::min(kSpanLimit, std::floor(length_[a] / targetEdge)));
        total *= n[a];
      }
      if (total <= cellCap) {
        break;
      }
      targetEdge *= std::max(1.01, std::pow(total / cellCap, 1.0 / dimension));
    }
    for (int a = 0; a < 3; ++a) {
      g.cells[a] = static_cast<long>(n[a]);
      g.edge[a] = (a < dimension) ? length_[a] / n[a] : length_[a];
      g.inverseEdge[a] = (a < dimension) ? n[a] / length_[a] : 0.0;
    }
  }
}

void SizeClassGrids::reserve(std::size_t n)
{
  sphere_.reserve(n);
  key_.reserve(n);
  next_.reserve(n);
  class_.reserve(n);
  storageOf_.reserve(n);
}

int SizeClassGrids::sizeClass(double radius) const
{
  return sizeClassOf(radius, smallestRadius_);
}

Vec3 SizeClassGrids::wrapped(const Vec3& x) const
{
  Vec3 w = x;
  for (int a = 0; a < 3; ++a) {
    if (periodic_[a]) {
      const double L = length_[a];
      w[a] -= L * std::floor((x[a] - origin_[a]) / L);
      if (w[a] >= origin_[a] + L) { // rounding can land exactly on the upper face
        w[a] -= L;
      }
      if (w[a] < origin_[a]) {
        w[a] = origin_[a];
      }
    }
  }
  return w;
}

long SizeClassGrids::cellIndex(const ClassGrid& g, const Vec3& x) const
{
  std::array<long, 3> c{ { 0, 0, 0 } };
  const int dimension = planar_ ? 2 : 3;
  for (int a = 0; a < dimension; ++a) {
    const double t = std::max(-1.0, std::min(kSpanLimit, (x[a] - origin_[a]) * g.inverseEdge[a]));
    // x is already wrapped on periodic axes; off-box particles on walled axes go to the
    // boundary cell (queries clamp the same way, so they are still found).
    c[a] = std::min(std::max(static_cast<long>(std::floor(t)), 0L), g.cells[a] - 1);
  }
  return (c[2] * g.cells[1] + c[1]) * g.cells[0] + c[0];
}

std::size_t SizeClassGrids::insert(const Vec3& centre, double radius)
{
  const std::size_t key = sphere_.size();
  if (key >= kEmpty) {
    throw std::length_error("SizeClassGrids: too many particles for 32-bit cell links");
  }
  const int k = sizeClass(radius);
  ClassGrid& g = classes_[k];
  if (g.head.empty()) {
    const std::size_t cells = static_cast<std::size_t>(g.cells[0] * g.cells[1] * g.cells[2]);
    g.head.assign(cells, kEmpty);
    g.runStart.assign(cells + 1, 0); // no compacted particles yet: every run empty
  }
  const Vec3 x = wrapped(centre);
  const long cell = cellIndex(g, x);
  const std::size_t s = key; // appended at the end of storage
  sphere_.push_back({ x.x(), x.y(), planar_ ? 0.0 : x.z(), radius });
  key_.push_back(static_cast<std::uint32_t>(key));
  class_.push_back(static_cast<std::uint8_t>(k));
  next_.push_back(g.head[cell]);
  storageOf_.push_back(static_cast<std::uint32_t>(s));
  g.head[cell] = static_cast<std::uint32_t>(s);
  g.maxRadius = std::max(g.maxRadius, radius);
  ++g.count;
  ++g.recent;

  // Keep at least four fifths of the particles in cell order.
  constexpr std::size_t kFirstCompaction = 1024;
  if (sphere_.size() >= std::max(kFirstCompaction, compactedSize_ + compactedSize_ / 4)) {
    compact();
  }
  return key;
}

void SizeClassGrids::compact()
{
  const std::size_t n = sphere_.size();
  // Counting sort by (class, cell): runStart becomes the first storage index of each cell.
  std::vector<std::uint32_t> cellOf(n);
  std::uint32_t offset = 0;
  for (int k = 0; k < kMaxClasses; ++k) {
    ClassGrid& g = classes_[k];
    if (g.count == 0) {
      continue;
    }
    std::fill(g.runStart.begin(), g.runStart.end(), 0u);
    for (std::size_t s = 0; s < n; ++s) {
      if (class_[s] == k) {
        const Vec3 x(sphere_[s].x, sphere_[s].y, sphere_[s].z);
        cellOf[s] = static_cast<std::uint32_t>(cellIndex(g, x));
        ++g.runStart[cellOf[s] + 1];
      }
    }
    g.runStart[0] = offset;
    for (std::size_t c = 0; c + 1 < g.runStart.size(); ++c) {
      g.runStart[c + 1] += g.runStart[c];
    }
    offset = g.runStart.back();
    std::fill(g.head.begin(), g.head.end(), kEmpty);
    g.recent = 0;
  }

  std::vector<Sphere> sphere(n);
  std::vector<std::uint32_t> key(n);
  std::vector<std::uint8_t> cls(n);
  std::array<std::vector<std::uint32_t>, kMaxClasses> fill;
  for (int k = 0; k < kMaxClasses; ++k) {
    fill[k] = classes_[k].runStart;
  }
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t t = fill[class_[s]][cellOf[s]]++;
    sphere[t] = sphere_[s];
    key[t] = key_[s];
    cls[t] = class_[s];
  }
  sphere_.swap(sphere);
  key_.swap(key);
  class_.swap(cls);
  std::fill(next_.begin(), next_.end(), kEmpty);
  for (std::size_t t = 0; t < n; ++t) {
    storageOf_[key_[t]] = static_cast<std::uint32_t>(t);
  }
  compactedSize_ = n;
}

void SizeClassGrids::insertAll(const Particles& particles)
{
  if (!sphere_.empty()) {
    throw std::logic_error("SizeClassGrids::insertAll needs empty grids");
  }
  reserve(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    insert(particles.position[i], particles.radius[i]);
  }
  if (compactedSize_ != sphere_.size()) {
    compact();
  }
}

void SizeClassGrids::setRadius(std::size_t key, double radius)
{
  const std::uint32_t s = storageOf_[key];
  sphere_[s].r = radius;
  ClassGrid& g = classes_[class_[s]];
  g.maxRadius = std::max(g.maxRadius, radius);
}

SizeClassGrids::CellSpan SizeClassGrids::cellSpan(const ClassGrid& g, int axis, double coordinate,
                                                  double reach) const
{
  const long n = g.cells[axis];
  if (planar_ && axis == 2) {
    return { 0, 1, false };
  }
  const double lo = std::max(-kSpanLimit, std::min(kSpanLimit,
                               (coordinate - reach - origin_[axis]) * g.inverseEdge[axis]));
  const double hi = std::max(-kSpanLimit, std::min(kSpanLimit,
                               (coordinate + reach - origin_[axis]) * g.inverseEdge[axis]));
  long first = static_cast<long>(std::floor(lo));
  long last = static_cast<long>(std::floor(hi));
  if (periodic_[axis]) {
    const long count = last - first + 1;
    if (count >= n) {
      return { 0, n, false }; // the reach spans the period: every cell, once
    }
    first %= n;
    if (first < 0) {
      first += n;
    }
    return { first, count, true }; // first + count - 1 < 2n: one wrap at most
  }
  // Walled axis: clamp both ends, as insert() clamps particles lying off the box.
  first = std::min(std::max(first, 0L), n - 1);
  last = std::min(std::max(last, 0L), n - 1);
  return { first, last - first + 1, false };
}

template <class Visit>
bool SizeClassGrids::visitCandidates(const ClassGrid& g, const Vec3& x, double reach,
                                     Visit&& visit) const
{
  const CellSpan sx = cellSpan(g, 0, x.x(), reach);
  const CellSpan sy = cellSpan(g, 1, x.y(), reach);
  const CellSpan sz = cellSpan(g, 2, x.z(), reach);
  const long nx = g.cells[0];
  const long ny = g.cells[1];
  const long nz = g.cells[2];
  for (long iz = 0; iz < sz.count; ++iz) {
    long cz = sz.first + iz;
    if (sz.wrap && cz >= nz) {
      cz -= nz;
    }
    for (long iy = 0; iy < sy.count; ++iy) {
      long cy = sy.first + iy;
      if (sy.wrap && cy >= ny) {
        cy -= ny;
      }
      const long row = (cz * ny + cy) * nx;
      // Compacted particles: the span along x is one contiguous run (two across a seam).
      long cx = sx.first;
      for (long left = sx.count; left > 0;) {
        const long run = std::min(left, nx - cx);
        const std::uint32_t end = g.runStart[row + cx + run];
        for (std::uint32_t s = g.runStart[row + cx]; s < end; ++s) {
          if (visit(s, sphere_[s])) {
            return true;
          }
        }
        left -= run;
        cx = 0;
      }
      // Particles inserted since the last compaction: linked per cell.
      if (g.recent == 0) {
        continue;
      }
      for (long ix = 0; ix < sx.count; ++ix) {
        long c = sx.first + ix;
        if (c >= nx) {
          c -= nx;
        }
        for (std::uint32_t s = g.head[row + c]; s != kEmpty; s = next_[s]) {
          if (visit(s, sphere_[s])) {
            return true;
          }
        }
      }
    }
  }
  return false;
}

bool SizeClassGrids::overlapsAny(const Vec3& centre, double r) const
{
  const Vec3 x = wrapped(centre);
  const std::array<double, 3> L{ { length_.x(), length_.y(), length_.z() } };
  const std::array<double, 3> halfL{ { 0.5 * L[0], 0.5 * L[1], 0.5 * L[2] } };
  const double zQuery = planar_ ? 0.0 : x.z();
  const auto overlaps = [&](std::uint32_t, const Sphere& s) {
    double d[3] = { s.x - x.x(), s.y - x.y(), s.z - zQuery };
    for (int a = 0; a < 3; ++a) {
      if (periodic_[a]) { // both centres wrapped into the box: |d| < L
        d[a] = d[a] > halfL[a] ? d[a] - L[a] : (d[a] < -halfL[a] ? d[a] + L[a] : d[a]);
      }
    }
    const double contact = r + s.r;
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < contact * contact;
  };

  // In a dense pack a rejected candidate usually overlaps something in its own cell: look
  // there first (reach 0 is the home cell alone), then everywhere it could reach.
  for (const ClassGrid& g : classes_) {
    if (g.count != 0 && visitCandidates(g, x, 0.0, overlaps)) {
      return true;
    }
  }
  for (const ClassGrid& g : classes_) {
    // No particle of this class can touch the candidate from further than r + its max radius.
    if (g.count != 0 && visitCandidates(g, x, r + g.maxRadius, overlaps)) {
      return true;
    }
  }
  return false;
}

SizeClassGrids::Nearest SizeClassGrids::nearest(const Vec3& centre, double r, double reach,
                                                std::size_t ignore) const
{
  const Vec3 x = wrapped(centre);
  const std::array<double, 3> L{ { length_.x(), length_.y(), length_.z() } };
  const std::array<double, 3> halfL{ { 0.5 * L[0], 0.5 * L[1], 0.5 * L[2] } };
  const double zQuery = planar_ ? 0.0 : x.z();

  // Work in storage indices; translate to a key once at the end.
  const std::uint32_t ignored = (ignore < storageOf_.size()) ? storageOf_[ignore] : kEmpty;
  Nearest best{ reach, npos, 0.0 };
  const auto closer = [&](std::uint32_t j, const Sphere& s) {
    if (j == ignored) {
      return false;
    }
    double d[3] = { s.x - x.x(), s.y - x.y(), s.z - zQuery };
    for (int a = 0; a < 3; ++a) {
      if (periodic_[a]) {
        d[a] = d[a] > halfL[a] ? d[a] - L[a] : (d[a] < -halfL[a] ? d[a] + L[a] : d[a]);
      }
    }
    const double distance2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double bound = r + s.r + best.gap; // centre distance of a surface at the best gap
    if (bound > 0.0 && distance2 < bound * bound) {
      const double gap = std::sqrt(distance2) - r - s.r;
      if (gap < best.gap) {
        best = { gap, j, s.r };
      }
    }
    return false;
  };

  // The home cells first: a close neighbour found there shrinks the reach of the full search.
  for (const ClassGrid& g : classes_) {
    if (g.count != 0) {
      visitCandidates(g, x, 0.0, closer);
    }
  }
  for (const ClassGrid& g : classes_) {
    // A surface of this class closer than the best gap so far has its centre within this.
    const double classReach = r + g.maxRadius + best.gap;
    if (g.count != 0 && classReach > 0.0) {
      visitCandidates(g, x, classReach, closer);
    }
  }
  if (best.key != npos) {
    best.key = key_[best.key];
  }
  return best;
}

void SizeClassGrids::neighboursWithin(const Vec3& centre, double r, double reach,
                                      std::size_t ignore, std::vector<std::size_t>& keys) const
{
  keys.clear();
  const Vec3 x = wrapped(centre);
  const std::uint32_t ignored = (ignore < storageOf_.size()) ? storageOf_[ignore] : kEmpty;
  for (const ClassGrid& g : classes_) {
    const double classReach = r + g.maxRadius + reach;
    if (g.count == 0 || !(classReach > 0.0)) {
      continue;
    }
    visitCandidates(g, x, classReach, [&](std::uint32_t s, const Sphere& sphere) {
      if (s != ignored) {
        const Vec3 d = separation(x, Vec3(sphere.x, sphere.y, planar_ ? x.z() : sphere.z));
        if (d.norm() - r - sphere.r < reach) {
          keys.push_back(key_[s]);
        }
      }
      return false;
    });
  }
}

Vec3 SizeClassGrids::separation(const Vec3& a, const Vec3& b) const
{
  Vec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (periodic_[k]) {
      d[k] -= length_[k] * std::round(d[k] / length_[k]);
    }
  }
  if (planar_) {
    d.z() = 0.0;
  }
  return d;
}

} // namespace dem
