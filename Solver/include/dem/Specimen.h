// RockDEM engine: laboratory specimens carved out of a dense pack (DEM Specimen;
// Documentation/Specimens.md).
//
// Laboratories test cylinders (UCS, triaxial, direct tension) and discs (Brazilian),
// not boxes. carveSpecimen keeps the particles whose centres lie inside a box, a
// cylinder along an axis or a disc (a short cylinder, Length <= Diameter), removes the
// others with their contacts and bonds, and shrinks the model box (and its walls) to the
// kept particles' bounding box, so that the specimen is cemented and tested afterwards as
// usual. In a 2D section the shapes are their outlines in the XY plane, through the whole
// slab: Box is a rectangle (Size X, Y), Disc a disc about Z (Diameter); the slab
// thickness is the thickness. SI units (m).
#pragma once

#include "dem/Model.h"
#include "dem/RemovedParticles.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace dem {

enum class SpecimenShape : std::uint8_t { Box = 0, Cylinder = 1, Disc = 2 };

/// "Box", "Cylinder", "Disc".
const char* specimenShapeName(SpecimenShape shape);

/// The shape of the Shape property's value (0 Box, 1 Cylinder, 2 Disc); throws InputError
/// naming a value out of range.
SpecimenShape specimenShape(int value);

struct SpecimenSettings {
  SpecimenShape shape = SpecimenShape::Cylinder;
  int axis = 2;                      ///< Cylinder / Disc axis: 0 X, 1 Y, 2 Z (Z in a 2D section)
  bool centerOnModel = true;         ///< centre the specimen in the model box (else at `center`)
  Vec3 center{ 0.0, 0.0, 0.0 };      ///< m, the specimen's centre when centerOnModel is off
  Vec3 size{ 0.05, 0.05, 0.05 };     ///< m, Box edge lengths (X, Y; Z in 3D)
  double diameter = 0.05;            ///< m, Cylinder / Disc diameter
  double length = 0.1;               ///< m, Cylinder length / Disc thickness along Axis (3D)
};

/// The specimen's centre (m) for the given model domain.
Vec3 specimenCenter(const SpecimenSettings& settings, const Domain& domain);

/// Throws InputError naming the parameter, its value and the valid range: an axis out of
/// range, a non-positive or non-finite size, a disc thicker than its diameter, a shape
/// that does not fit in the model box (the valid range is what fits at that centre),
/// Cylinder in a 2D section, a Disc whose axis is not Z in a 2D section.
void validate(const SpecimenSettings& settings, const Domain& domain);

/// Whether a point (m) lies inside the specimen shape (in a 2D section, z is not looked at).
bool insideSpecimen(const SpecimenSettings& settings, const Domain& domain, const Vec3& x);

/// What carveSpecimen did.
struct SpecimenReport {
  std::size_t kept = 0;          ///< particles kept
  RemovedParticles removed;      ///< the particles outside, with their bonds and contacts
  Vec3 origin{ 0, 0, 0 };        ///< m, the new model box
  Vec3 size{ 0, 0, 0 };          ///< m
  double porosity = 0.0;         ///< -, 1 - particle volume / shape volume
  std::string summary() const;
};

/// Carves the specimen (validate first; throws InputError when no particle lies inside).
/// The model box becomes the kept particles' bounding box (centre +- radius; the slab of a
/// 2D section is kept), every axis stops being periodic (a specimen has free surfaces: a
/// bond or contact history that joined two kept particles across a periodic face is
/// removed), the walls stand at the new box and any load test ends (Mode Off).
SpecimenReport carveSpecimen(Model& model, const SpecimenSettings& settings);

} // namespace dem
