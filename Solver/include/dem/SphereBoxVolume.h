// RockDEM engine: exact overlap volumes of a sphere with a box and areas of a disc with a
// rectangle (for the voxel model, dem/Voxelize.h; Documentation/Sections.md).
//
// Closed forms, no quadrature. The ball corner V(a, b, c) = volume of the unit ball with
// x > a, y > b, z > c comes from the divergence theorem, V = (1/3)(Omega - a A_x - b A_y
// - c A_z): Omega the area of its spherical face (Gauss-Bonnet on a triangle of three
// small circles) and A_x, A_y, A_z its flat faces (disc corners). A box is the alternating
// sum of V over its eight corners (inclusion-exclusion), so the pieces of a sphere cut by
// a grid add up to the sphere's volume to rounding. SI units (m, m^2, m^3).
#pragma once

#include "dem/Model.h"

namespace dem {

/// Area of the part of the unit disc with x > a and y > b (any a, b).
double unitDiscCornerArea(double a, double b);

/// Volume of the part of the unit ball with x > a, y > b and z > c (any a, b, c).
double unitBallCornerVolume(double a, double b, double c);

/// Volume (m^3) of the part of the sphere (centre, radius in m) inside the box [lo, hi].
double sphereBoxVolume(const Vec3& centre, double radius, const Vec3& lo, const Vec3& hi);

/// Area (m^2) of the part of the disc (centre cx, cy, radius in m) inside the rectangle
/// [x0, x1] x [y0, y1].
double discRectangleArea(double cx, double cy, double radius, double x0, double y0, double x1,
                         double y1);

} // namespace dem
