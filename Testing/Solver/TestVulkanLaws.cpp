// The force laws exist once in C++ and once in GLSL (DESIGN.md "Driver and backends"):
// the GLSL twins run on the Vulkan device (lavapipe in CI) on the same inputs as the C++
// functions and must give identical bits, edge cases included (zero overlap, gross
// sliding, a bond exactly at its strength, fixed particles of infinite mass, Cundall
// damping at zero velocity, a saturated servo). Reference: the C++ laws, which the
// physics tests check against Hertz, Mindlin, Potyondy & Cundall (PHYSICS.md).
#include "backends/vulkan/VulkanDevice.h"
#include "dem/BondLaw.h"
#include "dem/Bonds.h"
#include "dem/ContactLaws.h"
#include "dem/EmbeddedShaders.h"
#include "dem/WallControl.h"
#include "parity_layout.h"
#include "RequireVulkan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using dem::Vec3;

/// One case: PARITY_IN inputs.
struct Case {
  double in[PARITY_IN] = {};
  void set3(unsigned k, const Vec3& v)
  {
    in[k] = v.x();
    in[k + 1] = v.y();
    in[k + 2] = v.z();
  }
  Vec3 get3(unsigned k) const { return Vec3(in[k], in[k + 1], in[k + 2]); }
};

/// The C++ twin of law_parity.comp: the same laws on the same inputs.
std::vector<double> cpuResults(const Case& c)
{
  std::vector<double> out(PARITY_OUT, 0.0);
  auto put3 = [&](unsigned k, const Vec3& v) {
    out[k] = v.x();
    out[k + 1] = v.y();
    out[k + 2] = v.z();
  };
  const double* in = c.in;
  dem::ContactModel cm;
  cm.law = in[IN_LAW] == 0.0 ? dem::ContactLaw::HertzMindlin : dem::ContactLaw::Linear;
  cm.dampingCoefficient = in[IN_DAMPING];
  cm.friction = in[IN_FRICTION];
  cm.rollingFriction = in[IN_ROLLING];
  cm.youngsModulus = in[IN_YOUNG];
  cm.poissonsRatio = in[IN_POISSON];
  const bool planar = in[IN_PLANAR] != 0.0;
  const double slab = in[IN_SLAB];
  const double overlap = in[IN_OVERLAP];
  const Vec3 n = c.get3(IN_NORMAL);
  const dem::PairProperties pair =
    dem::pairProperties(cm, in[IN_RA], in[IN_MA], in[IN_RB], in[IN_MB], planar, slab);
  const double props[6] = { pair.effectiveModulus, pair.effectiveShearModulus, pair.effectiveRadius,
                            pair.effectiveMass, pair.linearNormalStiffness, pair.linearShearStiffness };
  std::copy(props, props + 6, out.begin() + OUT_PAIR);
  const dem::ContactConstants k = dem::contactConstants(cm, pair);
  out[OUT_CONSTANTS] = k.normalStiffness;
  out[OUT_CONSTANTS + 1] = k.normalDamping;
  out[OUT_CONSTANTS + 2] = k.tangentialStiffness;
  const dem::PairProperties wall = dem::wallProperties(cm, in[IN_RA], in[IN_MA], planar, slab);
  const double wprops[6] = { wall.effectiveModulus, wall.effectiveShearModulus, wall.effectiveRadius,
                             wall.effectiveMass, wall.linearNormalStiffness, wall.linearShearStiffness };
  std::copy(wprops, wprops + 6, out.begin() + OUT_WALL);
  const dem::ContactConstants kw = dem::contactConstants(cm, wall);
  out[OUT_WALL_CONSTANTS] = kw.normalStiffness;
  out[OUT_WALL_CONSTANTS + 1] = kw.normalDamping;
  out[OUT_WALL_CONSTANTS + 2] = kw.tangentialStiffness;
  out[OUT_NORMAL_STIFFNESS] = dem::normalStiffness(cm, pair, overlap);
  if (overlap > 0.0) {
    const dem::NormalResponse r = dem::normalResponse(cm.law, k, overlap, in[IN_APPROACH]);
    out[OUT_RESPONSE] = r.elasticForce;
    out[OUT_RESPONSE + 1] = r.force;
    out[OUT_RESPONSE + 2] = r.stiffness;
    out[OUT_RESPONSE + 3] = r.tangentialStiffness;
    Vec3 spring = c.get3(IN_SPRING);
    put3(OUT_TANGENTIAL, dem::mindlinCoulombForce(r.tangentialStiffness, cm.friction, r.force, n,
                                                  c.get3(IN_SLIP), spring));
    put3(OUT_SPRING, spring);
    Vec3 rolling = c.get3(IN_ROLL_SPRING);
    put3(OUT_ROLLING, dem::rollingTorque(cm, pair, overlap, r.force, n, c.get3(IN_ROLL), rolling));
    put3(OUT_ROLL_SPRING, rolling);
  }
  put3(OUT_ROTATED, dem::rotateIntoPlane(c.get3(IN_SPRING), n));
  out[OUT_CUNDALL] = dem::cundallDamping(in[IN_CUNDALL_FORCE], in[IN_CUNDALL_VELOCITY], in[IN_CUNDALL_ALPHA]);
  const double bondRadius = in[IN_BOND_RADIUS];
  const dem::BondSection section = dem::bondSection(bondRadius, planar, slab);
  out[OUT_SECTION] = section.area;
  out[OUT_SECTION + 1] = section.inertia;
  out[OUT_SECTION + 2] = section.polar;
  double fn = in[IN_BOND_FN];
  Vec3 fs = c.get3(IN_BOND_FS);
  double mt = in[IN_BOND_MT];
  Vec3 mb = c.get3(IN_BOND_MB);
  dem::incrementBond(section, in[IN_BOND_KN], in[IN_BOND_KS], planar, n, c.get3(IN_BOND_VELOCITY),
                     c.get3(IN_BOND_SPIN), in[IN_DT], fn, fs, mt, mb);
  out[OUT_BOND_STATE] = fn;
  put3(OUT_BOND_STATE + 1, fs);
  out[OUT_BOND_STATE + 4] = mt;
  put3(OUT_BOND_STATE + 5, mb);
  const dem::BondStresses stresses = dem::bondStresses(section, bondRadius, fn, fs, mt, mb, in[IN_BOND_BETA]);
  out[OUT_STRESSES] = stresses.sigmaMax;
  out[OUT_STRESSES + 1] = stresses.tauMax;
  out[OUT_STRESSES + 2] = stresses.compressive;
  // The GLSL twin takes tan(phi) (no double tangent in GLSL); the C++ takes phi: the host
  // gives the device std::tan(phi), as the Vulkan backend does.
  out[OUT_FAILURE] = static_cast<double>(dem::bondFailure(stresses, in[IN_BOND_SIGMA], in[IN_BOND_COHESION],
                                                          in[IN_BOND_PHI]));
  double damage = in[IN_BOND_DAMAGE];
  out[OUT_SOFTENED_FAILURE] = static_cast<double>(dem::softenedBondFailure(
    stresses, in[IN_BOND_SIGMA], in[IN_BOND_COHESION], in[IN_BOND_PHI], in[IN_BOND_SOFTENING], damage));
  out[OUT_DAMAGE] = damage;
  out[OUT_BOND_ENERGY] = dem::bondStoredEnergy(section, in[IN_BOND_KN], in[IN_BOND_KS], fn, fs, mt, mb);
  {
    const Vec3 force = c.get3(IN_BOND_FS);
    const Vec3 velocity = c.get3(IN_BOND_VELOCITY);
    const Vec3 torque = c.get3(IN_BOND_MB);
    const Vec3 spin = c.get3(IN_BOND_SPIN);
    Vec3 damped, dampedTorque;
    for (int k = 0; k < 3; ++k) {
      damped[k] = dem::cundallDamping(force[k], velocity[k], in[IN_CUNDALL_ALPHA]);
      dampedTorque[k] = dem::cundallDamping(torque[k], spin[k], in[IN_CUNDALL_ALPHA]);
    }
    out[OUT_DAMPING_WORK] = dem::cundallDampingWork(force, damped, velocity, torque, dampedTorque, spin, in[IN_DT]);
  }
  out[OUT_SERVO] = dem::servoWallVelocity(in[IN_SERVO_ELASTIC], in[IN_SERVO_STIFFNESS], in[IN_SERVO_AREA],
                                          in[IN_SERVO_TARGET], in[IN_SERVO_ALPHA], in[IN_DT],
                                          in[IN_SERVO_MAX_SPEED], static_cast<int>(in[IN_SERVO_SIDE]));
  return out;
}

Vec3 unit(std::mt19937_64& rng)
{
  std::normal_distribution<double> g(0.0, 1.0);
  Vec3 v(g(rng), g(rng), g(rng));
  return v / v.norm();
}

/// Random cases over the ranges a run meets, plus the edge cases.
std::vector<Case> makeCases()
{
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
  auto signedLog = [&](double lo, double hi) { return (u(rng) < 0.5 ? -1.0 : 1.0) * logUniform(lo, hi); };
  auto vec = [&](double lo, double hi) { return Vec3(signedLog(lo, hi), signedLog(lo, hi), signedLog(lo, hi)); };
  std::vector<Case> cases;
  for (int k = 0; k < 20000; ++k) {
    Case c;
    double* in = c.in;
    in[IN_LAW] = k % 2;
    in[IN_DAMPING] = k % 7 == 0 ? 0.0 : logUniform(0.01, 3.0);
    in[IN_FRICTION] = k % 11 == 0 ? 0.0 : u(rng);
    in[IN_ROLLING] = k % 3 == 0 ? 0.0 : logUniform(0.001, 0.5);
    in[IN_YOUNG] = logUniform(1e6, 1e11);
    in[IN_POISSON] = 0.45 * u(rng);
    in[IN_RA] = logUniform(1e-5, 1e-2);
    in[IN_RB] = logUniform(1e-5, 1e-2);
    in[IN_MA] = k % 13 == 0 ? std::numeric_limits<double>::infinity() : 2650.0 * 4.19 * std::pow(in[IN_RA], 3);
    in[IN_MB] = k % 17 == 0 ? std::numeric_limits<double>::infinity() : 2650.0 * 4.19 * std::pow(in[IN_RB], 3);
    in[IN_PLANAR] = k % 5 == 0 ? 1.0 : 0.0;
    in[IN_SLAB] = logUniform(1e-4, 1e-2);
    in[IN_OVERLAP] = k % 19 == 0 ? 0.0 : (k % 23 == 0 ? -1e-6 : logUniform(1e-12, 1e-4));
    in[IN_APPROACH] = signedLog(1e-6, 10.0);
    const Vec3 n = unit(rng);
    c.set3(IN_NORMAL, n);
    c.set3(IN_SLIP, dem::inPlane(vec(1e-12, 1e-5), n));
    // Gross sliding in every fourth case: a spring far beyond mu Fn / kt.
    c.set3(IN_SPRING, k % 29 == 0 ? Vec3::Zero() : vec(k % 4 == 0 ? 1e-3 : 1e-10, k % 4 == 0 ? 1e-1 : 1e-6));
    c.set3(IN_ROLL, dem::inPlane(vec(1e-9, 1e-3), n));
    c.set3(IN_ROLL_SPRING, k % 31 == 0 ? Vec3::Zero() : vec(1e-9, 1e-2));
    in[IN_CUNDALL_FORCE] = signedLog(1e-9, 1e3);
    in[IN_CUNDALL_VELOCITY] = k % 9 == 0 ? (k % 2 ? 0.0 : -0.0) : signedLog(1e-9, 10.0);
    in[IN_CUNDALL_ALPHA] = u(rng) * 0.99;
    in[IN_BOND_RADIUS] = logUniform(1e-5, 1e-2);
    in[IN_BOND_KN] = logUniform(1e9, 1e15);
    in[IN_BOND_KS] = logUniform(1e9, 1e15);
    in[IN_BOND_SIGMA] = logUniform(1e4, 1e8);
    in[IN_BOND_COHESION] = logUniform(1e4, 1e8);
    in[IN_BOND_PHI] = 0.9 * u(rng);
    in[IN_BOND_TAN_PHI] = std::tan(in[IN_BOND_PHI]);
    in[IN_BOND_BETA] = 0.25 * ((k / 5) % 5); // Moment Contribution 0, 0.25, 0.5, 0.75, 1, in 2D and 3D
    in[IN_BOND_FN] = signedLog(1e-6, 10.0);
    c.set3(IN_BOND_FS, dem::inPlane(vec(1e-6, 10.0), unit(rng)));
    in[IN_BOND_MT] = signedLog(1e-9, 1e-2);
    c.set3(IN_BOND_MB, vec(1e-9, 1e-2));
    c.set3(IN_BOND_VELOCITY, vec(1e-6, 1.0));
    c.set3(IN_BOND_SPIN, vec(1e-3, 1e3));
    in[IN_DT] = logUniform(1e-9, 1e-5);
    in[IN_SERVO_ELASTIC] = logUniform(1e-3, 1e4);
    in[IN_SERVO_STIFFNESS] = k % 8 == 0 ? 0.0 : logUniform(1e3, 1e9);
    in[IN_SERVO_AREA] = logUniform(1e-6, 1e-2);
    in[IN_SERVO_TARGET] = logUniform(1e3, 1e7);
    in[IN_SERVO_ALPHA] = u(rng);
    in[IN_SERVO_MAX_SPEED] = logUniform(1e-6, 1.0);
    in[IN_SERVO_SIDE] = k % 2;
    in[IN_BOND_SOFTENING] = k % 3 == 0 ? 0.0 : logUniform(0.1, 50.0); // brittle and softening bonds
    in[IN_BOND_DAMAGE] = k % 4 == 0 ? 0.0 : 0.9 * u(rng);
    cases.push_back(c);
  }
  // A bond exactly at its tensile strength, and exactly at its shear strength: the C++
  // stresses of the incremented state become the strengths (failure is >=).
  for (int k = 0; k < 200; ++k) {
    Case c = cases[k];
    const std::vector<double> r = cpuResults(c);
    if (k % 2 == 0) {
      c.in[IN_BOND_SIGMA] = r[OUT_STRESSES];
    } else {
      c.in[IN_BOND_SIGMA] = 2.0 * std::abs(r[OUT_STRESSES]) + 1.0; // no tensile failure
      c.in[IN_BOND_COHESION] = r[OUT_STRESSES + 1] - r[OUT_STRESSES + 2] * c.in[IN_BOND_TAN_PHI];
    }
    cases.push_back(c);
  }
  // Bonds on their softening line: the tensile strength set so that sigma_max is half way
  // along it (damage grows or stays, depending on the damage before).
  for (int k = 200; k < 400; ++k) {
    Case c = cases[k];
    const std::vector<double> r = cpuResults(c);
    if (r[OUT_STRESSES] > 0.0) {
      c.in[IN_BOND_SOFTENING] = 2.0;
      c.in[IN_BOND_SIGMA] = r[OUT_STRESSES] / 2.0;
      c.in[IN_BOND_COHESION] = 1e30; // no shear failure
      cases.push_back(c);
    }
  }
  // Spring parallel to the normal (its projection vanishes), and along the axes.
  for (int k = 0; k < 3; ++k) {
    Case c = cases[100 + k];
    Vec3 n = Vec3::Zero();
    n[k] = k == 1 ? -1.0 : 1.0;
    c.set3(IN_NORMAL, n);
    c.set3(IN_SPRING, 1e-6 * n);
    c.set3(IN_SLIP, Vec3::Zero());
    cases.push_back(c);
  }
  return cases;
}

} // namespace

TEST(VulkanLaws, SameBitsAsTheCppLawsOnTheDevice)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  const std::shared_ptr<dem::vk::Device> device = dem::vk::Device::open();
  const std::vector<Case> cases = makeCases();
  const std::uint64_t inBytes = cases.size() * sizeof(Case);
  const std::uint64_t outBytes = cases.size() * PARITY_OUT * sizeof(double);
  dem::vk::Buffer input = device->createBuffer(inBytes);
  dem::vk::Buffer output = device->createBuffer(outBytes);
  dem::vk::Buffer staging = device->createStaging(std::max(inBytes, outBytes));
  std::memcpy(staging.mapped, cases.data(), inBytes);
  struct Push {
    std::uint64_t cases, results;
    std::uint32_t count, pad;
  } push{ input.address, output.address, static_cast<std::uint32_t>(cases.size()), 0 };
  const dem::vk::Pipeline& pipeline = device->pipeline(dem::shaders::module("law_parity"), sizeof(Push));
  const dem::vk::Api& api = device->api();
  device->submit([&](VkCommandBuffer cb) {
    VkBufferCopy up{ 0, 0, inBytes };
    api.vkCmdCopyBuffer(cb, staging.buffer, input.buffer, 1, &up);
    api.vkCmdFillBuffer(cb, output.buffer, 0, VK_WHOLE_SIZE, 0);
    device->barrier(cb);
    api.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
    api.vkCmdPushConstants(cb, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push), &push);
    api.vkCmdDispatch(cb, static_cast<std::uint32_t>((cases.size() + 63) / 64), 1, 1);
    device->barrier(cb);
    VkBufferCopy down{ 0, 0, outBytes };
    api.vkCmdCopyBuffer(cb, output.buffer, staging.buffer, 1, &down);
  });
  const double* gpu = static_cast<const double*>(staging.mapped);
  std::size_t mismatches = 0;
  std::size_t grossSliding = 0, atStrength = 0, failed = 0, softening = 0;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::vector<double> cpu = cpuResults(cases[c]);
    for (unsigned k = 0; k < PARITY_OUT; ++k) {
      if (std::memcmp(&cpu[k], &gpu[PARITY_OUT * c + k], sizeof(double)) != 0) {
        if (++mismatches <= 10) {
          ADD_FAILURE() << "case " << c << " result " << k << ": C++ " << cpu[k] << ", GLSL "
                        << gpu[PARITY_OUT * c + k];
        }
      }
    }
    // The edge cases are there: Coulomb caps hit, bonds at their strength.
    const Vec3 spring = cases[c].get3(IN_SPRING) + cases[c].get3(IN_SLIP);
    if (cases[c].in[IN_OVERLAP] > 0.0 && cpu[OUT_RESPONSE + 3] * spring.norm() > cases[c].in[IN_FRICTION] * cpu[OUT_RESPONSE + 1]) {
      ++grossSliding;
    }
    if (cpu[OUT_FAILURE] != 0.0) {
      ++failed;
    }
    if (cpu[OUT_STRESSES] == cases[c].in[IN_BOND_SIGMA]) {
      ++atStrength;
    }
    if (cpu[OUT_DAMAGE] > cases[c].in[IN_BOND_DAMAGE] && cpu[OUT_SOFTENED_FAILURE] == 0.0) {
      ++softening;
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << cases.size() * PARITY_OUT << " results";
  EXPECT_GT(grossSliding, 1000u);
  EXPECT_GE(atStrength, 100u);
  EXPECT_GT(failed, 100u);
  EXPECT_GT(softening, 50u) << "bonds on the softening line whose damage grew";
  device->destroy(input);
  device->destroy(output);
  device->destroy(staging);
}

TEST(VulkanLaws, NoFloatingPointOperationMayBeFusedIntoAnFma)
{
  // SPIR-V specification 3.20 (Decoration NoContraction = 42) and 3.32 (OpFMul = 133,
  // OpFAdd = 129, OpDecorate = 71): every OpFMul/OpFAdd result is decorated.
  const dem::shaders::SpirvModule m = dem::shaders::module("pair_forces");
  const std::vector<std::uint32_t> words = dem::vk::withoutContraction(m.words, m.count);
  std::vector<std::uint32_t> arithmetic, decorated;
  for (std::size_t at = 5; at < words.size();) {
    const std::uint32_t length = words[at] >> 16;
    const std::uint32_t opcode = words[at] & 0xffffu;
    ASSERT_GT(length, 0u);
    if (opcode == 129 || opcode == 133 || opcode == 131) {
      arithmetic.push_back(words[at + 2]);
    }
    if (opcode == 71 && words[at + 2] == 42) {
      decorated.push_back(words[at + 1]);
    }
    at += length;
  }
  ASSERT_GT(arithmetic.size(), 50u);
  for (std::uint32_t id : arithmetic) {
    EXPECT_NE(std::find(decorated.begin(), decorated.end(), id), decorated.end()) << "result %" << id;
  }
  EXPECT_EQ(words.size(), m.count + 3 * decorated.size());
}

TEST(VulkanDevice, AnArrayLargerThanTheBindingRangeIsReachedWhole)
{
  ROCKDEM_REQUIRE_VULKAN_DEVICE();
  // The backend reaches its arrays by buffer device address (GL_EXT_buffer_reference), so
  // maxStorageBufferRange (128 MiB on lavapipe) does not cap an array: a kernel sums an
  // array 1.25 x that size whose only non-zero element is its last.
  const std::shared_ptr<dem::vk::Device> device = dem::vk::Device::open();
  const std::uint64_t limit = device->maxStorageBufferRange();
  ASSERT_GT(limit, 0u);
  const std::uint32_t count = static_cast<std::uint32_t>(std::min<std::uint64_t>(limit / 8 + limit / 32, 1u << 28));
  ASSERT_GT(8ull * count, limit);
  dem::vk::Buffer data = device->createBuffer(8ull * count);
  const std::uint64_t half = count / 1024 + 2; // partial sums: two halves, read one, write the other
  dem::vk::Buffer sums = device->createBuffer(16ull * half);
  dem::vk::Buffer staging = device->createStaging(16);
  const double one = 1.0;
  std::memcpy(staging.mapped, &one, 8);
  struct Push {
    std::uint64_t params, data, result;
    std::uint32_t count, pad;
  };
  const dem::vk::Pipeline& reduce = device->pipeline(dem::shaders::module("reduce_sum"), sizeof(Push));
  const dem::vk::Api& api = device->api();
  device->submit([&](VkCommandBuffer cb) {
    api.vkCmdFillBuffer(cb, data.buffer, 0, VK_WHOLE_SIZE, 0);
    device->barrier(cb);
    VkBufferCopy last{ 0, 8ull * (count - 1), 8 };
    api.vkCmdCopyBuffer(cb, staging.buffer, data.buffer, 1, &last);
    device->barrier(cb);
    api.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, reduce.pipeline);
    std::uint64_t source = data.address;
    std::uint32_t n = count;
    bool first = true;
    int side = 0;
    while (first || n > 1) {
      const std::uint32_t groups = (n + 1023) / 1024;
      const std::uint64_t target = sums.address + 8ull * half * static_cast<std::uint64_t>(side);
      side = 1 - side;
      const Push push{ 0, source, target, n, 0 };
      api.vkCmdPushConstants(cb, reduce.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push), &push);
      api.vkCmdDispatch(cb, groups, 1, 1);
      device->barrier(cb);
      source = target;
      n = groups;
      first = false;
    }
    VkBufferCopy back{ source - sums.address, 0, 8 };
    api.vkCmdCopyBuffer(cb, sums.buffer, staging.buffer, 1, &back);
  });
  double total = 0.0;
  std::memcpy(&total, staging.mapped, 8);
  EXPECT_EQ(total, 1.0) << "array of " << 8ull * count << " bytes, binding range " << limit;
  device->destroy(data);
  device->destroy(sums);
  device->destroy(staging);
}
