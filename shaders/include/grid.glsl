// RockDEM shaders: the cell grids of the neighbour search, one per size class, mirroring
// dem::SizeClassGrids (wrapped centres, cell index, cell span of a query, separation).
// Class c's cells are numbered from classOffset[c]: (cz * ny + cy) * nx + cx. SI units.
#ifndef ROCKDEM_GRID_GLSL
#define ROCKDEM_GRID_GLSL

#include "geometry.glsl"

const double SPAN_LIMIT = 1.0e12LF;

/// SizeClassGrids::wrapped: the centre moved into the box on periodic axes.
dvec3 wrapped(Params p, dvec3 x)
{
  dvec3 w = x;
  const dvec3 o = origin(p);
  const dvec3 L = boxSize(p);
  for (int a = 0; a < 3; ++a) {
    if ((p.periodicMask & (1u << a)) != 0u) {
      w[a] -= L[a] * floor((x[a] - o[a]) / L[a]);
      if (w[a] >= o[a] + L[a]) {
        w[a] -= L[a];
      }
      if (w[a] < o[a]) {
        w[a] = o[a];
      }
    }
  }
  return w;
}

/// SizeClassGrids::cellIndex of a wrapped centre in class c, plus the class's offset.
uint cellKey(Params p, uint c, dvec3 x)
{
  int64_t cell[3] = int64_t[3](0l, 0l, 0l);
  const int dimension = p.planar != 0u ? 2 : 3;
  const dvec3 o = origin(p);
  for (int a = 0; a < dimension; ++a) {
    const double t = stdMax(-1.0LF, stdMin(SPAN_LIMIT, (x[a] - o[a]) * p.classInverseEdge[3u * c + uint(a)]));
    const int64_t cells = int64_t(p.classCells[3u * c + uint(a)]);
    cell[a] = min(max(int64_t(floor(t)), 0l), cells - 1l);
  }
  const int64_t nx = int64_t(p.classCells[3u * c]);
  const int64_t ny = int64_t(p.classCells[3u * c + 1u]);
  return p.classOffset[c] + uint((cell[2] * ny + cell[1]) * nx + cell[0]);
}

/// SizeClassGrids::CellSpan: cells [first, first + count) along an axis, wrapping.
struct CellSpan {
  int64_t first;
  int64_t count;
  bool wrap;
};

/// a mod n in [0, n) (n > 0), as C++'s a %= n; if (a < 0) a += n.
int64_t positiveModulo(int64_t a, int64_t n)
{
  return a >= 0l ? a % n : (n - ((-a) % n)) % n;
}

/// SizeClassGrids::cellSpan.
CellSpan cellSpan(Params p, uint c, int axis, double coordinate, double reach)
{
  const int64_t n = int64_t(p.classCells[3u * c + uint(axis)]);
  if (p.planar != 0u && axis == 2) {
    return CellSpan(0l, 1l, false);
  }
  const double o = origin(p)[axis];
  const double inverseEdge = p.classInverseEdge[3u * c + uint(axis)];
  const double lo = stdMax(-SPAN_LIMIT, stdMin(SPAN_LIMIT, (coordinate - reach - o) * inverseEdge));
  const double hi = stdMax(-SPAN_LIMIT, stdMin(SPAN_LIMIT, (coordinate + reach - o) * inverseEdge));
  int64_t first = int64_t(floor(lo));
  int64_t last = int64_t(floor(hi));
  if ((p.periodicMask & (1u << axis)) != 0u) {
    const int64_t count = last - first + 1l;
    if (count >= n) {
      return CellSpan(0l, n, false);
    }
    return CellSpan(positiveModulo(first, n), count, true);
  }
  first = min(max(first, 0l), n - 1l);
  last = min(max(last, 0l), n - 1l);
  return CellSpan(first, last - first + 1l, false);
}

/// std::round(x): halfway cases away from zero.
double roundHalfAway(double x)
{
  const double t = trunc(x);
  return abs(x - t) >= 0.5LF ? t + sign(x) : t;
}

/// SizeClassGrids::separation: b - a with std::round on periodic axes; z = 0 in 2D.
dvec3 gridSeparation(Params p, dvec3 a, dvec3 b)
{
  dvec3 d = b - a;
  const dvec3 L = boxSize(p);
  for (int k = 0; k < 3; ++k) {
    if ((p.periodicMask & (1u << k)) != 0u) {
      d[k] -= L[k] * roundHalfAway(d[k] / L[k]);
    }
  }
  if (p.planar != 0u) {
    d.z = 0.0LF;
  }
  return d;
}

/// The neighbours of particle i (SizeClassGrids::neighboursWithin with reach = skin):
/// every j != i whose surface gap to i is below the skin. Counts them (all, and those
/// above i) and, when `write` is set, writes them unsorted to partners[base ...].
/// `sortedSlots` holds the particles sorted by cell key (cellStart/cellEnd).
uvec2 searchNeighbours(Params p, Uints sortedSlots, uint i, bool write, uint base)
{
  const dvec3 x = wrapped(p, load3(p.position, i));
  const double r = p.radius.v[i];
  uint all = 0u;
  uint above = 0u;
  for (uint c = 0u; c < 4u; ++c) {
    const double classReach = r + p.classMaxRadius[c] + p.skin;
    if (p.classCount[c] == 0u || !(classReach > 0.0LF)) {
      continue;
    }
    const CellSpan sx = cellSpan(p, c, 0, x.x, classReach);
    const CellSpan sy = cellSpan(p, c, 1, x.y, classReach);
    const CellSpan sz = cellSpan(p, c, 2, x.z, classReach);
    const int64_t nx = int64_t(p.classCells[3u * c]);
    const int64_t ny = int64_t(p.classCells[3u * c + 1u]);
    const int64_t nz = int64_t(p.classCells[3u * c + 2u]);
    for (int64_t iz = 0l; iz < sz.count; ++iz) {
      int64_t cz = sz.first + iz;
      if (sz.wrap && cz >= nz) {
        cz -= nz;
      }
      for (int64_t iy = 0l; iy < sy.count; ++iy) {
        int64_t cy = sy.first + iy;
        if (sy.wrap && cy >= ny) {
          cy -= ny;
        }
        for (int64_t ix = 0l; ix < sx.count; ++ix) {
          int64_t cx = sx.first + ix;
          if (sx.wrap && cx >= nx) {
            cx -= nx;
          }
          const uint key = p.classOffset[c] + uint((cz * ny + cy) * nx + cx);
          const uint end = p.cellEnd.v[key];
          for (uint s = p.cellStart.v[key]; s < end; ++s) {
            const uint j = sortedSlots.v[s];
            if (j == i) {
              continue;
            }
            dvec3 xj = wrapped(p, load3(p.position, j));
            if (p.planar != 0u) {
              xj.z = x.z;
            }
            const dvec3 d = gridSeparation(p, x, xj);
            if (norm3(d) - r - p.radius.v[j] < p.skin) {
              if (write) {
                p.partners.v[base + all] = j;
              }
              ++all;
              if (j > i) {
                ++above;
              }
            }
          }
        }
      }
    }
  }
  return uvec2(all, above);
}

#endif
