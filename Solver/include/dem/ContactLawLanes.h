// RockDEM engine: the time step's contact laws written once for a 3-vector type V whose
// components are of a lane type S: Eigen's Vector3d with S = double (one contact; the
// traits are in dem/ContactLaws.h), or dem::Lane3 of a SIMD vector of doubles (several
// contacts at once, the CPU backend's AVX2 pair kernel). Every lane performs the same IEEE operations in the same
// order as the double instance, without fused multiply-adds, so a lane gives the double's
// bits exactly (add, subtract, multiply, divide and square root are correctly rounded).
// Branches become selects where lanes may disagree; LaneOps<S>::any keeps the scalar
// instance's early outs. VecOps<V> gives the 3-vector operations. The Eigen functions of dem/ContactLaws.h (rotateIntoPlane,
// mindlinCoulombForce, hertzMindlinResponse, linearResponse) call these, and the GLSL twin
// in shaders/include/contact_laws.glsl performs the same operations in the same order.
//
// This header includes no Eigen on purpose: the AVX2 translation unit includes it and must
// not emit out-of-line copies of inline functions shared with the default build.
// SI units as in dem/ContactLaws.h.
#pragma once

#include <cmath>

// A law that both loops of a backend run (the scalar one and the SIMD kernel) is inlined
// into each (out of line, its input and result would travel through memory on every call).
#if defined(__GNUC__)
#define ROCKDEM_INLINE_LAW inline __attribute__((always_inline))
#else
#define ROCKDEM_INLINE_LAW inline
#endif

namespace dem {

/// Lane operations of a lane type S. The double instance is here; a SIMD lane type defines
/// its specialisation before it instantiates the laws.
template <class S> struct LaneOps;

template <> struct LaneOps<double> {
  using Mask = bool;
  static double broadcast(double x) { return x; }
  static double sqrt(double x) { return std::sqrt(x); }
  static double abs(double x) { return std::abs(x); }
  static double select(bool m, double a, double b) { return m ? a : b; }
  static bool both(bool a, bool b) { return a && b; }
  static bool any(bool m) { return m; }
};

/// The 3-vector operations of a vector type V (VecOps<V>::Scalar is its lane type): dot
/// and squared norm summed as (x + y) + z, cross as Eigen's cross for 3-vectors, products
/// and quotients with a lane scalar component by component (a quotient divides each
/// component, no reciprocal), as Eigen evaluates them for Vector3d.
template <class V> struct VecOps;

/// A 3-vector of lanes (the SIMD kernel's vector type).
template <class S> struct Lane3 {
  S x, y, z;
};

template <class S> inline Lane3<S> operator+(const Lane3<S>& a, const Lane3<S>& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
template <class S> inline Lane3<S> operator-(const Lane3<S>& a, const Lane3<S>& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}

template <class S> struct VecOps<Lane3<S>> {
  using Scalar = S;
  static S dot(const Lane3<S>& a, const Lane3<S>& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
  static S squaredNorm(const Lane3<S>& a) { return (a.x * a.x + a.y * a.y) + a.z * a.z; }
  static Lane3<S> cross(const Lane3<S>& a, const Lane3<S>& b)
  {
    return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
  }
  static Lane3<S> scaled(const S& s, const Lane3<S>& v) { return { s * v.x, s * v.y, s * v.z }; }
  static Lane3<S> divided(const Lane3<S>& v, const S& s) { return { v.x / s, v.y / s, v.z / s }; }
  template <class M> static Lane3<S> select(const M& m, const Lane3<S>& a, const Lane3<S>& b)
  {
    using Ops = LaneOps<S>;
    return { Ops::select(m, a.x, b.x), Ops::select(m, a.y, b.y), Ops::select(m, a.z, b.z) };
  }
  static Lane3<S> zero() { return { S{}, S{}, S{} }; }
};

/// v minus its component along the unit normal n (dem::inPlane).
template <class V> inline V inPlaneLanes(const V& v, const V& n)
{
  using O = VecOps<V>;
  return v - O::scaled(O::dot(v, n), n);
}

/// The normal response of one contact (dem::NormalResponse), per lane.
template <class S> struct NormalResponseLanes {
  S elasticForce;
  S force;
  S stiffness;
  S tangentialStiffness;
};

/// dem::hertzMindlinResponse per lane: K, c and kt are the contact's constants.
template <class S>
inline NormalResponseLanes<S> hertzMindlinResponseLanes(const S& normalStiffness,
  const S& normalDamping, const S& tangentialStiffness, const S& overlap, const S& approachSpeed)
{
  using Ops = LaneOps<S>;
  const S root = Ops::sqrt(overlap); // m^(1/2)
  const S elastic = normalStiffness * overlap * root;
  const S viscous = normalDamping * Ops::sqrt(root) * approachSpeed;
  const S force = elastic + viscous;
  return { elastic, Ops::select(force > 0.0, force, S{}), 1.5 * normalStiffness * root,
           tangentialStiffness * root };
}

/// dem::linearResponse per lane.
template <class S>
inline NormalResponseLanes<S> linearResponseLanes(const S& normalStiffness,
  const S& normalDamping, const S& tangentialStiffness, const S& overlap, const S& approachSpeed)
{
  using Ops = LaneOps<S>;
  const S elastic = normalStiffness * overlap;
  const S force = elastic + normalDamping * approachSpeed;
  return { elastic, Ops::select(force > 0.0, force, S{}), normalStiffness, tangentialStiffness };
}

/// dem::rotateIntoPlane per lane: a stored in-plane vector rotated into the plane normal to
/// the unit n, keeping its length (zero stays zero, as does a vector along n).
template <class V> inline V rotateIntoPlaneLanes(const V& v, const V& n)
{
  using O = VecOps<V>;
  using S = typename O::Scalar;
  using Ops = LaneOps<S>;
  const S length2 = O::squaredNorm(v);
  const auto nonzero = length2 != 0.0;
  if (!Ops::any(nonzero)) {
    return O::zero();
  }
  const V projected = inPlaneLanes(v, n);
  const S projected2 = O::squaredNorm(projected);
  const auto keep = Ops::both(nonzero, projected2 > 0.0);
  return O::select(keep, O::scaled(Ops::sqrt(length2 / projected2), projected), O::zero());
}

/// dem::mindlinCoulombForce per lane: the spring (m) rotated into the plane, incremented by
/// the slip and capped at |Ft| <= mu Fn; returns Ft = -kt * spring (N) on particle A.
template <class V>
inline V mindlinCoulombForceLanes(const typename VecOps<V>::Scalar& kt,
                                  const typename VecOps<V>::Scalar& friction,
                                  const typename VecOps<V>::Scalar& normalForce, const V& n,
                                  const V& slipIncrement, V& spring)
{
  using O = VecOps<V>;
  using S = typename O::Scalar;
  using Ops = LaneOps<S>;
  spring = rotateIntoPlaneLanes(spring, n) + slipIncrement;
  const S limit = friction * normalForce;            // N, Coulomb: |Ft| <= mu Fn
  const S trial2 = kt * kt * O::squaredNorm(spring); // N^2
  const auto sliding = trial2 > limit * limit;
  if (Ops::any(sliding)) {
    // Gross sliding: keep the spring at the length that carries exactly mu Fn.
    const S trial = Ops::sqrt(trial2);
    const S factor = Ops::select(Ops::both(kt > 0.0, trial > 0.0), limit / trial, S{});
    spring = O::select(sliding, O::scaled(factor, spring), spring);
  }
  const S minusKt = -kt;
  return O::scaled(minusKt, spring);
}

} // namespace dem
