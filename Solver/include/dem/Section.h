// RockDEM engine: a plane section through a model (reference guide "Cut sections": Add
// Section XZ / YZ / XY; DESIGN.md pipeline DEMSection; Documentation/Sections.md).
//
// The plane cuts each sphere whose centre lies closer to it than its radius in an exact
// circle: centre = the centre's projection onto the plane, radius sqrt(R^2 - d^2) (d the
// centre's distance from the plane). An intact bond crosses the plane where its segment
// between the two centres (A to A + the minimum-image branch) does. A broken bond whose
// contact point lies within the trace distance of the plane leaves a trace: its crack (a
// disc of the bond's radius at the contact point, normal along the bond axis) projected
// onto the plane, an ellipse (a segment when the crack is perpendicular to the plane).
// A 2D section model is its own section: every disc, in the model plane (z = mid-slab).
// SI units (m).
#pragma once

#include "dem/Model.h"

#include <cstddef>
#include <string>
#include <vector>

namespace dem {

/// The orientations of the reference guide's commands, and any other.
enum class SectionOrientation : std::uint8_t { XY = 0, XZ = 1, YZ = 2, Custom = 3 };

/// "XY", "XZ", "YZ", "Custom".
const char* sectionOrientationName(SectionOrientation orientation);

/// The orientation of the Section property's value (0 XY, 1 XZ, 2 YZ, 3 Custom); throws
/// InputError naming a value out of range.
SectionOrientation sectionOrientation(int value);

struct SectionParameters {
  SectionOrientation orientation = SectionOrientation::XY;
  Vec3 origin{ 0.0, 0.0, 0.0 };  ///< m, a point of the plane
  Vec3 normal{ 0.0, 0.0, 1.0 };  ///< the plane's normal (Custom only; any length > 0)
  double traceDistance = 0.0;    ///< m, >= 0; 0 = half the mean particle diameter
  int circleSides = 32;          ///< vertices of a drawn circle or trace, >= 3

  /// The unit normal used: Z for XY, Y for XZ, X for YZ, the normalised normal for Custom.
  Vec3 unitNormal() const;
};

/// Throws InputError naming the parameter: a non-finite origin, a zero or non-finite
/// normal (Custom), a negative or non-finite trace distance, fewer than 3 circle sides.
void validate(const SectionParameters& params);

/// The circle where the plane cuts a particle.
struct SectionCircle {
  std::size_t particle = 0;  ///< slot
  Vec3 centre{ 0, 0, 0 };    ///< m, in the plane
  double radius = 0.0;       ///< m, sqrt(R^2 - d^2)
  double distance = 0.0;     ///< m, signed distance of the particle's centre from the plane
};

/// Where an intact bond crosses the plane.
struct BondCrossing {
  std::size_t bond = 0;      ///< index in model.bonds
  Vec3 point{ 0, 0, 0 };     ///< m, on the plane
};

/// A broken bond's crack projected onto the plane: the ellipse centre + cos t major +
/// sin t minor.
struct CrackTrace {
  std::size_t bond = 0;      ///< index in model.bonds
  Vec3 centre{ 0, 0, 0 };    ///< m, the contact point projected onto the plane
  Vec3 major{ 0, 0, 0 };     ///< m, semi-axis (length: the bond radius)
  Vec3 minor{ 0, 0, 0 };     ///< m, semi-axis (length: bond radius x |cos| of the crack's tilt)
  double distance = 0.0;     ///< m, signed distance of the contact point from the plane
};

struct ModelSection {
  Vec3 origin{ 0, 0, 0 };    ///< m, the plane's point used
  Vec3 normal{ 0, 0, 1 };    ///< unit normal used
  Vec3 u{ 1, 0, 0 };         ///< unit, in the plane
  Vec3 v{ 0, 1, 0 };         ///< unit, in the plane, normal x u
  double traceDistance = 0.0; ///< m, the trace distance used
  bool modelPlane = false;   ///< a 2D section model: the section is the model itself
  std::vector<SectionCircle> circles;
  std::vector<BondCrossing> crossings;
  std::vector<CrackTrace> traces;
  /// What the section found (counts), or why it is empty (the plane misses the model,
  /// the model has no particles).
  std::string message;
};

/// Vertex k of n of a drawn circle or trace: centre + cos(2 pi k / n) a + sin(2 pi k / n) b
/// (a, b the semi-axis vectors: radius u and radius v for a circle).
Vec3 ellipseVertex(const Vec3& centre, const Vec3& a, const Vec3& b, int k, int n);

/// Cuts the model with the plane. Circles are in slot order, crossings and traces in
/// bond order. In a 2D section model the plane parameters are not used: every particle
/// is a circle of its radius at its centre (distance 0), every intact bond "crosses" at
/// its contact point and every broken bond leaves a trace (the message says so).
ModelSection sectionModel(const Model& model, const SectionParameters& params);

} // namespace dem
