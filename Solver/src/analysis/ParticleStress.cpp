// RockDEM engine: per-particle stress (see dem/ParticleStress.h). SI units.
#include "dem/ParticleStress.h"

#include "dem/Simulation.h"

#include <cmath>

namespace dem {

void InteractionForces::clear()
{
  slotA.clear();
  slotB.clear();
  force.clear();
  armA.clear();
  armB.clear();
}

void InteractionForces::append(std::uint32_t a, std::uint32_t b, const Vec3& f, const Vec3& arm_a,
                               const Vec3& arm_b)
{
  slotA.push_back(a);
  slotB.push_back(b);
  force.push_back(f);
  armA.push_back(arm_a);
  armB.push_back(arm_b);
}

std::vector<StressTensor> particleStresses(const Model& model, const InteractionForces& forces)
{
  const Particles& p = model.particles;
  // Sum of arm (x) force per particle (N m), in the fixed order of the interaction list.
  std::vector<Eigen::Matrix3d> moment(p.size(), Eigen::Matrix3d::Zero());
  for (std::size_t c = 0; c < forces.size(); ++c) {
    const Vec3& f = forces.force[c];
    moment[forces.slotA[c]] += forces.armA[c] * f.transpose();
    if (forces.slotB[c] != WallPartner) {
      moment[forces.slotB[c]] -= forces.armB[c] * f.transpose(); // B feels -f
    }
  }
  std::vector<StressTensor> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double volume = particleVolume(model.domain, p.radius[i]);
    const Eigen::Matrix3d s = -(moment[i] + moment[i].transpose()) / (2.0 * volume);
    out[i] = { { s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2) } };
  }
  return out;
}

std::vector<StressTensor> particleStresses(const Model& model)
{
  if (model.particles.empty()) {
    return {};
  }
  return particleStresses(model, freshInteractionForces(model));
}

double meanStress(const StressTensor& s, bool section2D)
{
  return section2D ? 0.5 * (s[0] + s[1]) : (s[0] + s[1] + s[2]) / 3.0;
}

double vonMisesStress(const StressTensor& s, bool section2D)
{
  if (section2D) {
    const double half = 0.5 * (s[0] - s[1]);
    return 2.0 * std::sqrt(half * half + s[3] * s[3]);
  }
  const double dxy = s[0] - s[1];
  const double dyz = s[1] - s[2];
  const double dzx = s[2] - s[0];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) +
                   3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

} // namespace dem
