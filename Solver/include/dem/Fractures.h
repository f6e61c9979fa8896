// RockDEM engine: fractures from broken bonds, exported as a discrete fracture network
// (reference guide "Exporting fractures to a DFN"; PHYSICS.md section 5;
// Documentation/Fractures.md).
//
// The broken bonds of each set (tensile, shear, inherited) are grouped into spatially
// connected clusters; a plane is fitted through each cluster's crack positions (the
// bond's contact point when it broke, Bonds::failurePosition), weighted by the bond's
// cross-section area; a cluster that is planar enough becomes a fracture disc.
//
// Conventions (x = East, y = North, z = Up):
// - weighted covariance C = sum w (p - c)(p - c)^T / sum w, eigenvalues l1 <= l2 <= l3;
//   the normal is l1's eigenvector, flipped upward (nz >= 0);
// - Planarity = 1 - l1 / l2 (1 = all cracks in one plane; 0 = no preferred plane);
// - in-plane size: the sides of the uniform rectangle with the same variances,
//   L2 = sqrt(12 l2) and L3 = sqrt(12 l3); disc Area = L2 L3 and Radius = sqrt(Area / pi)
//   (the disc of the same area);
// - Dip = arccos(nz) in [0, 90] degrees; Azimuth (dip direction, clockwise from North)
//   = atan2(nx, ny) mod 360 degrees.
// In a 2D section (XY) the fit is the 2x2 covariance in XY: the fracture is a vertical
// plane (Dip 90) whose trace has length L = sqrt(12 l2); its polygon is the L x slab
// rectangle, Radius = L / 2 and Area = L x slab.
//
// SI units: m, m^2, degrees where named.
#pragma once

#include "dem/Model.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

/// Parameters of the export (GUI labels in the comments).
struct FractureParameters {
  int minimumCracks = 10;          ///< Minimum Cracks: a cluster with fewer cracks is rejected, >= 3
  double minimumPlanarity = 0.8;   ///< Minimum Planarity: 1 - l1/l2 at least this, [0, 1]
  double clusterDistance = 0.0;    ///< Cluster Distance, m, >= 0; 0 = two mean particle diameters
  double minimumFill = 0.0;        ///< Minimum Fill: broken fraction of the bonds crossing the disc, [0, 1]; 0 = off
  /// Orientation Tolerance, degrees, [0, 90): a crack joins a plane grown through a
  /// non-planar cluster when its local plane is within this angle of the plane's running
  /// normal; 0 = off (distance clustering and the plane split only).
  double orientationTolerance = 30.0;
  /// Band Significance, standard deviations, [0, inf): the damage a non-planar cluster
  /// leaves after the split and the growth is scanned for flat bands (slabs one Cluster
  /// Distance thick, every orientation and offset); the band whose cracks most exceed the
  /// count expected from the cluster's damage fraction becomes a candidate plane when the
  /// excess is at least this many standard deviations (and a part of it is a disc when
  /// its Fill has the grown planes' contrast, or the broken bonds crossing it exceed the
  /// model's damage fraction by this many standard deviations); 0 = off.
  double bandSignificance = 8.0;
  int discSides = 24;              ///< Disc Sides: vertices of each disc polygon, >= 3
};

/// Throws InputError naming the parameter, its value and the valid range.
void validate(const FractureParameters& params);

/// The fracture sets: tensile, shear and inherited failures stay apart.
enum class FractureSet : std::uint8_t { Tensile = 0, Shear = 1, Inherited = 2 };
constexpr int FractureSetCount = 3;
/// "Tensile", "Shear", "Inherited".
const char* fractureSetName(FractureSet set);

/// One fracture disc.
struct FractureDisc {
  FractureSet set = FractureSet::Tensile;
  Vec3 center{ 0, 0, 0 };        ///< m, area-weighted centroid of the cracks
  Vec3 normal{ 0, 0, 1 };        ///< unit, upward (nz >= 0)
  Vec3 strike{ 1, 0, 0 };        ///< unit, in-plane axis of the largest extent (l3)
  double dip = 0.0;              ///< degrees, [0, 90]
  double azimuth = 0.0;          ///< degrees, dip direction clockwise from North, [0, 360)
  double radius = 0.0;           ///< m, sqrt(Area / pi) (2D: half the trace length)
  double area = 0.0;             ///< m^2, L2 x L3 (2D: trace length x slab)
  double planarity = 0.0;        ///< 1 - l1 / l2
  double fill = 0.0;             ///< broken fraction of the bonds crossing the disc
  std::array<double, 3> eigenvalues{ { 0, 0, 0 } }; ///< m^2, l1 <= l2 <= l3
  std::vector<std::size_t> bonds; ///< indices into Model::bonds of its cracks
  std::vector<Vec3> polygon;     ///< m, the disc (Disc Sides vertices; 2D: 4) in order
  std::size_t crackCount() const { return bonds.size(); }
};

/// What the export did, for one set or for all.
struct FractureCounts {
  std::size_t brokenBonds = 0;       ///< broken bonds considered (cracks)
  std::size_t clusters = 0;          ///< spatially connected clusters
  std::size_t discs = 0;             ///< discs emitted
  std::size_t rejectedTooSmall = 0;  ///< clusters with fewer than Minimum Cracks
  std::size_t rejectedNonPlanar = 0; ///< clusters below Minimum Planarity that did not resolve into planar parts
  std::size_t rejectedSparse = 0;    ///< planar clusters whose disc has a Fill below Minimum Fill
  std::size_t splitClusters = 0;     ///< non-planar clusters resolved into planar parts
  std::size_t grownClusters = 0;     ///< of those, resolved by orientation-aware growth (Orientation Tolerance)
  std::size_t scannedClusters = 0;   ///< non-planar clusters with discs from the band scan (Band Significance)
  std::size_t cracksInDiscs = 0;     ///< cracks that ended up in a disc
  FractureCounts& operator+=(const FractureCounts& o);
};

struct FractureReport {
  std::array<FractureCounts, FractureSetCount> sets{}; ///< indexed by FractureSet
  FractureCounts total;
  double clusterDistance = 0.0;   ///< m, the distance used (the default resolved)
  int minimumCracks = 0;          ///< the parameters the counts refer to
  double minimumPlanarity = 0.0;
  double minimumFill = 0.0;
  double orientationTolerance = 0.0; ///< degrees
  double bandSignificance = 0.0;     ///< standard deviations
  /// Several lines: per set "Tensile: N broken bonds, C clusters, D discs, ...", then a
  /// line saying why nothing was emitted when that is the case.
  std::string summary() const;
};

struct FractureNetwork {
  std::vector<FractureDisc> discs; ///< ordered by set, then by decreasing crack count
  FractureReport report;
};

/// Mean particle diameter of a model, m (0 without particles).
double meanParticleDiameter(const Model& model);
/// The Cluster Distance used when the parameter is 0: this many mean diameters.
constexpr double DefaultClusterDiameters = 2.0;

/// Orientation of a unit normal (either sense): {dip, azimuth} in degrees after flipping
/// it upward. A horizontal plane has azimuth 0.
std::array<double, 2> dipAzimuth(const Vec3& normal);
/// The upward unit normal of a plane with this dip and azimuth (degrees):
/// n = (sin d sin a, sin d cos a, cos d).
Vec3 normalFromDipAzimuth(double dipDegrees, double azimuthDegrees);

/// Clusters the broken bonds of `model` and fits a disc to each planar cluster.
///
/// Clustering (per set, union-find over a uniform grid of cell Cluster Distance): two
/// cracks are connected when their crack positions lie within Cluster Distance, or when
/// their bonds share a particle and the positions lie within two largest particle
/// diameters (so that a cluster never joins across a periodic seam).
/// A cluster with at least Minimum Cracks cracks becomes a disc if its Planarity is at
/// least Minimum Planarity and its Fill (the fraction of all bonds whose segment crosses
/// the disc that are broken: 1 for a clean fracture, about the damage fraction for a
/// chance alignment in diffuse damage) is at least Minimum Fill (default 0: off, since the
/// fractures of a small failed specimen are partly broken zones with fills of 0.3-0.6).
/// A non-planar cluster may be two or more intersecting fractures: planes are extracted
/// from it one after another (the plane through three of its cracks with the most cracks
/// within half the clustering distance, 256 deterministic trials, refined by a fit to
/// those cracks); a plane is kept if it holds at least a quarter of the cluster's cracks
/// and Minimum Cracks, and its connected parts are kept when they make discs. The split
/// stands only if the kept planes hold at least 75 % of the cluster's cracks.
/// Otherwise, with Orientation Tolerance > 0, planes are grown through the cluster by
/// orientation (a failed specimen's damage: a thick, connected blob with planar parts and
/// scattered cracks): every crack gets a local plane, the area-weighted fit of the cracks
/// of its cluster within Cluster Distance, refitted twice to those within a quarter
/// Cluster Distance of the plane (its Local Planarity is 1 - l1/l2 of that fit, 0 when
/// fewer than 6 cracks or fewer than half its neighbours lie near the plane); seeds are
/// taken in order of decreasing Local Planarity (at least 0.5), and a plane
/// grows from its seed to neighbours within Cluster Distance whose local normal is within
/// Orientation Tolerance of the plane's running normal (the fit of its cracks so far,
/// kept while that fit is planar) and whose position is within half a Cluster Distance of
/// the running plane; only cracks whose Local Planarity reaches 0.5 grow the plane
/// further. Coplanar planes merge (normals within Orientation Tolerance, each centre
/// within half a Cluster Distance of the other's plane). A grown plane holding at least
/// 5 % of its cluster (and Minimum Cracks) is a disc when it passes the same tests as a
/// cluster and is clearly more broken than the model: Fill >= D + (1 - D) / 2, D the
/// broken fraction of all bonds (a chance alignment in diffuse damage has a Fill near D); the
/// cracks of no disc stay unassigned (scattered damage).
/// With Band Significance > 0 the cracks of a non-planar cluster that are in no disc yet
/// are then scanned for bands: for each normal (2D: every degree in the plane; 3D: 1,000
/// directions spread over a hemisphere) the cluster's bonds (intact and broken, their
/// centre-to-centre midpoints, inside the cluster's box) and its unassigned cracks are
/// counted in slabs one Cluster Distance thick at offsets a quarter of that apart; with p
/// the unassigned cracks over the bonds of the box, the slab with the largest z = (k - n p)
/// / sqrt(n p (1 - p)) (k cracks, n bonds in it) is a candidate when z reaches Band
/// Significance (chance maxima over the ~10^5 slabs of a uniform spread are about 5); its
/// connected parts become discs when they pass the tests of a cluster and are clearly more
/// broken than the model: Fill >= D + (1 - D) / 2 as a grown plane, or, of the n bonds
/// crossing the disc, k broken, (k - n D) / sqrt(n D (1 - D)) >= Band Significance (a
/// wide band moderately denser than dense damage); the candidate's slab (cracks and
/// bonds) is set aside and the scan repeats on the rest, at most 8 candidates. This reads the thick,
/// steep band through a specimen's diffuse damage that the local growth misses. Only when
/// no plane is found is the cluster rejected as non-planar.
FractureNetwork extractFractures(const Model& model, const FractureParameters& params);

} // namespace dem
