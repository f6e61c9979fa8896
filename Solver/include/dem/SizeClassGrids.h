// RockDEM engine: overlap and nearest-surface search over particles of very different sizes.
//
// One uniform cell grid per size class. Classes double in radius from the smallest radius
// in play, rmin: class k holds radii in [rmin 2^k, rmin 2^(k+1)) for k = 0, 1, 2, and
// class 3 holds everything from 8 rmin up. A class's cell edge is about twice the largest
// radius it is meant to hold, so a query against class k visits only the cells within
// (query radius + largest radius stored in class k): a fine class is never searched with
// the reach that a coarse particle needs, and the cost of a query grows only with the
// number of neighbours it can actually touch, not with the radius ratio.
//
// The number of cells per class is capped (a fine class in a huge box would otherwise
// need billions of cells): when capped, that class's cells are larger than ideal, which
// costs speed, never correctness.
//
// Periodic axes: cells wrap and separations use the minimum image; if a query's reach
// spans the whole periodic length, each cell is visited once (no double counting). The
// minimum image is the true separation as long as r_i + r_j <= L/2 (Pack keeps every
// radius <= L/4). 2D section: cells and separations in XY only; z is ignored.
//
// Stored particles are addressed by key: the order of insertion, 0, 1, 2, ... (insertAll
// inserts particle slot i as key i). SI units: metres.
#pragma once

#include "dem/Model.h"
#include "dem/SizeClass.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dem {

class SizeClassGrids {
public:
  static constexpr int kMaxClasses = MaxSizeClasses;
  /// Default cap on cells per class (2^22, about 4.2 million: 16 MiB of cell heads).
  static constexpr std::size_t kDefaultMaxCellsPerClass = std::size_t(1) << 22;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  /// Bytes per stored particle, for memory estimates, at the peak of a compact(): centre
  /// and radius (32), key, link and slot index (12), class (1), the sorted copy made while
  /// compacting (41), and cell heads and run starts (8 per cell, at most about one cell
  /// per particle when the pack is large), rounded up.
  static constexpr std::size_t kBytesPerParticle = 96;

  /// smallestRadius: the smallest radius in play (m, > 0), which anchors the classes;
  /// largestRadius: the largest radius expected (m). Larger radii are still accepted
  /// (class 3 takes them). maxCellsPerClass caps each class's cell count.
  SizeClassGrids(const Domain& domain, double smallestRadius, double largestRadius,
                 std::size_t maxCellsPerClass = kDefaultMaxCellsPerClass);

  void reserve(std::size_t n);
  /// Stores a particle and returns its key (the number stored before it).
  std::size_t insert(const Vec3& centre, double radius);
  /// Stores every particle, particle slot i as key i. The grids must be empty.
  void insertAll(const Particles& particles);
  /// Changes a stored particle's radius (it keeps its cell and class; the class's
  /// largest radius, and so its search reach, follows).
  void setRadius(std::size_t key, double radius);

  std::size_t size() const { return sphere_.size(); }
  /// The class a particle of this radius belongs to (0 .. kMaxClasses-1): sizeClassOf().
  int sizeClass(double radius) const;
  /// Number of particles stored in class k.
  std::size_t classCount(int k) const { return classes_[k].count; }
  /// Largest radius stored in class k (m); 0 while it is empty.
  double classMaxRadius(int k) const { return classes_[k].maxRadius; }
  /// Cells of class k along x, y, z.
  std::array<long, 3> cellCounts(int k) const { return classes_[k].cells; }
  /// Cell edge of class k along an axis (m).
  double cellEdge(int k, int axis) const { return classes_[k].edge[axis]; }

  /// True if a particle of radius r centred at x would overlap a stored one
  /// (centre distance < r + r_j; touching is not overlapping).
  bool overlapsAny(const Vec3& x, double r) const;

  /// The nearest stored surface to a particle (x, r): gap = |x_j - x| - r - r_j, minimum
  /// over stored keys j != ignore with gap < reach (negative when overlapping).
  struct Nearest {
    double gap;       ///< m; equals the reach when nothing is closer
    std::size_t key;  ///< npos when nothing lies within the reach
    double radius;    ///< m, radius of that particle (0 when none)
  };
  Nearest nearest(const Vec3& x, double r, double reach, std::size_t ignore = npos) const;

  /// Collects into `keys` (cleared first) every stored particle j != ignore whose surface
  /// gap to (x, r) is below `reach`, each exactly once, in no particular order.
  void neighboursWithin(const Vec3& x, double r, double reach, std::size_t ignore,
                        std::vector<std::size_t>& keys) const;

  /// Separation b - a (m) with the minimum image on periodic axes; z = 0 in a 2D section.
  Vec3 separation(const Vec3& a, const Vec3& b) const;

private:
  struct ClassGrid {
    double nominalMaxRadius = 0.0;     ///< m, the radius its cells are sized for
    double maxRadius = 0.0;            ///< m, largest radius stored in it
    std::array<long, 3> cells{ { 1, 1, 1 } };
    std::array<double, 3> edge{ { 0.0, 0.0, 0.0 } };      ///< m
    std::array<double, 3> inverseEdge{ { 0.0, 0.0, 0.0 } }; ///< 1/m
    /// Particles stored at the last compact(): cell c holds storage indices
    /// [runStart[c], runStart[c + 1]), and a row of cells is one contiguous run.
    std::vector<std::uint32_t> runStart;
    /// Particles inserted since: first storage index in each cell, linked through next_.
    std::vector<std::uint32_t> head;
    std::size_t count = 0;             ///< particles in this class
    std::size_t recent = 0;            ///< of which inserted since the last compact()
  };
  /// Cells [first, first + count) along one axis; indices wrap when `wrap` is set.
  struct CellSpan {
    long first;
    long count;
    bool wrap;
  };

  CellSpan cellSpan(const ClassGrid& g, int axis, double coordinate, double reach) const;
  long cellIndex(const ClassGrid& g, const Vec3& x) const;
  Vec3 wrapped(const Vec3& x) const;
  template <class Visit> bool visitCandidates(const ClassGrid& g, const Vec3& x, double reach,
                                              Visit&& visit) const;

  Vec3 origin_;
  Vec3 length_;
  std::array<bool, 3> periodic_{ { false, false, false } };
  bool planar_ = false;   ///< 2D section: XY only
  double smallestRadius_;
  std::array<ClassGrid, kMaxClasses> classes_;

  /// A stored particle: centre (m, wrapped into the box on periodic axes) and radius (m),
  /// kept together so that a candidate costs one memory access.
  struct Sphere {
    double x, y, z, r;
  };
  // Storage is indexed by a storage index, not by key: compact() re-sorts it by class and
  // cell, so that the particles of one cell lie next to each other in memory (a query then
  // reads a few contiguous runs instead of chasing pointers all over a large pack).
  std::vector<Sphere> sphere_;           ///< by storage index
  std::vector<std::uint32_t> key_;       ///< by storage index: the particle's key
  std::vector<std::uint32_t> next_;      ///< by storage index: next recent one in the same cell
  std::vector<std::uint8_t> class_;      ///< by storage index
  std::vector<std::uint32_t> storageOf_; ///< by key
  std::size_t compactedSize_ = 0;        ///< particles stored at the last compact()

  /// Re-sorts storage by class and cell (O(n)); insert() calls it each time the number
  /// stored has grown by a quarter, so the cost is amortised O(1) per particle.
  void compact();
};

} // namespace dem
