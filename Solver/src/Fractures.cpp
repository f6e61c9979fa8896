// RockDEM engine: fractures from broken bonds (see dem/Fractures.h).
#include "dem/Fractures.h"

#include "dem/Errors.h"
#include "dem/Random.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <unordered_map>

namespace dem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = 180.0 / kPi;
constexpr int kTrials = 256;            ///< plane candidates per extraction
constexpr double kPlaneShare = 0.25;    ///< a split plane holds at least this share of the remaining cracks
constexpr double kSplitCoverage = 0.75; ///< the split planes hold at least this share of the cluster
constexpr double kLocalScale = 1.0;     ///< local plane of a crack: its set's cracks within this x Cluster Distance
constexpr std::size_t kLocalMinimum = 6; ///< cracks (itself included) for a local plane
constexpr double kLocalGate = 0.5;      ///< Local Planarity a crack needs to seed or grow a plane
constexpr double kGrownShare = 0.05;    ///< a grown plane holds at least this share of its cluster
constexpr double kGrownFillContrast = 0.5; ///< a grown plane's Fill exceeds the damage fraction D by this share of 1 - D
constexpr double kGrowThickness = 0.5;  ///< a grown plane takes cracks within this x Cluster Distance of it
constexpr double kMaxThickness = 2.0;   ///< a disc's cracks lie within a slab this x Cluster Distance thick (sqrt(12 l1))
constexpr int kScanDirections3D = 1000; ///< band-scan normals over a hemisphere (2D: every degree in the plane)
constexpr int kScanOffsets = 4;         ///< band-scan offsets per slab thickness
constexpr int kScanBands = 8;           ///< bands taken from one cluster at most

struct Crack {
  Vec3 position;        ///< m
  double weight;        ///< m^2, bond cross-section area
  std::int64_t idA;
  std::int64_t idB;
  std::size_t bond;     ///< index into Model::bonds
};

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{ 0 }); }
  std::size_t find(std::size_t a)
  {
    while (parent[a] != a) {
      parent[a] = parent[parent[a]];
      a = parent[a];
    }
    return a;
  }
  void unite(std::size_t a, std::size_t b)
  {
    a = find(a);
    b = find(b);
    if (a != b) {
      // The smaller index is the root: the result does not depend on visiting order.
      if (b < a) {
        std::swap(a, b);
      }
      parent[b] = a;
    }
  }
};

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const
  {
    std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

/// Calls fn(i, j) for every pair i < j of `members` (local indices) whose crack positions
/// lie within `distance` (> 0), over a uniform grid of cell `distance`; the pairs of one i
/// come in ascending cell order (deterministic).
template <typename Fn>
void forEachPairWithin(const std::vector<Crack>& cracks, const std::vector<std::size_t>& members, double distance, Fn&& fn)
{
  const std::size_t n = members.size();
  if (n == 0 || !(distance > 0.0)) {
    return;
  }
  const double cell = distance;
  const double d2 = distance * distance;
  std::unordered_map<CellKey, std::vector<std::size_t>, CellHash> grid;
  grid.reserve(n);
  std::vector<CellKey> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = cracks[members[i]].position;
    keys[i] = CellKey{ static_cast<std::int64_t>(std::floor(p.x() / cell)),
      static_cast<std::int64_t>(std::floor(p.y() / cell)), static_cast<std::int64_t>(std::floor(p.z() / cell)) };
    grid[keys[i]].push_back(i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = cracks[members[i]].position;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(CellKey{ keys[i].x + dx, keys[i].y + dy, keys[i].z + dz });
          if (it == grid.end()) {
            continue;
          }
          for (std::size_t j : it->second) {
            if (j > i && (cracks[members[j]].position - p).squaredNorm() <= d2) {
              fn(i, j);
            }
          }
        }
      }
    }
  }
}

/// Connected parts of `members` (indices into cracks): joined when within `distance`,
/// or when sharing a particle and within `shareDistance`. Parts are sorted by their
/// smallest member; members of a part are ascending.
std::vector<std::vector<std::size_t>> connectedParts(const std::vector<Crack>& cracks,
  const std::vector<std::size_t>& members, double distance, double shareDistance)
{
  const std::size_t n = members.size();
  UnionFind uf(n);
  if (n == 0) {
    return {};
  }
  forEachPairWithin(cracks, members, distance, [&](std::size_t i, std::size_t j) { uf.unite(i, j); });
  // Bonds sharing a particle.
  std::unordered_map<std::int64_t, std::vector<std::size_t>> byParticle;
  byParticle.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    byParticle[cracks[members[i]].idA].push_back(i);
    byParticle[cracks[members[i]].idB].push_back(i);
  }
  const double s2 = shareDistance * shareDistance;
  for (const auto& entry : byParticle) {
    const auto& list = entry.second;
    for (std::size_t a = 0; a < list.size(); ++a) {
      for (std::size_t b = a + 1; b < list.size(); ++b) {
        if ((cracks[members[list[a]]].position - cracks[members[list[b]]].position).squaredNorm() <= s2) {
          uf.unite(list[a], list[b]);
        }
      }
    }
  }
  std::unordered_map<std::size_t, std::size_t> partOfRoot;
  std::vector<std::vector<std::size_t>> parts;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t root = uf.find(i);
    auto it = partOfRoot.find(root);
    if (it == partOfRoot.end()) {
      it = partOfRoot.emplace(root, parts.size()).first;
      parts.emplace_back();
    }
    parts[it->second].push_back(members[i]);
  }
  for (auto& part : parts) {
    std::sort(part.begin(), part.end());
  }
  std::sort(parts.begin(), parts.end(),
    [](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) { return a.front() < b.front(); });
  return parts;
}

struct PlaneFit {
  Vec3 center{ 0, 0, 0 };
  Vec3 normal{ 0, 0, 1 };
  Vec3 major{ 1, 0, 0 }; ///< in-plane axis of the largest variance
  std::array<double, 3> lambda{ { 0, 0, 0 } };
  double planarity = 0.0;
};

/// Area-weighted moments of crack positions about a reference point (for a running fit).
struct Moments {
  Vec3 origin{ 0, 0, 0 };
  double w = 0.0;
  Vec3 p{ 0, 0, 0 };
  Eigen::Matrix3d pp = Eigen::Matrix3d::Zero();
  void add(const Crack& c)
  {
    const Vec3 d = c.position - origin;
    w += c.weight;
    p += c.weight * d;
    pp.noalias() += c.weight * d * d.transpose();
  }
};

/// Principal axes of the moments (2D: in the XY plane).
PlaneFit fitMoments(const Moments& m, bool section2D)
{
  PlaneFit f;
  if (!(m.w > 0.0)) {
    return f;
  }
  const Vec3 mean = m.p / m.w;
  const Eigen::Matrix3d C = m.pp / m.w - mean * mean.transpose();
  f.center = m.origin + mean;
  if (section2D) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(C.topLeftCorner<2, 2>());
    const auto& ev = es.eigenvalues();
    f.lambda = { { std::max(ev(0), 0.0), std::max(ev(1), 0.0), 0.0 } };
    f.normal = Vec3(es.eigenvectors()(0, 0), es.eigenvectors()(1, 0), 0.0).normalized();
    f.major = Vec3(es.eigenvectors()(0, 1), es.eigenvectors()(1, 1), 0.0).normalized();
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
    const auto& ev = es.eigenvalues();
    f.lambda = { { std::max(ev(0), 0.0), std::max(ev(1), 0.0), std::max(ev(2), 0.0) } };
    f.normal = es.eigenvectors().col(0).normalized();
    f.major = es.eigenvectors().col(2).normalized();
  }
  f.planarity = f.lambda[1] > 0.0 ? std::max(0.0, 1.0 - f.lambda[0] / f.lambda[1]) : 0.0;
  return f;
}

/// Area-weighted principal axes of the crack positions (2D: in the XY plane).
PlaneFit fitPlane(const std::vector<Crack>& cracks, const std::vector<std::size_t>& members, bool section2D)
{
  Moments m;
  if (members.empty()) {
    return PlaneFit{};
  }
  m.origin = cracks[members.front()].position;
  for (std::size_t k : members) {
    m.add(cracks[k]);
  }
  return fitMoments(m, section2D);
}

FractureDisc makeDisc(FractureSet set, const PlaneFit& f, const std::vector<Crack>& cracks,
  const std::vector<std::size_t>& members, const Domain& domain, int sides)
{
  FractureDisc d;
  d.set = set;
  d.center = f.center;
  d.normal = f.normal;
  // Upward; a vertical plane's normal points to a dip direction in [0, 180) (dipAzimuth).
  if (d.normal.z() < 0.0 || (d.normal.z() == 0.0 && std::atan2(d.normal.x(), d.normal.y()) < 0.0)) {
    d.normal = -d.normal;
  }
  const auto da = dipAzimuth(d.normal);
  d.dip = da[0];
  d.azimuth = da[1];
  d.strike = f.major;
  d.eigenvalues = f.lambda;
  d.planarity = f.planarity;
  d.bonds.reserve(members.size());
  for (std::size_t m : members) {
    d.bonds.push_back(cracks[m].bond);
  }
  std::sort(d.bonds.begin(), d.bonds.end());
  if (domain.section2D) {
    const double length = std::sqrt(12.0 * f.lambda[1]);
    const double t = domain.slabThickness();
    d.radius = 0.5 * length;
    d.area = length * t;
    const Vec3 up(0, 0, 1);
    const Vec3 u = f.major;
    d.polygon = { d.center - 0.5 * length * u - 0.5 * t * up, d.center + 0.5 * length * u - 0.5 * t * up,
      d.center + 0.5 * length * u + 0.5 * t * up, d.center - 0.5 * length * u + 0.5 * t * up };
  } else {
    const double l2 = std::sqrt(12.0 * f.lambda[1]);
    const double l3 = std::sqrt(12.0 * f.lambda[2]);
    d.area = l2 * l3;
    d.radius = std::sqrt(d.area / kPi);
    const Vec3 u = f.major;
    const Vec3 v = d.normal.cross(u).normalized(); // u x v = normal: counter-clockwise seen from above
    d.polygon.reserve(static_cast<std::size_t>(sides));
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * kPi * k / sides;
      d.polygon.push_back(d.center + d.radius * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  return d;
}

/// Every bond as the segment between its particle centres (across a periodic seam: A to
/// A + the minimum-image branch), for the fill of a disc.
struct BondSegments {
  std::vector<Vec3> a, b, mid;
  std::vector<double> halfLength;
  std::vector<char> broken;
};

BondSegments bondSegments(const Model& model)
{
  BondSegments out;
  const Bonds& bonds = model.bonds;
  const Particles& p = model.particles;
  std::unordered_map<std::int64_t, std::size_t> slot;
  slot.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    slot[p.id[i]] = i;
  }
  const Domain& d = model.domain;
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const auto ia = slot.find(bonds.idA[k]);
    const auto ib = slot.find(bonds.idB[k]);
    if (ia == slot.end() || ib == slot.end()) {
      throw InputError("A bond joins particle id " +
        std::to_string(ia == slot.end() ? bonds.idA[k] : bonds.idB[k]) + ", which is not in the model.");
    }
    const Vec3& a = p.position[ia->second];
    const Vec3 branch = minimumImage(d, a, p.position[ib->second]);
    out.a.push_back(a);
    out.b.push_back(a + branch);
    out.mid.push_back(a + 0.5 * branch);
    out.halfLength.push_back(0.5 * branch.norm());
    out.broken.push_back(bonds.broken(k) ? 1 : 0);
  }
  return out;
}

/// The bonds crossing a disc (their segment crosses its plane inside the disc; in 2D
/// inside the trace) and how many of them are broken.
struct Footprint {
  std::size_t crossing = 0;
  std::size_t broken = 0;
  /// Fill: the broken fraction of the crossing bonds; 0 when none crosses.
  double fill() const { return crossing ? static_cast<double>(broken) / static_cast<double>(crossing) : 0.0; }
  /// How many binomial standard deviations the broken count lies above what a damage
  /// fraction D (0 < D < 1) predicts for as many bonds: (k - n D) / sqrt(n D (1 - D)).
  double significanceOver(double D) const
  {
    const double n = static_cast<double>(crossing);
    return n > 0.0 ? (static_cast<double>(broken) - n * D) / std::sqrt(n * D * (1.0 - D)) : 0.0;
  }
};

Footprint discFootprint(const FractureDisc& disc, const BondSegments& seg, bool section2D)
{
  Footprint f;
  const Vec3& n = disc.normal;
  const Vec3& c = disc.center;
  const double R = disc.radius;
  for (std::size_t k = 0; k < seg.a.size(); ++k) {
    if ((seg.mid[k] - c).norm() > R + seg.halfLength[k] + (section2D ? R : 0.0)) {
      continue;
    }
    const double sa = n.dot(seg.a[k] - c);
    const double sb = n.dot(seg.b[k] - c);
    if ((sa > 0.0 && sb > 0.0) || (sa < 0.0 && sb < 0.0) || (sa == 0.0 && sb == 0.0)) {
      continue;
    }
    const Vec3 x = seg.a[k] + sa / (sa - sb) * (seg.b[k] - seg.a[k]);
    const bool inside = section2D ? std::abs(disc.strike.dot(x - c)) <= R : (x - c).norm() <= R;
    if (inside) {
      ++f.crossing;
      f.broken += seg.broken[k] ? 1 : 0;
    }
  }
  return f;
}

/// Plane of three (2D: two) cracks; false when degenerate.
bool planeThrough(const std::vector<Vec3>& pts, bool section2D, Vec3& normal)
{
  if (section2D) {
    const Vec3 t = pts[1] - pts[0];
    normal = Vec3(-t.y(), t.x(), 0.0);
  } else {
    normal = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
  }
  const double len = normal.norm();
  if (!(len > 1e-300)) {
    return false;
  }
  normal /= len;
  return true;
}

std::vector<std::size_t> inliers(const std::vector<Crack>& cracks, const std::vector<std::size_t>& from,
  const Vec3& point, const Vec3& normal, double halfThickness)
{
  std::vector<std::size_t> out;
  for (std::size_t m : from) {
    if (std::abs(normal.dot(cracks[m].position - point)) <= halfThickness) {
      out.push_back(m);
    }
  }
  return out;
}

/// Extracts planes from a non-planar cluster (see extractFractures); the planar parts,
/// or nothing when the split does not explain the cluster.
template <typename Accept>
std::vector<std::vector<std::size_t>> splitIntoPlanes(const std::vector<Crack>& cracks,
  const std::vector<std::size_t>& cluster, const FractureParameters& params, double distance,
  double shareDistance, bool section2D, const Accept& accept)
{
  const double h = 0.5 * distance;
  const std::size_t minimum = static_cast<std::size_t>(params.minimumCracks);
  Random rng(0x5EEDF7AC7u ^ static_cast<std::uint64_t>(cluster.front()));
  std::vector<std::size_t> remaining = cluster;
  std::vector<std::vector<std::size_t>> result;
  std::vector<char> assigned(cracks.size(), 0);
  std::size_t assignedCount = 0;
  const int picks = section2D ? 2 : 3;
  while (remaining.size() >= minimum) {
    std::size_t bestCount = 0;
    Vec3 bestPoint = Vec3::Zero();
    Vec3 bestNormal = Vec3::UnitZ();
    std::vector<Vec3> pts(3);
    for (int t = 0; t < kTrials; ++t) {
      for (int k = 0; k < picks; ++k) {
        pts[k] = cracks[remaining[static_cast<std::size_t>(rng.uniform() * remaining.size()) % remaining.size()]].position;
      }
      Vec3 normal;
      if (!planeThrough(pts, section2D, normal)) {
        continue;
      }
      std::size_t count = 0;
      for (std::size_t m : remaining) {
        count += std::abs(normal.dot(cracks[m].position - pts[0])) <= h ? 1 : 0;
      }
      if (count > bestCount) {
        bestCount = count;
        bestPoint = pts[0];
        bestNormal = normal;
      }
    }
    const std::size_t needed = std::max(minimum, static_cast<std::size_t>(std::ceil(kPlaneShare * cluster.size())));
    if (bestCount < needed) {
      break;
    }
    // Refine: fit the plane to its cracks, twice; a crack near the intersection of two
    // fractures may belong to both (inliers are taken from the whole cluster).
    std::vector<std::size_t> in = inliers(cracks, remaining, bestPoint, bestNormal, h);
    for (int refine = 0; refine < 2 && in.size() >= 3; ++refine) {
      const PlaneFit f = fitPlane(cracks, in, section2D);
      bestPoint = f.center;
      bestNormal = f.normal;
      in = inliers(cracks, remaining, bestPoint, bestNormal, h);
    }
    if (in.size() < needed) {
      break;
    }
    const std::vector<std::size_t> plane = inliers(cracks, cluster, bestPoint, bestNormal, h);
    for (auto& part : connectedParts(cracks, plane, distance, shareDistance)) {
      if (part.size() >= minimum && accept(part)) {
        for (std::size_t m : part) {
          if (!assigned[m]) {
            assigned[m] = 1;
            ++assignedCount;
          }
        }
        result.push_back(std::move(part));
      }
    }
    std::vector<std::size_t> rest;
    std::set_difference(remaining.begin(), remaining.end(), in.begin(), in.end(), std::back_inserter(rest));
    remaining.swap(rest);
  }
  if (static_cast<double>(assignedCount) < kSplitCoverage * static_cast<double>(cluster.size())) {
    return {};
  }
  return result;
}

/// Planes grown through a non-planar cluster by orientation (see extractFractures): the
/// accepted planes (each ascending), or nothing.
template <typename Accept>
std::vector<std::vector<std::size_t>> growPlanes(const std::vector<Crack>& cracks,
  const std::vector<std::size_t>& cluster, const FractureParameters& params, double distance, bool section2D,
  const Accept& accept)
{
  const std::size_t n = cluster.size();
  const double localRadius = kLocalScale * distance;
  const double halfThickness = kGrowThickness * distance;
  const double localThickness = 0.5 * halfThickness;
  const double gate = kLocalGate;
  const double cosTolerance = std::cos(params.orientationTolerance / kDegrees);
  const std::size_t minimum = static_cast<std::size_t>(params.minimumCracks);
  // Neighbours within the local radius (local indices, ascending).
  std::vector<std::vector<std::size_t>> near(n);
  forEachPairWithin(cracks, cluster, localRadius, [&](std::size_t i, std::size_t j) {
    near[i].push_back(j);
    near[j].push_back(i);
  });
  // The local plane of every crack.
  std::vector<Vec3> localNormal(n, Vec3::UnitZ());
  std::vector<double> localPlanarity(n, 0.0);
  std::vector<std::size_t> part;
  for (std::size_t i = 0; i < n; ++i) {
    std::sort(near[i].begin(), near[i].end());
    if (near[i].size() + 1 < kLocalMinimum) {
      continue;
    }
    part.assign(1, cluster[i]);
    for (std::size_t j : near[i]) {
      part.push_back(cluster[j]);
    }
    // Robust: refit twice to the neighbours near the plane (scattered cracks tilt a plain
    // fit); the crack's Local Planarity is that of the refit, 0 when fewer than half of
    // its neighbours lie near its plane.
    PlaneFit f = fitPlane(cracks, part, section2D);
    std::vector<std::size_t> in = part;
    for (int refine = 0; refine < 2; ++refine) {
      in = inliers(cracks, part, f.center, f.normal, localThickness);
      if (in.size() < kLocalMinimum) {
        break;
      }
      f = fitPlane(cracks, in, section2D);
    }
    localNormal[i] = f.normal;
    localPlanarity[i] = (in.size() >= kLocalMinimum && 2 * in.size() >= part.size()) ? f.planarity : 0.0;
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return localPlanarity[a] > localPlanarity[b]; });
  std::vector<char> assigned(n, 0);
  std::vector<std::vector<std::size_t>> grown;
  const double d2 = distance * distance;
  for (std::size_t seed : order) {
    if (localPlanarity[seed] < gate) {
      break;
    }
    if (assigned[seed]) {
      continue;
    }
    Moments moments;
    moments.origin = cracks[cluster[seed]].position;
    moments.add(cracks[cluster[seed]]);
    Vec3 normal = localNormal[seed];
    Vec3 centre = cracks[cluster[seed]].position;
    std::vector<std::size_t> region{ seed };
    assigned[seed] = 1;
    for (std::size_t q = 0; q < region.size(); ++q) {
      const std::size_t i = region[q];
      if (localPlanarity[i] < gate) {
        continue; // joins the plane, but does not grow it
      }
      const Vec3& pi = cracks[cluster[i]].position;
      for (std::size_t j : near[i]) {
        const Vec3& pj = cracks[cluster[j]].position;
        if (assigned[j] || (pj - pi).squaredNorm() > d2 || std::abs(localNormal[j].dot(normal)) < cosTolerance ||
          std::abs(normal.dot(pj - centre)) > halfThickness) {
          continue;
        }
        assigned[j] = 1;
        region.push_back(j);
        moments.add(cracks[cluster[j]]);
        const PlaneFit f = fitMoments(moments, section2D);
        centre = f.center;
        if (region.size() >= kLocalMinimum && f.planarity >= gate) {
          normal = f.normal;
        }
      }
    }
    if (region.size() < minimum) {
      continue;
    }
    std::vector<std::size_t> plane;
    plane.reserve(region.size());
    for (std::size_t i : region) {
      plane.push_back(cluster[i]);
    }
    std::sort(plane.begin(), plane.end());
    grown.push_back(std::move(plane));
  }
  // Coplanar planes merge (the two halves of a fracture cut by another one, whose crossing
  // line has no planar neighbourhood): normals within Orientation Tolerance and each
  // centre within the thickness of the other's plane. Larger planes first.
  std::stable_sort(grown.begin(), grown.end(),
    [](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) { return a.size() > b.size(); });
  std::vector<std::vector<std::size_t>> merged;
  std::vector<PlaneFit> fits;
  for (auto& plane : grown) {
    const PlaneFit f = fitPlane(cracks, plane, section2D);
    bool joined = false;
    for (std::size_t k = 0; k < merged.size() && !joined; ++k) {
      const PlaneFit& g = fits[k];
      if (std::abs(f.normal.dot(g.normal)) >= cosTolerance && std::abs(g.normal.dot(f.center - g.center)) <= halfThickness &&
        std::abs(f.normal.dot(g.center - f.center)) <= halfThickness) {
        std::vector<std::size_t> both;
        std::merge(merged[k].begin(), merged[k].end(), plane.begin(), plane.end(), std::back_inserter(both));
        merged[k].swap(both);
        fits[k] = fitPlane(cracks, merged[k], section2D);
        joined = true;
      }
    }
    if (!joined) {
      merged.push_back(std::move(plane));
      fits.push_back(f);
    }
  }
  const std::size_t needed = std::max(minimum, static_cast<std::size_t>(std::ceil(kGrownShare * static_cast<double>(n))));
  std::vector<std::vector<std::size_t>> result;
  for (auto& plane : merged) {
    if (plane.size() >= needed && accept(plane)) {
      result.push_back(std::move(plane));
    }
  }
  return result;
}

/// Unit normals of the band scan: every degree in the XY plane (2D), or kScanDirections3D
/// directions spread evenly over the upper hemisphere (a Fibonacci lattice).
std::vector<Vec3> scanDirections(bool section2D)
{
  std::vector<Vec3> out;
  if (section2D) {
    for (int k = 0; k < 180; ++k) {
      const double a = k * kPi / 180.0;
      out.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    return out;
  }
  const double golden = kPi * (1.0 + std::sqrt(5.0));
  for (int k = 0; k < kScanDirections3D; ++k) {
    const double z = (k + 0.5) / kScanDirections3D;
    const double r = std::sqrt(1.0 - z * z);
    out.emplace_back(r * std::cos(golden * (k + 0.5)), r * std::sin(golden * (k + 0.5)), z);
  }
  return out;
}

/// Bands scanned through the unassigned cracks `rest` of a non-planar cluster (see
/// extractFractures): slabs `thickness` thick over every scan direction and offset; the
/// slab whose cracks most exceed the count expected from the damage fraction of the
/// cluster's box, in standard deviations, is a candidate when that reaches `significance`;
/// its connected parts that `accept` takes are returned. Repeated on the cracks left, at
/// most kScanBands times, until a candidate yields nothing.
template <typename Accept, typename Parts>
std::vector<std::vector<std::size_t>> scanBands(const std::vector<Crack>& cracks, std::vector<std::size_t> rest,
  const std::vector<Vec3>& bondMid, double thickness, double significance, std::size_t minimum, bool section2D,
  const Accept& accept, const Parts& parts)
{
  std::vector<std::vector<std::size_t>> result;
  if (rest.size() < minimum || !(thickness > 0.0)) {
    return result;
  }
  // Cracks are placed at their bond's midpoint now, as the intact bonds are.
  const auto at = [&](std::size_t k) -> const Vec3& { return bondMid[cracks[k].bond]; };
  Vec3 lo = at(rest.front());
  Vec3 hi = lo;
  for (std::size_t k : rest) {
    lo = lo.cwiseMin(at(k));
    hi = hi.cwiseMax(at(k));
  }
  lo -= Vec3::Constant(thickness);
  hi += Vec3::Constant(thickness);
  std::vector<Vec3> box; // the bonds of the cluster's box
  for (const Vec3& m : bondMid) {
    if ((m.array() >= lo.array()).all() && (m.array() <= hi.array()).all()) {
      box.push_back(m);
    }
  }
  const std::vector<Vec3> normals = scanDirections(section2D);
  const double step = thickness / kScanOffsets;
  for (int band = 0; band < kScanBands && rest.size() >= minimum && !box.empty(); ++band) {
    const double p = static_cast<double>(rest.size()) / static_cast<double>(box.size());
    if (!(p > 0.0 && p < 1.0)) {
      break;
    }
    double bestZ = -1.0;
    Vec3 bestNormal(0, 0, 1);
    double bestLow = 0.0;
    std::vector<double> bonds, broken;
    for (const Vec3& n : normals) {
      double smin = n.dot(box.front());
      double smax = smin;
      for (const Vec3& m : box) {
        smin = std::min(smin, n.dot(m));
        smax = std::max(smax, n.dot(m));
      }
      smin -= thickness;
      const std::size_t bins = static_cast<std::size_t>((smax - smin) / step) + 2;
      bonds.assign(bins, 0.0);
      broken.assign(bins, 0.0);
      for (const Vec3& m : box) {
        bonds[static_cast<std::size_t>((n.dot(m) - smin) / step)] += 1.0;
      }
      for (std::size_t k : rest) {
        const double s = (n.dot(at(k)) - smin) / step;
        if (s >= 0.0 && s < static_cast<double>(bins)) {
          broken[static_cast<std::size_t>(s)] += 1.0;
        }
      }
      for (std::size_t i = 0; i + kScanOffsets <= bins; ++i) {
        double nb = 0.0;
        double kb = 0.0;
        for (int j = 0; j < kScanOffsets; ++j) {
          nb += bonds[i + static_cast<std::size_t>(j)];
          kb += broken[i + static_cast<std::size_t>(j)];
        }
        if (kb < static_cast<double>(minimum) || nb <= 0.0) {
          continue;
        }
        const double z = (kb - nb * p) / std::sqrt(nb * p * (1.0 - p));
        if (z > bestZ) {
          bestZ = z;
          bestNormal = n;
          bestLow = smin + static_cast<double>(i) * step;
        }
      }
    }
    if (bestZ < significance) {
      break;
    }
    std::vector<std::size_t> slab, left;
    for (std::size_t k : rest) {
      const double s = bestNormal.dot(at(k)) - bestLow;
      (s >= 0.0 && s < thickness ? slab : left).push_back(k);
    }
    for (const auto& part : parts(slab)) {
      if (part.size() >= minimum && accept(part)) {
        result.push_back(part);
      }
    }
    // The candidate's slab is set aside, cracks and bonds, whether or not it made a disc:
    // the next candidate is tested against the damage fraction of the rest.
    rest.swap(left);
    box.erase(std::remove_if(box.begin(), box.end(),
                [&](const Vec3& m) {
                  const double s = bestNormal.dot(m) - bestLow;
                  return s >= 0.0 && s < thickness;
                }),
      box.end());
  }
  return result;
}

std::string plural(std::size_t n, const char* one, const char* many)
{
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace

void validate(const FractureParameters& p)
{
  if (p.minimumCracks < 3) {
    throw InputError("Minimum Cracks = " + std::to_string(p.minimumCracks) +
      " is out of range: valid range is [3, inf) (a plane needs at least three cracks).");
  }
  requireInRange("Minimum Planarity", p.minimumPlanarity, 0.0, 1.0);
  requireNonNegative("Cluster Distance", p.clusterDistance, "m");
  requireInRange("Minimum Fill", p.minimumFill, 0.0, 1.0);
  if (!(p.orientationTolerance >= 0.0 && p.orientationTolerance < 90.0)) {
    throw InputError("Orientation Tolerance = " + formatValue(p.orientationTolerance) +
      " degrees is out of range: valid range is [0, 90) degrees (0 = off).");
  }
  requireNonNegative("Band Significance", p.bandSignificance, "standard deviations");
  if (p.discSides < 3) {
    throw InputError("Disc Sides = " + std::to_string(p.discSides) +
      " is out of range: valid range is [3, inf) (a polygon needs at least three vertices).");
  }
}

const char* fractureSetName(FractureSet set)
{
  switch (set) {
    case FractureSet::Tensile:
      return "Tensile";
    case FractureSet::Shear:
      return "Shear";
    case FractureSet::Inherited:
      return "Inherited";
  }
  return "Unknown";
}

FractureCounts& FractureCounts::operator+=(const FractureCounts& o)
{
  brokenBonds += o.brokenBonds;
  clusters += o.clusters;
  discs += o.discs;
  rejectedTooSmall += o.rejectedTooSmall;
  rejectedNonPlanar += o.rejectedNonPlanar;
  rejectedSparse += o.rejectedSparse;
  splitClusters += o.splitClusters;
  grownClusters += o.grownClusters;
  scannedClusters += o.scannedClusters;
  cracksInDiscs += o.cracksInDiscs;
  return *this;
}

std::string FractureReport::summary() const
{
  std::string s = plural(total.brokenBonds, "broken bond", "broken bonds") + " (" +
    std::to_string(sets[0].brokenBonds) + " tensile, " + std::to_string(sets[1].brokenBonds) + " shear, " +
    std::to_string(sets[2].brokenBonds) + " inherited), " + plural(total.clusters, "cluster", "clusters") +
    " (Cluster Distance " + formatValue(clusterDistance) + " m): " + plural(total.discs, "disc", "discs") +
    " emitted, " + std::to_string(total.rejectedTooSmall) + " rejected as too small (fewer than " +
    std::to_string(minimumCracks) + " cracks), " + std::to_string(total.rejectedNonPlanar) +
    " rejected as non-planar (Planarity below " + formatValue(minimumPlanarity) + "), " +
    std::to_string(total.rejectedSparse) + " rejected as sparse (Fill below " + formatValue(minimumFill) + ").";
  for (int k = 0; k < FractureSetCount; ++k) {
    const FractureCounts& c = sets[static_cast<std::size_t>(k)];
    if (c.brokenBonds == 0) {
      continue;
    }
    s += std::string("\n  ") + fractureSetName(static_cast<FractureSet>(k)) + " set: " +
      plural(c.brokenBonds, "broken bond", "broken bonds") + ", " + plural(c.clusters, "cluster", "clusters") +
      ", " + plural(c.discs, "disc", "discs") + " emitted (" + std::to_string(c.cracksInDiscs) +
      " cracks in discs), " + std::to_string(c.rejectedTooSmall) + " rejected as too small, " +
      std::to_string(c.rejectedNonPlanar) + " rejected as non-planar, " + std::to_string(c.rejectedSparse) +
      " rejected as sparse";
    if (c.splitClusters) {
      s += ", " + std::to_string(c.splitClusters) + " non-planar resolved into planar parts";
      if (c.grownClusters) {
        s += " (" + std::to_string(c.grownClusters) + " by planes grown within Orientation Tolerance " +
          formatValue(orientationTolerance) + " deg)";
      }
      if (c.scannedClusters) {
        s += " (" + std::to_string(c.scannedClusters) + " with bands scanned at Band Significance " +
          formatValue(bandSignificance) + ")";
      }
    }
    s += ".";
  }
  if (total.discs == 0) {
    if (total.brokenBonds == 0) {
      s += "\nNothing emitted: the model has no broken bonds.";
    } else {
      s += "\nNothing emitted: every cluster was rejected (" + std::to_string(total.rejectedTooSmall) +
        " too small, " + std::to_string(total.rejectedNonPlanar) + " non-planar, " +
        std::to_string(total.rejectedSparse) +
        " sparse); lower Minimum Cracks, Minimum Planarity or Minimum Fill to accept them.";
    }
  }
  return s;
}

double meanParticleDiameter(const Model& model)
{
  const auto& r = model.particles.radius;
  if (r.empty()) {
    return 0.0;
  }
  return 2.0 * std::accumulate(r.begin(), r.end(), 0.0) / static_cast<double>(r.size());
}

std::array<double, 2> dipAzimuth(const Vec3& normal)
{
  Vec3 n = normal.normalized();
  if (n.z() < 0.0) {
    n = -n;
  }
  const double dip = std::acos(std::min(1.0, std::max(-1.0, n.z()))) * kDegrees;
  double az = std::atan2(n.x(), n.y()) * kDegrees;
  if (n.z() == 0.0 && az < 0.0) {
    az += 180.0; // vertical plane: either sense is "upward"; take the dip direction in [0, 180)
  }
  if (az < 0.0) {
    az += 360.0;
  }
  if (az >= 360.0) {
    az -= 360.0;
  }
  return { { dip, az } };
}

Vec3 normalFromDipAzimuth(double dipDegrees, double azimuthDegrees)
{
  const double d = dipDegrees / kDegrees;
  const double a = azimuthDegrees / kDegrees;
  return Vec3(std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d));
}

FractureNetwork extractFractures(const Model& model, const FractureParameters& params)
{
  validate(params);
  FractureNetwork out;
  FractureReport& report = out.report;
  report.minimumCracks = params.minimumCracks;
  report.minimumPlanarity = params.minimumPlanarity;
  report.minimumFill = params.minimumFill;
  report.orientationTolerance = params.orientationTolerance;
  report.bandSignificance = params.bandSignificance;
  const double distance = params.clusterDistance > 0.0 ? params.clusterDistance : DefaultClusterDiameters * meanParticleDiameter(model);
  report.clusterDistance = distance;
  const auto& r = model.particles.radius;
  const double shareDistance = 4.0 * (r.empty() ? 0.0 : *std::max_element(r.begin(), r.end()));
  const bool section2D = model.domain.section2D;
  const Bonds& b = model.bonds;

  std::vector<Crack> cracks;
  std::array<std::vector<std::size_t>, FractureSetCount> members;
  for (std::size_t k = 0; k < b.size(); ++k) {
    int set = -1;
    switch (static_cast<BondFailure>(b.failure[k])) {
      case BondFailure::Intact:
        break;
      case BondFailure::Tension:
        set = 0;
        break;
      case BondFailure::Shear:
        set = 1;
        break;
      case BondFailure::Inherited:
        set = 2;
        break;
    }
    if (set < 0) {
      continue;
    }
    const double area = bondSection(b.radius[k], section2D, model.domain.slabThickness()).area;
    members[static_cast<std::size_t>(set)].push_back(cracks.size());
    cracks.push_back(Crack{ b.failurePosition[k], area > 0.0 ? area : 1.0, b.idA[k], b.idB[k], k });
  }

  const BondSegments segments = bondSegments(model);
  std::vector<std::size_t> crackOfBond(b.size(), 0); // the crack of a broken bond
  for (std::size_t k = 0; k < cracks.size(); ++k) {
    crackOfBond[cracks[k].bond] = k;
  }
  const double damage = b.size() ? static_cast<double>(cracks.size()) / static_cast<double>(b.size()) : 0.0;
  const double grownFill = damage + kGrownFillContrast * (1.0 - damage);
  const std::size_t minimum = static_cast<std::size_t>(params.minimumCracks);

  for (int s = 0; s < FractureSetCount; ++s) {
    const FractureSet set = static_cast<FractureSet>(s);
    FractureCounts& c = report.sets[static_cast<std::size_t>(s)];
    c.brokenBonds = members[static_cast<std::size_t>(s)].size();
    std::vector<FractureDisc> discs;
    // A disc for a part that is planar and filled enough; false otherwise.
    enum class Verdict { Emitted, NonPlanar, Sparse };
    auto tryDisc = [&](const std::vector<std::size_t>& part, std::vector<FractureDisc>* into,
                       Footprint* footprint = nullptr) {
      const PlaneFit f = fitPlane(cracks, part, section2D);
      // Planar: flat for its size (Planarity) and thin in absolute terms (the thickness of
      // the uniform slab with its spread, sqrt(12 l1), within kMaxThickness Cluster
      // Distances); the damage cloud of a whole 2D section of aspect 2 is "flat" for its size.
      if (f.planarity < params.minimumPlanarity || std::sqrt(12.0 * f.lambda[0]) > kMaxThickness * distance) {
        return Verdict::NonPlanar;
      }
      FractureDisc d = makeDisc(set, f, cracks, part, model.domain, params.discSides);
      const Footprint fp = discFootprint(d, segments, section2D);
      d.fill = fp.fill();
      if (footprint) {
        *footprint = fp;
      }
      if (d.fill < params.minimumFill) {
        return Verdict::Sparse;
      }
      if (into) {
        into->push_back(std::move(d));
      }
      return Verdict::Emitted;
    };
    // A plane grown by orientation is a disc only if it is clearly more broken than the
    // model as a whole: Fill >= D + (1 - D) / 2, D the broken fraction of all bonds (in
    // diffuse damage a chance alignment has a Fill near D).
    auto grownDisc = [&](const std::vector<std::size_t>& part, std::vector<FractureDisc>* into) {
      std::vector<FractureDisc> one;
      if (tryDisc(part, &one) != Verdict::Emitted || one.front().fill < grownFill) {
        return false;
      }
      if (into) {
        into->push_back(std::move(one.front()));
      }
      return true;
    };
    // A part of a band the scan found (scanBands) is a disc if its own footprint is as
    // clearly more broken than the model as a whole as the scan asked of the band's slab:
    // the broken bonds crossing it exceed D x the crossing bonds by Band Significance
    // binomial standard deviations (a chance alignment in diffuse damage has about D; the
    // scan's significance already stands for "not chance", so the band is not held to the
    // grown planes' contrast D + (1 - D) / 2, which a 2-diameter slab of a band a few
    // slabs thick does not reach inside dense damage).
    auto bandDisc = [&](const std::vector<std::size_t>& part, std::vector<FractureDisc>* into) {
      std::vector<FractureDisc> one;
      Footprint fp;
      if (tryDisc(part, &one, &fp) != Verdict::Emitted) {
        return false;
      }
      const bool contrast = one.front().fill >= grownFill;
      const bool significant = damage > 0.0 && damage < 1.0 && fp.significanceOver(damage) >= params.bandSignificance;
      if (!contrast && !significant) {
        return false;
      }
      if (into) {
        into->push_back(std::move(one.front()));
      }
      return true;
    };
    // Non-planar: perhaps intersecting fractures (splitIntoPlanes). Returns the discs found.
    auto resolve = [&](const std::vector<std::size_t>& cluster) {
      std::vector<FractureDisc> found;
      const auto parts = splitIntoPlanes(cracks, cluster, params, distance, shareDistance, section2D,
        [&](const std::vector<std::size_t>& part) { return tryDisc(part, nullptr) == Verdict::Emitted; });
      for (const auto& part : parts) {
        tryDisc(part, &found);
      }
      return found;
    };
    const auto clusters = connectedParts(cracks, members[static_cast<std::size_t>(s)], distance, shareDistance);
    c.clusters = clusters.size();
    for (const auto& cluster : clusters) {
      if (cluster.size() < minimum) {
        ++c.rejectedTooSmall;
        continue;
      }
      const Verdict v = tryDisc(cluster, &discs);
      if (v == Verdict::Sparse) {
        ++c.rejectedSparse;
        continue;
      }
      if (v == Verdict::Emitted) {
        continue;
      }
      auto found = resolve(cluster);
      if (found.empty() && params.orientationTolerance > 0.0) {
        for (const auto& part : growPlanes(cracks, cluster, params, distance, section2D,
               [&](const std::vector<std::size_t>& p) { return grownDisc(p, nullptr); })) {
          grownDisc(part, &found);
        }
        c.grownClusters += found.empty() ? 0 : 1;
      }
      if (params.bandSignificance > 0.0) {
        std::vector<char> taken(cracks.size(), 0);
        for (const auto& d : found) {
          for (std::size_t bond : d.bonds) {
            taken[crackOfBond[bond]] = 1;
          }
        }
        std::vector<std::size_t> rest;
        for (std::size_t k : cluster) {
          if (!taken[k]) {
            rest.push_back(k);
          }
        }
        const auto bands = scanBands(cracks, rest, segments.mid, distance, params.bandSignificance, minimum,
          section2D, [&](const std::vector<std::size_t>& part) { return bandDisc(part, &found); }, // the disc, once
          [&](const std::vector<std::size_t>& slab) { return connectedParts(cracks, slab, distance, shareDistance); });
        c.scannedClusters += bands.empty() ? 0 : 1;
      }
      if (found.empty()) {
        ++c.rejectedNonPlanar;
        continue;
      }
      ++c.splitClusters;
      for (auto& d : found) {
        discs.push_back(std::move(d));
      }
    }
    // Cracks in discs (a crack near the intersection of two discs counts once).
    std::vector<char> bondInDisc(b.size(), 0);
    for (const auto& d : discs) {
      for (std::size_t k : d.bonds) {
        if (!bondInDisc[k]) {
          bondInDisc[k] = 1;
          ++c.cracksInDiscs;
        }
      }
    }
    c.discs = discs.size();
    std::stable_sort(discs.begin(), discs.end(),
      [](const FractureDisc& a, const FractureDisc& d) { return a.crackCount() > d.crackCount(); });
    for (auto& d : discs) {
      out.discs.push_back(std::move(d));
    }
    report.total += c;
  }
  return out;
}

} // namespace dem
