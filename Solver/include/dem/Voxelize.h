// RockDEM engine: the voxel model of a particle model (reference guide "Current
// limitations": "Convert to Voxel Model produces an empty model"; DESIGN.md pipeline
// DEMVoxelize; Documentation/Sections.md).
//
// A regular grid of voxels over the particles. Each voxel holds
// - the solid fraction: the exact volume of every sphere inside it (dem/SphereBoxVolume.h; in a
//   2D section model the disc area inside the pixel, the discs spanning the slab) over the
//   voxel volume;
// - the bonds whose midpoint lies in it (installed, broken), the damage broken /
//   installed and the broken-bond density broken / voxel volume;
// - the stress of the voxel as a piece of the continuum, sum_p V(p in voxel) sigma_p /
//   V_voxel (so that the voxels' volume average is the specimen's Love-Weber stress), its
//   mean and its von Mises (deviator) stress;
// - the displacement of the solid in it (volume-weighted mean of its particles');
// - with a DFN, the fracture intensity P32 = fracture area inside the voxel / voxel volume
//   and the set of the fracture with the most area in it.
// Voxel index v = i + nx (j + ny k) (x fastest). SI units.
#pragma once

#include "dem/Model.h"
#include "dem/ParticleStress.h"
#include "dem/SeedFractures.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

/// How the voxel size is chosen.
enum class VoxelSizing : std::uint8_t {
  VoxelSize = 0,      ///< the Voxel Size (m) as given
  NumberOfVoxels = 1, ///< Number Of Voxels along the longest axis of the particles' extent
};

/// The sizing of the Size By property's value (0 Voxel Size, 1 Number Of Voxels); throws
/// InputError naming a value out of range.
VoxelSizing voxelSizing(int value);

struct VoxelParameters {
  VoxelSizing sizing = VoxelSizing::NumberOfVoxels;
  double voxelSize = 0.001;   ///< m, > 0 (VoxelSize sizing)
  int numberOfVoxels = 64;    ///< along the longest axis, >= 1 (NumberOfVoxels sizing)
  double margin = 0.05;       ///< -, >= 0: room around the particles' extent on each side,
                              ///< as a fraction of its longest axis (not on periodic axes)
  double memoryLimit = 2048;  ///< MiB, > 0: the largest grid to build
};

/// Throws InputError naming the parameter, its value and the valid range.
void validate(const VoxelParameters& params);

/// The grid: voxel (i, j, k) spans origin + (i, j, k) * spacing to origin + (i + 1, j + 1,
/// k + 1) * spacing.
struct VoxelGrid {
  std::array<int, 3> dimensions{ { 0, 0, 0 } }; ///< voxels per axis
  Vec3 origin{ 0, 0, 0 };                      ///< m, lowest corner
  Vec3 spacing{ 0, 0, 0 };                     ///< m, voxel edge per axis
  std::array<bool, 3> wraps{ { false, false, false } }; ///< periodic axis: indices wrap around

  std::size_t count() const
  {
    return static_cast<std::size_t>(dimensions[0]) * dimensions[1] * dimensions[2];
  }
  double voxelVolume() const { return spacing.x() * spacing.y() * spacing.z(); }
};

/// Bytes per voxel that voxelize() and the VTK copy of its result hold at the peak.
std::size_t voxelBytes(bool withFractures);

/// The grid fitted to a model: over the spheres' extent (centre +- radius) widened on each
/// side by the margin x its longest axis; on a periodic axis over the model box, with the
/// spacing that divides it exactly; in a 2D section one layer through the slab. Voxels are
/// cubes of the Voxel Size (or of the longest extent / Number Of Voxels, the extent
/// without the margin) except on periodic axes and the 2D slab axis. A grid fitted to
/// one state of a run serves its other states (the voxels stay where they are while the
/// model moves): the parts of particles and the bonds that leave it are not counted, and
/// the voxel model says how much.
/// Throws InputError when the grid needs more memory than the Memory Limit or than the
/// machine has available (the message names the voxel size, the grid, the memory needed
/// and the limit).
VoxelGrid planVoxelGrid(const Model& model, const VoxelParameters& params, bool withFractures);

/// A fracture network for the voxel model: planar polygons (m) and the set of each
/// (-1 when unknown; 0 tensile, 1 shear, 2 inherited from DEM Fractures To DFN).
struct FractureSetPolygons {
  std::vector<FracturePolygon> polygons;
  std::vector<int> sets;
};

struct VoxelModel {
  VoxelGrid grid;
  std::vector<double> solidFraction;      ///< -, solid volume / voxel volume
  std::vector<std::int32_t> bonds;        ///< bonds (intact or broken) with their midpoint in the voxel
  std::vector<std::int32_t> brokenBonds;  ///< broken ones among them
  std::vector<double> damage;             ///< -, broken / installed (0 without bonds)
  std::vector<double> brokenBondDensity;  ///< 1/m^3, broken bonds / voxel volume
  std::vector<StressTensor> stress;       ///< Pa, compression positive, sum V sigma / V_voxel
  std::vector<double> meanStress;         ///< Pa
  std::vector<double> deviatoricStress;   ///< Pa, von Mises (in 2D the in-plane s1 - s2)
  std::vector<Vec3> displacement;         ///< m, mean of the solid in the voxel (0 if none)
  std::vector<double> fractureIntensity;  ///< 1/m, P32 (empty without a DFN)
  std::vector<std::int32_t> fractureSet;  ///< set with the most area (-1 none; empty without a DFN)
  double solidVolume = 0.0;               ///< m^3, sum over the voxels
  double particleVolume = 0.0;            ///< m^3, sum of the particles' volumes
  std::size_t bondsOutside = 0;           ///< bonds whose midpoint lies outside the grid
  double fractureArea = 0.0;              ///< m^2, fracture area inside the grid
  std::string message;                    ///< the grid and what it holds
};

/// Builds the voxel model of a model state on a grid (planVoxelGrid). `stresses` are the
/// particle stresses (particleStresses(), slot order). `fractures` (may be null) are
/// rasterised into the fracture intensity. Throws InputError for invalid fractures, a grid
/// without voxels, or stresses of the wrong size.
VoxelModel voxelize(const Model& model, const VoxelGrid& grid, const std::vector<StressTensor>& stresses,
                    const FractureSetPolygons* fractures);

/// voxelize() on the grid fitted to the model itself (planVoxelGrid(model, params, ...)).
VoxelModel voxelize(const Model& model, const VoxelParameters& params,
                    const std::vector<StressTensor>& stresses, const FractureSetPolygons* fractures);

/// Area (m^2) of the planar polygon inside the box [lo, hi] (the polygon clipped by the
/// box's six planes, Sutherland-Hodgman; exact for any simple polygon, convex or not).
double polygonBoxArea(const FracturePolygon& polygon, const Vec3& lo, const Vec3& hi);

} // namespace dem
