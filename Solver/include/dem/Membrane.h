// RockDEM engine: the flexible membrane around a cylindrical specimen in Triaxial and
// Isotropic tests (Confinement = Membrane; Documentation/Specimens.md, "The flexible
// membrane").
//
// Boundary-particle method: the lateral surface between the platens is cut into axial
// slices x angular sectors about the specimen's axis, each bin about MembraneBinSize mean
// diameters on a side; in each bin the grain reaching farthest from the axis (centre
// distance + radius) is the surface grain there, and it is pushed towards the axis by the
// confining pressure x the bin's share of the lateral surface at that grain's outer radius
// (an empty bin's share goes to the nearest occupied sector of its slice).
// The surface is found afresh every step from the current positions (so it follows
// barrelling and a shear band through the side), serially in slot order: the forces depend
// on the positions only, are bit-identical on any thread count, and a reloaded model
// recomputes them exactly. SI units: m, N, Pa.
#pragma once

#include "dem/LoadTest.h"
#include "dem/Model.h"

#include <cstddef>
#include <vector>

namespace dem {

/// Edge of a membrane bin (along the axis and around it), in mean particle diameters.
constexpr double MembraneBinSize = 1.25;

/// The membrane's surface now.
struct MembraneSurface {
  Vec3 centre{ 0.0, 0.0, 0.0 };  ///< m, centroid of the particle centres (the axis passes through it)
  double length = 0.0;           ///< m, between the platens
  double radius = 0.0;           ///< m, mean over the bins of the surface grain's outer radius (centre distance + radius)
  double radiusSpread = 0.0;     ///< m, standard deviation of those outer radii (0 for a perfect cylinder)
  double minRadius = 0.0;        ///< m, smallest of them
  double maxRadius = 0.0;        ///< m, largest of them
  int sectors = 0;               ///< bins around the axis
  int slices = 0;                ///< bins along the axis
  std::size_t surfaceGrains = 0; ///< bins holding a grain (one pushed grain each; an empty bin's area goes to the nearest occupied sector of its slice)
  double lateralArea = 0.0;      ///< m^2, 2 pi radius length
  double crossSection = 0.0;     ///< m^2, pi radius^2 (the platens' area)
  double force = 0.0;            ///< N, sum of the magnitudes of the membrane forces
  Vec3 netForce{ 0.0, 0.0, 0.0 }; ///< N, their vector sum (about zero on a round specimen)
};

/// Whether the model's test confines with the membrane now: Confinement Membrane, Mode
/// Triaxial or Isotropic, a stage started, a 3D model with its six walls.
bool membraneActive(const Model& model);

/// The membrane's surface now (zeros when membraneActive is false). With `forces`: resized
/// to the particle count and filled with the membrane force on each particle (N, towards the
/// axis, through the centre; zero off the surface), or cleared when the membrane is not
/// active. Serial, slot order.
MembraneSurface membraneSurface(const Model& model, std::vector<Vec3>* forces = nullptr);

/// The lateral surface of a cylindrical specimen along axis `a` between its platens (walls
/// 2a and 2a + 1), found as the membrane finds it (the bins, each bin's outermost grain),
/// with `pressure` (Pa) on it: its `radius` is the mean outer reach of the surface grains,
/// the radius the press measures a cylinder's section with, under the membrane and in an
/// unconfined test alike. With `forces` as membraneSurface. Zeros without particles or
/// walls. Serial, slot order.
MembraneSurface lateralSurface(const Model& model, int a, double pressure, std::vector<Vec3>* forces = nullptr);

/// Throws InputError naming Confinement unless the model can be confined by a membrane for
/// `settings` (Confinement Membrane): a 3D model whose particles form a cylinder along Axis
/// (every centre within half the smaller lateral extent of the axis through the middle of
/// that extent; a box's corners lie up to 1.41 half widths out). No-op for Rigid Walls.
void validateMembraneSpecimen(const Model& model, const LoadTestSettings& settings);

} // namespace dem
