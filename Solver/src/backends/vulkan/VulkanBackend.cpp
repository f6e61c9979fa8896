// RockDEM engine: the Vulkan backend (see VulkanBackend.h). SI units.
#include "backends/vulkan/VulkanBackend.h"

#include "control.h"
#include "dem/EmbeddedShaders.h"
#include "dem/LoadTest.h"
#include "dem/SizeClass.h"
#include "dem/SizeClassGrids.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace dem {
namespace vk {
/// A piece of a host array to move to or from a device array.
struct Transfer {
  void* host;
  std::uint64_t bytes;
  VkBuffer buffer;
  std::uint64_t offset;
};
} // namespace vk

namespace {

using vk::Transfer;

/// How many elements an array holds, in terms of the model's sizes.
enum class Count {
  N, N3, NPlus1, Pairs, Pairs3, PairsRolling3, Adjacency, Walls, Walls3, WallsRolling3,
  Bonds, Bonds3, Bonds2, Cells, Histogram, ScanBlocks, Control, WallData, Clock, Indirect, Partial
};

enum class Group { Fixed, Pairs, Walls };

struct ArraySpec {
  const char* name;
  Count count;
  std::uint32_t elementBytes;
};

const ArraySpec kArrays[] = {
  { "position", Count::N3, 8 }, { "velocity", Count::N3, 8 }, { "angularVelocity", Count::N3, 8 },
  { "displacement", Count::N3, 8 }, { "force", Count::N3, 8 }, { "torque", Count::N3, 8 },
  { "undampedForce", Count::N3, 8 }, { "positionAtBuild", Count::N3, 8 },
  { "radius", Count::N, 8 }, { "mass", Count::N, 8 }, { "inertia", Count::N, 8 },
  { "inverseMass", Count::N, 8 }, { "inverseInertia", Count::N, 8 }, { "kinetic", Count::N, 8 }, { "dampingWork", Count::N, 8 },
  { "flags", Count::N, 4 }, { "sizeClass", Count::N, 4 },
  { "keysA", Count::N, 4 }, { "keysB", Count::N, 4 }, { "valuesA", Count::N, 4 }, { "valuesB", Count::N, 4 },
  { "histogram", Count::Histogram, 4 }, { "cellStart", Count::Cells, 4 }, { "cellEnd", Count::Cells, 4 },
  { "fullCount", Count::NPlus1, 4 }, { "halfCount", Count::NPlus1, 4 }, { "wallCount", Count::NPlus1, 4 },
  { "fullScan", Count::NPlus1, 4 }, { "halfScan", Count::NPlus1, 4 }, { "wallScan", Count::NPlus1, 4 },
  { "scanBlocks", Count::ScanBlocks, 4 },
  { "partners", Count::Adjacency, 4 }, { "adjacencyStart", Count::NPlus1, 4 },
  { "adjacency", Count::Adjacency, 4 }, { "pairStart", Count::NPlus1, 4 },
  { "pairI", Count::Pairs, 4 }, { "pairJ", Count::Pairs, 4 }, { "pairConstants", Count::Pairs3, 8 },
  { "pairSpring", Count::Pairs3, 8 }, { "pairRolling", Count::PairsRolling3, 8 },
  { "pairForce", Count::Pairs3, 8 }, { "pairTorqueI", Count::Pairs3, 8 }, { "pairTorqueJ", Count::Pairs3, 8 },
  { "pairNormal", Count::Pairs, 8 }, { "oldPairStart", Count::NPlus1, 4 }, { "oldPairJ", Count::Pairs, 4 },
  { "oldPairSpring", Count::Pairs3, 8 }, { "oldPairRolling", Count::PairsRolling3, 8 },
  { "wallStart", Count::NPlus1, 4 }, { "wallSlot", Count::Walls, 4 }, { "wallIndex", Count::Walls, 4 },
  { "wallTouching", Count::Walls, 4 }, { "wallConstants", Count::Walls3, 8 },
  { "wallSpring", Count::Walls3, 8 }, { "wallRolling", Count::WallsRolling3, 8 },
  { "wallForce", Count::Walls3, 8 }, { "wallNormal", Count::Walls, 8 }, { "wallStiffness", Count::Walls, 8 },
  { "wallElastic", Count::Walls, 8 }, { "oldWallStart", Count::NPlus1, 4 }, { "oldWallIndex", Count::Walls, 4 },
  { "oldWallTouching", Count::Walls, 4 }, { "oldWallSpring", Count::Walls3, 8 },
  { "oldWallRolling", Count::WallsRolling3, 8 },
  { "bondI", Count::Bonds, 4 }, { "bondJ", Count::Bonds, 4 }, { "bondRadius", Count::Bonds, 8 },
  { "bondKn", Count::Bonds, 8 }, { "bondKs", Count::Bonds, 8 }, { "bondTensileStrength", Count::Bonds, 8 },
  { "bondCohesion", Count::Bonds, 8 }, { "bondTanFriction", Count::Bonds, 8 },
  { "bondMomentContribution", Count::Bonds, 8 }, { "bondSoftening", Count::Bonds, 8 },
  { "bondDamage", Count::Bonds, 8 },
  { "bondNormalForce", Count::Bonds, 8 }, { "bondShearForce", Count::Bonds3, 8 },
  { "bondTwistingMoment", Count::Bonds, 8 }, { "bondBendingMoment", Count::Bonds3, 8 },
  { "bondFailure", Count::Bonds, 4 }, { "bondFailureTime", Count::Bonds, 8 },
  { "bondFailurePosition", Count::Bonds3, 8 }, { "bondFailureNormal", Count::Bonds3, 8 },
  { "bondForce", Count::Bonds3, 8 }, { "bondTorqueI", Count::Bonds3, 8 }, { "bondTorqueJ", Count::Bonds3, 8 },
  { "breakEnergy", Count::Bonds, 8 },
  { "bondAdjacencyStart", Count::NPlus1, 4 }, { "bondAdjacency", Count::Bonds2, 4 },
  { "ctl", Count::Control, 4 }, { "walls", Count::WallData, 8 }, { "clock", Count::Clock, 8 },
  { "indirect", Count::Indirect, 4 }, { "partialSums", Count::Partial, 8 },
};

Group groupOf(Count c)
{
  switch (c) {
    case Count::Pairs: case Count::Pairs3: case Count::PairsRolling3: case Count::Adjacency:
      return Group::Pairs;
    case Count::Walls: case Count::Walls3: case Count::WallsRolling3:
      return Group::Walls;
    default:
      return Group::Fixed;
  }
}

std::uint32_t groupsFor(std::uint64_t items, std::uint32_t size)
{
  return static_cast<std::uint32_t>((items + size - 1) / size);
}

constexpr std::uint32_t kGroupSize = GROUP_SIZE;
constexpr std::uint32_t kDispatchX = DISPATCH_X;
constexpr std::uint64_t kStagingBytes = 32ull << 20;
constexpr std::int64_t kMaxStepsPerSubmission = 64;
constexpr std::uint64_t kWallsStagingOffset = 1024; // bytes: after the counters (0), clock (256) and kinetic energy (512)

struct PushParams {
  std::uint64_t params;
};
struct PushParamsArg {
  std::uint64_t params;
  std::uint32_t arg;
  std::uint32_t pad;
};
struct PushSort {
  std::uint64_t params, keysIn, valuesIn, keysOut, valuesOut;
  std::uint32_t shift, count;
};
struct PushScan {
  std::uint64_t params, data, result, blocks;
  std::uint32_t count, pad;
};
struct PushReduce {
  std::uint64_t params, data, result;
  std::uint32_t count, pad;
};

/// The sizes the arrays are allocated for.
struct Sizes {
  std::uint64_t n, pairs, walls, bonds, cells, tiles, scanBlocks, partial;
  bool rolling;
};

std::uint64_t elements(Count c, const Sizes& s)
{
  switch (c) {
    case Count::N: return s.n;
    case Count::N3: return 3 * s.n;
    case Count::NPlus1: return s.n + 1;
    case Count::Pairs: return s.pairs;
    case Count::Pairs3: return 3 * s.pairs;
    case Count::PairsRolling3: return s.rolling ? 3 * s.pairs : 1;
    case Count::Adjacency: return 2 * s.pairs;
    case Count::Walls: return s.walls;
    case Count::Walls3: return 3 * s.walls;
    case Count::WallsRolling3: return s.rolling ? 3 * s.walls : 1;
    case Count::Bonds: return std::max<std::uint64_t>(s.bonds, 1);
    case Count::Bonds3: return 3 * std::max<std::uint64_t>(s.bonds, 1);
    case Count::Bonds2: return 2 * std::max<std::uint64_t>(s.bonds, 1);
    case Count::Cells: return s.cells;
    case Count::Histogram: return 16 * s.tiles;
    case Count::ScanBlocks: return s.scanBlocks;
    case Count::Control: return CTL_COUNT;
    case Count::WallData: return 6 * WALL_STRIDE;
    case Count::Clock: return 4;
    case Count::Indirect: return IND_COUNT;
    case Count::Partial: return s.partial;
  }
  return 0;
}


/// Moves the pieces between host and device arrays through the staging buffer, as many
/// per submission as fit (a piece larger than the staging buffer goes in parts).
void moveThroughStaging(vk::Device& device, vk::Buffer& staging, std::vector<Transfer>& items, bool toDevice)
{
  const std::uint64_t capacity = staging.bytes;
  std::size_t next = 0;
  std::uint64_t pieceOffset = 0;
  while (next < items.size()) {
    struct Part {
      std::size_t item;
      std::uint64_t hostOffset, stagingOffset, bytes;
    };
    std::vector<Part> parts;
    std::uint64_t used = 0;
    while (next < items.size() && used < capacity) {
      const Transfer& t = items[next];
      const std::uint64_t bytes = std::min(t.bytes - pieceOffset, capacity - used);
      parts.push_back({ next, pieceOffset, used, bytes });
      used += (bytes + 15) / 16 * 16;
      pieceOffset += bytes;
      if (pieceOffset == t.bytes) {
        ++next;
        pieceOffset = 0;
      }
    }
    char* stage = static_cast<char*>(staging.mapped);
    if (toDevice) {
      for (const Part& p : parts) {
        std::memcpy(stage + p.stagingOffset, static_cast<const char*>(items[p.item].host) + p.hostOffset, p.bytes);
      }
    }
    device.submit([&](VkCommandBuffer cb) {
      for (const Part& p : parts) {
        const Transfer& t = items[p.item];
        if (toDevice) {
          const VkBufferCopy region{ p.stagingOffset, t.offset + p.hostOffset, p.bytes };
          device.api().vkCmdCopyBuffer(cb, staging.buffer, t.buffer, 1, &region);
        } else {
          const VkBufferCopy region{ t.offset + p.hostOffset, p.stagingOffset, p.bytes };
          device.api().vkCmdCopyBuffer(cb, t.buffer, staging.buffer, 1, &region);
        }
      }
    });
    if (!toDevice) {
      for (const Part& p : parts) {
        std::memcpy(static_cast<char*>(items[p.item].host) + p.hostOffset, stage + p.stagingOffset, p.bytes);
      }
    }
  }
}

} // namespace

struct VulkanBackend::Array {
  ArraySpec spec;
  std::uint64_t vk::Params::*member = nullptr;
  vk::Buffer buffer;
};

// ---------------------------------------------------------------------------------------
// Set-up

VulkanBackend::VulkanBackend(Model& model, const ContactModel& contactModel, double timestep,
                             bool tightLists)
  : model_(model)
  , contactModel_(contactModel)
  , timestep_(timestep)
{
  device_ = vk::Device::open();
  const Particles& p = model.particles;
  if (p.size() >= (1ull << 31) / 3) {
    throw vk::Unavailable("the model has too many particles for 32-bit indices");
  }
  // The initial lists (and the import of the stored history by global ids) are the CPU
  // backend's; it stays as the host mirror that sync() fills.
  host_.reset(new CpuBackend(model, contactModel, timestep));
  n_ = static_cast<std::uint32_t>(p.size());
  bonds_ = static_cast<std::uint32_t>(model.bonds.size());
  rolling_ = contactModel.rollingFriction > 0.0;
  const ContactState& st = host_->state();
  pairs_ = static_cast<std::uint32_t>(st.pairI.size());
  adjacency_ = static_cast<std::uint32_t>(st.adjacency.size());
  wallEntries_ = static_cast<std::uint32_t>(st.wallSlot.size());
  pairCapacity_ = tightLists ? pairs_ + 1 : pairs_ + pairs_ / 4 + n_ / 2 + 1024;
  wallCapacity_ = tightLists ? wallEntries_ + 1 : wallEntries_ + wallEntries_ / 4 + n_ / 16 + 256;

  // Parameters that stay for the run.
  vk::Params& q = params_;
  const Domain& d = model.domain;
  q.dt = timestep;
  q.skin = st.skinDistance;
  q.alpha = model.solver.settlingDamping;
  q.gravityX = model.gravity.x();
  q.gravityY = model.gravity.y();
  q.gravityZ = model.gravity.z();
  q.originX = d.origin.x();
  q.originY = d.origin.y();
  q.originZ = d.origin.z();
  q.sizeX = d.size.x();
  q.sizeY = d.size.y();
  q.sizeZ = d.size.z();
  q.youngsModulus = contactModel.youngsModulus;
  q.poissonsRatio = contactModel.poissonsRatio;
  q.dampingCoefficient = contactModel.dampingCoefficient;
  q.friction = contactModel.friction;
  q.rollingFriction = contactModel.rollingFriction;
  q.smallestRadius = st.smallestRadius;
  q.n = n_;
  q.periodicMask = (d.periodic[0] ? 1u : 0u) | (d.periodic[1] ? 2u : 0u) | (d.periodic[2] ? 4u : 0u);
  q.planar = d.section2D ? 1u : 0u;
  q.plain = (!d.periodic[0] && !d.periodic[1] && !d.periodic[2] && !d.section2D) ? 1u : 0u;
  q.law = contactModel.law == ContactLaw::HertzMindlin ? 0u : 1u;
  q.rolling = rolling_ ? 1u : 0u;
  q.bondCount = bonds_;
  // The grids of the neighbour search (one per size class), as the CPU builds them.
  std::uint64_t totalCells = 1;
  if (n_ > 0) {
    const auto [rmin, rmax] = std::minmax_element(p.radius.begin(), p.radius.end());
    const SizeClassGrids grids(d, *rmin, *rmax);
    totalCells = 0;
    for (int c = 0; c < 4; ++c) {
      q.classMaxRadius[c] = 0.0;
      q.classCount[c] = 0;
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int c = sizeClassOf(p.radius[i], *rmin);
      q.classMaxRadius[c] = std::max(q.classMaxRadius[c], p.radius[i]);
      ++q.classCount[c];
    }
    for (int c = 0; c < 4; ++c) {
      const std::array<long, 3> cells = grids.cellCounts(c);
      q.classOffset[c] = static_cast<std::uint32_t>(totalCells);
      std::uint64_t count = 1;
      for (int a = 0; a < 3; ++a) {
        q.classCells[3 * c + a] = static_cast<std::uint32_t>(cells[a]);
        const bool inPlane = !(d.section2D && a == 2);
        q.classInverseEdge[3 * c + a] = inPlane ? static_cast<double>(cells[a]) / d.size[a] : 0.0;
        count *= static_cast<std::uint64_t>(cells[a]);
      }
      if (q.classCount[c] > 0) {
        totalCells += count;
      }
    }
    totalCells = std::max<std::uint64_t>(totalCells, 1);
  }
  if (totalCells >= (1ull << 32)) {
    throw vk::Unavailable("the neighbour grids have too many cells for 32-bit keys");
  }
  q.totalCells = static_cast<std::uint32_t>(totalCells);
  q.sortTiles = std::max<std::uint32_t>(1, groupsFor(n_, SORT_TILE));
  std::uint32_t bits = 1;
  while (bits < 32 && (std::uint64_t(1) << bits) < totalCells) {
    ++bits;
  }
  sortPasses_ = (bits + 3) / 4;
  sortPasses_ += sortPasses_ % 2; // an even number of passes leaves the result in keysA
  try {
    allocate();
    upload();
  } catch (...) {
    release(); // a failed allocation leaves nothing behind on the device
    throw;
  }
}

VulkanBackend::~VulkanBackend()
{
  release();
}

void VulkanBackend::release()
{
  if (device_) {
    for (Array& a : arrays_) {
      device_->destroy(a.buffer);
    }
    arrays_.clear();
    device_->destroy(paramsBuffer_);
    device_->destroy(staging_);
  }
}

std::string VulkanBackend::path() const
{
  return "GPU Vulkan: " + device_->name();
}

DeviceMemory VulkanBackend::deviceMemory() const
{
  DeviceMemory m;
  double particles = 0.0, bonds = 0.0, pairs = 0.0;
  m.total = paramsBuffer_.bytes;
  for (const Array& a : arrays_) {
    m.total += a.buffer.bytes;
    const double bytes = static_cast<double>(a.buffer.bytes);
    switch (a.spec.count) {
      case Count::Bonds: case Count::Bonds3: case Count::Bonds2:
        bonds += bytes;
        break;
      case Count::Pairs: case Count::Pairs3: case Count::PairsRolling3: case Count::Adjacency:
        pairs += bytes;
        break;
      case Count::Control: case Count::WallData: case Count::Clock: case Count::Indirect:
      case Count::Walls: case Count::Walls3: case Count::WallsRolling3:
        break; // fixed size, or the walls' contacts (a surface layer)
      default:
        particles += bytes; // per particle, and the grids and scan blocks that scale with it
        break;
    }
  }
  m.perParticle = n_ ? particles / n_ : 0.0;
  m.perBond = bonds_ ? bonds / bonds_ : 0.0;
  m.perPair = pairCapacity_ ? pairs / pairCapacity_ : 0.0;
  m.pairSlots = pairCapacity_;
  return m;
}

void VulkanBackend::allocate()
{
  Sizes s{ n_, pairCapacity_, wallCapacity_, bonds_, params_.totalCells, params_.sortTiles,
           groupsFor(std::uint64_t(n_) + 1, SCAN_BLOCK), 2 * std::uint64_t(groupsFor(n_, 1024)) + 4,
           rolling_ };
  // The arrays of the parameter block, each with its size.
  std::map<std::string, std::uint64_t vk::Params::*> members;
  for (std::size_t f = 0; f < vk::addressFieldCount(); ++f) {
    members[vk::addressFields()[f].name] = vk::addressFields()[f].member;
  }
  std::uint64_t total = 0;
  for (const ArraySpec& spec : kArrays) {
    if (!members.count(spec.name)) {
      throw std::logic_error(std::string("VulkanBackend: no parameter for array ") + spec.name);
    }
    total += std::max<std::uint64_t>(16, elements(spec.count, s) * spec.elementBytes);
  }
  if (std::size(kArrays) != vk::addressFieldCount()) {
    throw std::logic_error("VulkanBackend: the array table and the parameter block differ");
  }
  const std::uint64_t budget = device_->memoryBytes() / 10 * 9;
  if (total > budget) {
    auto size = [](std::uint64_t bytes) {
      std::ostringstream out;
      if (bytes < (1ull << 20)) {
        out << (bytes + 1023) / 1024 << " KiB";
      } else {
        out << (bytes + (1ull << 19)) / (1ull << 20) << " MiB";
      }
      return out.str();
    };
    throw vk::Unavailable("too little device memory: the model needs " + size(total) + ", " +
                          device_->name() + " has " + size(device_->memoryBytes()) +
                          " (a run may use 90 % of it)");
  }
  arrays_.reserve(std::size(kArrays));
  for (const ArraySpec& spec : kArrays) {
    Array a;
    a.spec = spec;
    a.member = members[spec.name];
    a.buffer = device_->createBuffer(elements(spec.count, s) * spec.elementBytes);
    params_.*(a.member) = a.buffer.address;
    arrays_.push_back(a);
  }
  for (const Array& a : arrays_) {
    const std::string name = a.spec.name;
    if (name == "ctl") {
      control_ = &a.buffer;
    } else if (name == "indirect") {
      indirect_ = &a.buffer;
    } else if (name == "clock") {
      clock_ = &a.buffer;
    } else if (name == "walls") {
      walls_ = &a.buffer;
    } else if (name == "partialSums") {
      partialSums_ = &a.buffer;
    }
  }
  paramsBuffer_ = device_->createBuffer(sizeof(vk::Params));
  staging_ = device_->createStaging(std::min<std::uint64_t>(kStagingBytes, std::max<std::uint64_t>(total, 1 << 20)));
  // Every array starts at zero (counts end with a 0 the kernels never write).
  device_->submit([&](VkCommandBuffer cb) {
    for (Array& a : arrays_) {
      device_->api().vkCmdFillBuffer(cb, a.buffer.buffer, 0, VK_WHOLE_SIZE, 0);
    }
  });
  params_.pairCapacity = pairCapacity_;
  params_.adjacencyCapacity = 2 * pairCapacity_;
  params_.wallCapacity = wallCapacity_;
}

void VulkanBackend::grow(bool pairs, bool walls, std::uint32_t neededPairs, std::uint32_t neededWalls)
{
  const std::uint64_t newPairs = pairs ? std::uint64_t(neededPairs) + neededPairs / 4 + 1024 : pairCapacity_;
  const std::uint64_t newWalls = walls ? std::uint64_t(neededWalls) + neededWalls / 4 + 256 : wallCapacity_;
  if (newPairs >= (1ull << 31) || newWalls >= (1ull << 31)) {
    throw std::runtime_error("GPU solver: the neighbour list outgrew 32-bit indices; run on the CPU.");
  }
  Sizes s{ n_, newPairs, newWalls, bonds_, params_.totalCells, params_.sortTiles, 0, 0, rolling_ };
  // The bigger buffers first (nothing changes if one cannot be had), then the live lists
  // copied into them.
  std::vector<std::pair<Array*, vk::Buffer>> bigger;
  try {
    for (Array& a : arrays_) {
      const Group g = groupOf(a.spec.count);
      if ((g == Group::Pairs && pairs) || (g == Group::Walls && walls)) {
        bigger.emplace_back(&a, device_->createBuffer(elements(a.spec.count, s) * a.spec.elementBytes));
      }
    }
  } catch (const vk::Unavailable& e) {
    for (auto& b : bigger) {
      device_->destroy(b.second);
    }
    throw std::runtime_error(std::string("GPU solver: growing the contact lists failed (") + e.what() +
                             "); run on the CPU (GPU Solver off).");
  }
  device_->submit([&](VkCommandBuffer cb) {
    for (auto& b : bigger) {
      VkBufferCopy region{ 0, 0, std::min(b.first->buffer.bytes, b.second.bytes) };
      device_->api().vkCmdCopyBuffer(cb, b.first->buffer.buffer, b.second.buffer, 1, &region);
    }
  });
  for (auto& b : bigger) {
    device_->destroy(b.first->buffer);
    b.first->buffer = b.second;
    params_.*(b.first->member) = b.second.address;
  }
  pairCapacity_ = static_cast<std::uint32_t>(newPairs);
  wallCapacity_ = static_cast<std::uint32_t>(newWalls);
  params_.pairCapacity = pairCapacity_;
  params_.adjacencyCapacity = 2 * pairCapacity_;
  params_.wallCapacity = wallCapacity_;
}

void VulkanBackend::setStageParameters()
{
  const LoadTestState& t = model_.test;
  const LoadTestSettings& s = t.settings;
  vk::Params& q = params_;
  const bool testMode = s.mode != TestMode::Off;
  // dem::controlWalls acts while a test runs (not Off, not Idle).
  q.testRunning = (testMode && t.stage != TestStage::Idle) ? 1u : 0u;
  q.axis = static_cast<std::uint32_t>(s.axis);
  q.servoAll = (t.stage == TestStage::Consolidate || s.mode == TestMode::Isotropic) ? 1u : 0u;
  q.servoSides = (s.mode == TestMode::Triaxial && t.stage != TestStage::Consolidate) ? 1u : 0u;
  q.platenMoving = t.stage == TestStage::Shear ? 1u : 0u;
  q.tension = (q.testRunning && s.mode == TestMode::Tension) ? 1u : 0u;
  const double platenSpeed = s.strainRate * t.initialLength[s.axis];
  q.platenVelocity = s.mode == TestMode::Tension ? platenSpeed : -platenSpeed;
  q.confiningStress = s.confiningStress;
  q.servoAlpha = s.servoAlpha;
  q.alpha = localDamping(t, model_.solver.settlingDamping); // Consolidation Damping while consolidating
  // During a press test the side walls are frictionless and the platens (the walls on
  // the test axis) have the test's Platen Friction (CpuBackend::computeForces).
  q.wallFriction = testMode ? 0.0 : contactModel_.friction;
  q.platenFriction = testMode ? s.platenFriction : contactModel_.friction;
  q.wallRollingFriction = testMode ? 0.0 : contactModel_.rollingFriction;
  q.wallRollingOn = q.wallRollingFriction > 0.0 ? 1u : 0u;
  q.lengthFromWalls = 0;
  for (int k = 0; k < 3; ++k) {
    const bool platenAxis = testMode && k == s.axis;
    if (model_.walls[2 * k].active || model_.walls[2 * k + 1].active || platenAxis) {
      q.lengthFromWalls |= 1u << k;
    }
  }
}

bool VulkanBackend::servoNeedsParticles() const
{
  // A servo on a specimen with an unwalled side would need the spread of the particle
  // centres (dem::specimenLengths) every step; the load tests never ask for it (Triaxial
  // and Isotropic have walls on every axis), and such a step runs on the host.
  const vk::Params& q = params_;
  if (!q.testRunning || !(q.servoAll || q.servoSides)) {
    return false;
  }
  for (int k = 0; k < 3; ++k) {
    if (!(q.lengthFromWalls & (1u << k)) && !(q.planar && k == 2)) {
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Transfers

const vk::Buffer& VulkanBackend::array(const char* name) const
{
  for (const Array& a : arrays_) {
    if (std::strcmp(a.spec.name, name) == 0) {
      return a.buffer;
    }
  }
  throw std::logic_error(std::string("VulkanBackend: no array ") + name);
}

namespace {
template <class T> Transfer piece(std::vector<T>& v, const vk::Buffer& b, std::uint64_t count)
{
  return { v.data(), count * sizeof(T), b.buffer, 0 };
}
} // namespace

/// Host arrays whose device copies have another element type (32-bit indices and flags),
/// and the walls and clock, which the device keeps as flat doubles.
struct VulkanBackend::Images {
  std::vector<std::uint32_t> adjacencyStart, adjacency, wallIndex, wallTouching, failure;
  std::vector<double> walls, clock;
  // The pairs' forces as the device holds them (the host keeps them in dem::PairResult
  // rows). The pairs' torques are not moved: the device recomputes them, as the host does,
  // before its gather reads them, and the gather reads no pair without a normal force.
  std::vector<Vec3> pairForce;
};

std::vector<vk::Transfer> VulkanBackend::dynamicState(Images& im)
{
  // Host arrays sized as the device lists are now.
  Particles& p = model_.particles;
  ContactState& st = host_->state();
  Bonds& b = model_.bonds;
  const std::size_t n = n_;
  st.pairI.resize(pairs_);
  st.pairJ.resize(pairs_);
  st.pairConstants.resize(pairs_);
  st.pairSpring.resize(pairs_);
  st.pairRolling.resize(rolling_ ? pairs_ : 0);
  st.pairResult.resize(pairs_);
  st.pairRollingTorque.resize(rolling_ ? pairs_ : 0);
  im.pairForce.resize(pairs_);
  st.pairNormal.resize(pairs_);
  st.pairLive.assign(pairs_, 1); // the device keeps no such flag: the host checks every pair
  st.wallSlot.resize(wallEntries_);
  st.wallConstants.resize(wallEntries_);
  st.wallSpring.resize(wallEntries_);
  st.wallRolling.resize(rolling_ ? wallEntries_ : 0);
  st.wallForce.resize(wallEntries_);
  st.wallNormal.resize(wallEntries_);
  st.wallStiffness.resize(wallEntries_);
  st.wallElastic.resize(wallEntries_);
  im.adjacencyStart.resize(n + 1);
  im.adjacency.resize(adjacency_);
  im.wallIndex.resize(wallEntries_);
  im.wallTouching.resize(wallEntries_);
  im.failure.resize(bonds_);
  im.walls.resize(6 * WALL_STRIDE);
  im.clock.resize(4);
  std::vector<Transfer> items;
  auto add = [&](auto& v, const char* name, std::uint64_t count) {
    if (count > 0) {
      items.push_back(piece(v, array(name), count));
    }
  };
  add(p.position, "position", n);
  add(p.velocity, "velocity", n);
  add(p.angularVelocity, "angularVelocity", n);
  add(p.displacement, "displacement", n);
  add(p.force, "force", n);
  add(p.torque, "torque", n);
  add(st.undampedForce, "undampedForce", n);
  add(st.positionAtBuild, "positionAtBuild", n);
  add(im.adjacencyStart, "adjacencyStart", n + 1);
  add(im.adjacency, "adjacency", adjacency_);
  add(st.pairI, "pairI", pairs_);
  add(st.pairJ, "pairJ", pairs_);
  add(st.pairConstants, "pairConstants", pairs_);
  add(st.pairSpring, "pairSpring", pairs_);
  if (rolling_) {
    add(st.pairRolling, "pairRolling", pairs_);
  }
  add(im.pairForce, "pairForce", pairs_);
  add(st.pairNormal, "pairNormal", pairs_);
  add(st.wallStart, "wallStart", n + 1);
  add(st.wallSlot, "wallSlot", wallEntries_);
  add(im.wallIndex, "wallIndex", wallEntries_);
  add(im.wallTouching, "wallTouching", wallEntries_);
  add(st.wallConstants, "wallConstants", wallEntries_);
  add(st.wallSpring, "wallSpring", wallEntries_);
  if (rolling_) {
    add(st.wallRolling, "wallRolling", wallEntries_);
  }
  add(st.wallForce, "wallForce", wallEntries_);
  add(st.wallNormal, "wallNormal", wallEntries_);
  add(st.wallStiffness, "wallStiffness", wallEntries_);
  add(st.wallElastic, "wallElastic", wallEntries_);
  add(b.normalForce, "bondNormalForce", bonds_);
  add(b.shearForce, "bondShearForce", bonds_);
  add(b.twistingMoment, "bondTwistingMoment", bonds_);
  add(b.bendingMoment, "bondBendingMoment", bonds_);
  add(b.damage, "bondDamage", bonds_);
  add(im.failure, "bondFailure", bonds_);
  add(b.failureTime, "bondFailureTime", bonds_);
  add(b.failurePosition, "bondFailurePosition", bonds_);
  add(b.failureNormal, "bondFailureNormal", bonds_);
  add(st.bondForce, "bondForce", bonds_);
  add(st.bondTorqueI, "bondTorqueI", bonds_);
  add(st.bondTorqueJ, "bondTorqueJ", bonds_);
  if (countDissipation_) {
    st.dampingWork.resize(n);
    st.breakEnergy.resize(bonds_);
    add(st.dampingWork, "dampingWork", n);
    add(st.breakEnergy, "breakEnergy", bonds_);
  }
  add(im.walls, "walls", im.walls.size());
  add(im.clock, "clock", im.clock.size());
  return items;
}

void VulkanBackend::upload()
{
  Particles& p = model_.particles;
  ContactState& st = host_->state();
  Bonds& b = model_.bonds;
  const std::size_t n = n_;
  pairs_ = static_cast<std::uint32_t>(st.pairI.size());
  adjacency_ = static_cast<std::uint32_t>(st.adjacency.size());
  wallEntries_ = static_cast<std::uint32_t>(st.wallSlot.size());
  if (pairs_ > pairCapacity_ || wallEntries_ > wallCapacity_) {
    grow(pairs_ > pairCapacity_, wallEntries_ > wallCapacity_, pairs_, wallEntries_);
  }
  // The state that changes as the run goes, in the device's element types.
  Images im;
  std::vector<Transfer> items = dynamicState(im);
  std::copy(st.adjacencyStart.begin(), st.adjacencyStart.end(), im.adjacencyStart.begin());
  std::copy(st.adjacency.begin(), st.adjacency.end(), im.adjacency.begin());
  for (std::size_t k = 0; k < pairs_; ++k) {
    im.pairForce[k] = st.pairResult[k].force;
  }
  std::copy(st.wallIndex.begin(), st.wallIndex.end(), im.wallIndex.begin());
  std::copy(st.wallTouching.begin(), st.wallTouching.end(), im.wallTouching.begin());
  std::copy(b.failure.begin(), b.failure.end(), im.failure.begin());
  for (int w = 0; w < 6; ++w) {
    const Wall& wall = model_.walls[w];
    double* x = &im.walls[WALL_STRIDE * w];
    x[WALL_POSITION] = wall.position;
    x[WALL_VELOCITY] = wall.velocity;
    x[WALL_ACTIVE] = wall.active ? 1.0 : 0.0;
    x[WALL_FORCE] = wall.force.x();
    x[WALL_FORCE + 1] = wall.force.y();
    x[WALL_FORCE + 2] = wall.force.z();
    x[WALL_STIFFNESS] = wall.contactStiffness;
    x[WALL_ELASTIC] = wall.elasticForce;
    x[WALL_CONTACTS] = static_cast<double>(wall.contacts);
    x[WALL_POSITION_AT_BUILD] = st.wallPositionAtBuild[w];
    x[WALL_ACTIVE_AT_BUILD] = st.wallActiveAtBuild[w] ? 1.0 : 0.0;
  }
  im.clock[CLOCK_TIME] = model_.clock.time;
  auto add = [&](auto& v, const char* name, std::uint64_t count) {
    if (count > 0) {
      items.push_back(piece(v, array(name), count));
    }
  };
  // What stays for the run, and what the device derives from the lists.
  add(p.radius, "radius", n);
  add(p.mass, "mass", n);
  add(p.inertia, "inertia", n);
  add(st.inverseMass, "inverseMass", n);
  add(st.inverseInertia, "inverseInertia", n);
  add(p.flags, "flags", n);
  std::vector<std::uint32_t> sizeClass(n);
  for (std::size_t i = 0; i < n; ++i) {
    sizeClass[i] = static_cast<std::uint32_t>(sizeClassOf(p.radius[i], st.smallestRadius));
  }
  add(sizeClass, "sizeClass", n);
  std::vector<std::uint32_t> pairStart(n + 1, 0); // the pair list's CSR
  for (std::uint32_t i : st.pairI) {
    ++pairStart[i + 1];
  }
  for (std::size_t i = 0; i < n; ++i) {
    pairStart[i + 1] += pairStart[i];
  }
  std::vector<std::uint32_t> partners(adjacency_); // each gather entry's partner slot
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t e = st.adjacencyStart[i]; e < st.adjacencyStart[i + 1]; ++e) {
      const std::size_t k = st.adjacency[e] >> 1;
      partners[e] = (st.adjacency[e] & 1u) ? st.pairI[k] : st.pairJ[k];
    }
  }
  add(pairStart, "pairStart", n + 1);
  add(partners, "partners", partners.size());
  std::vector<double> tanFriction(bonds_);
  for (std::size_t k = 0; k < bonds_; ++k) {
    tanFriction[k] = std::tan(b.frictionAngle[k]); // as dem::bondFailure computes it
  }
  std::vector<std::uint32_t> bondAdjacencyStart(st.bondAdjacencyStart.begin(), st.bondAdjacencyStart.end());
  std::vector<std::uint32_t> bondAdjacency(st.bondAdjacency.begin(), st.bondAdjacency.end());
  add(st.bondI, "bondI", bonds_);
  add(st.bondJ, "bondJ", bonds_);
  add(b.radius, "bondRadius", bonds_);
  add(b.normalStiffness, "bondKn", bonds_);
  add(b.shearStiffness, "bondKs", bonds_);
  add(b.tensileStrength, "bondTensileStrength", bonds_);
  add(b.cohesion, "bondCohesion", bonds_);
  add(tanFriction, "bondTanFriction", bonds_);
  add(b.momentContribution, "bondMomentContribution", bonds_);
  add(b.softening, "bondSoftening", bonds_);
  add(bondAdjacencyStart, "bondAdjacencyStart", bonds_ ? n + 1 : 0);
  add(bondAdjacency, "bondAdjacency", bondAdjacency.size());
  // Control: the list sizes, and the pair kernel's dispatch.
  std::vector<std::uint32_t> ctl(CTL_COUNT, 0);
  ctl[CTL_PAIRS] = pairs_;
  ctl[CTL_ADJACENCY] = adjacency_;
  ctl[CTL_WALL_ENTRIES] = wallEntries_;
  std::vector<std::uint32_t> indirect(IND_COUNT, 0);
  const std::uint32_t groups = groupsFor(pairs_, kGroupSize);
  indirect[IND_PAIRS] = std::min(groups, kDispatchX);
  indirect[IND_PAIRS + 1] = groups ? groupsFor(groups, kDispatchX) : 0;
  indirect[IND_PAIRS + 2] = 1;
  add(ctl, "ctl", ctl.size());
  add(indirect, "indirect", indirect.size());
  moveThroughStaging(*device_, staging_, items, true);
  synced_ = true;
}

void VulkanBackend::download()
{
  Images im;
  std::vector<Transfer> items = dynamicState(im);
  moveThroughStaging(*device_, staging_, items, false);
  // Back into the CPU layout.
  ContactState& st = host_->state();
  st.adjacencyStart.assign(im.adjacencyStart.begin(), im.adjacencyStart.end());
  st.adjacency.assign(im.adjacency.begin(), im.adjacency.end());
  for (std::size_t k = 0; k < pairs_; ++k) {
    st.pairResult[k].force = im.pairForce[k];
  }
  st.wallIndex.assign(im.wallIndex.begin(), im.wallIndex.end());
  st.wallTouching.assign(im.wallTouching.begin(), im.wallTouching.end());
  st.touching.assign(n_, 0);
  model_.bonds.failure.assign(im.failure.begin(), im.failure.end());
  for (int w = 0; w < 6; ++w) {
    Wall& wall = model_.walls[w];
    const double* x = &im.walls[WALL_STRIDE * w];
    wall.position = x[WALL_POSITION];
    wall.velocity = x[WALL_VELOCITY];
    wall.force = Vec3(x[WALL_FORCE], x[WALL_FORCE + 1], x[WALL_FORCE + 2]);
    wall.contactStiffness = x[WALL_STIFFNESS];
    wall.elasticForce = x[WALL_ELASTIC];
    wall.contacts = static_cast<std::int64_t>(x[WALL_CONTACTS]);
    st.wallPositionAtBuild[w] = x[WALL_POSITION_AT_BUILD];
    st.wallActiveAtBuild[w] = x[WALL_ACTIVE_AT_BUILD] != 0.0;
  }
  model_.clock.time = im.clock[CLOCK_TIME];
}

void VulkanBackend::recordControlReadback(VkCommandBuffer cb)
{
  // The counters and the clock to the start of the staging buffer.
  VkBufferCopy c{ 0, 0, CTL_COUNT * 4 };
  device_->api().vkCmdCopyBuffer(cb, control_->buffer, staging_.buffer, 1, &c);
  VkBufferCopy t{ 0, 256, 32 };
  device_->api().vkCmdCopyBuffer(cb, clock_->buffer, staging_.buffer, 1, &t);
}

void VulkanBackend::readControlReadback(std::uint32_t* ctl)
{
  std::memcpy(ctl, staging_.mapped, CTL_COUNT * 4);
  double time = 0.0;
  std::memcpy(&time, static_cast<const char*>(staging_.mapped) + 256 + 8 * CLOCK_TIME, 8);
  model_.clock.time = time;
}

// ---------------------------------------------------------------------------------------
// Recording

const vk::Pipeline& VulkanBackend::pipeline(const char* kernel, std::uint32_t pushBytes)
{
  // Kernel names are string literals: their addresses identify them.
  auto found = pipelines_.find(kernel);
  if (found == pipelines_.end()) {
    found = pipelines_.emplace(kernel, &device_->pipeline(shaders::module(kernel), pushBytes)).first;
  }
  return *found->second;
}

void VulkanBackend::dispatch(VkCommandBuffer cb, const char* kernel, const void* push,
                             std::uint32_t pushBytes, std::uint32_t groupsX, std::uint32_t groupsY)
{
  const vk::Api& api = device_->api();
  const vk::Pipeline& pl = pipeline(kernel, pushBytes);
  api.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pl.pipeline);
  api.vkCmdPushConstants(cb, pl.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, push);
  api.vkCmdDispatch(cb, groupsX, groupsY, 1);
  device_->barrier(cb);
}

void VulkanBackend::dispatchIndirect(VkCommandBuffer cb, const char* kernel, const void* push,
                                     std::uint32_t pushBytes, std::uint32_t slot)
{
  const vk::Api& api = device_->api();
  const vk::Pipeline& pl = pipeline(kernel, pushBytes);
  api.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pl.pipeline);
  api.vkCmdPushConstants(cb, pl.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, push);
  api.vkCmdDispatchIndirect(cb, indirect_->buffer, 4 * slot);
  device_->barrier(cb);
}

void VulkanBackend::dispatchItems(VkCommandBuffer cb, const char* kernel, std::uint64_t items)
{
  const PushParams push{ paramsBuffer_.address };
  const std::uint32_t groups = groupsFor(items, kGroupSize);
  if (groups == 0) {
    return;
  }
  dispatch(cb, kernel, &push, sizeof(push), std::min(groups, kDispatchX), groupsFor(groups, kDispatchX));
}

void VulkanBackend::recordScan(VkCommandBuffer cb, std::uint64_t data, std::uint64_t result,
                               std::uint32_t scanSlot, std::uint32_t oneSlot)
{
  const PushScan push{ paramsBuffer_.address, data, result, params_.scanBlocks, n_ + 1, 0 };
  dispatchIndirect(cb, "scan_reduce", &push, sizeof(push), scanSlot);
  dispatchIndirect(cb, "scan_blocks", &push, sizeof(push), oneSlot);
  dispatchIndirect(cb, "scan_apply", &push, sizeof(push), scanSlot);
}

void VulkanBackend::recordRebuild(VkCommandBuffer cb)
{
  const std::uint64_t P = paramsBuffer_.address;
  const PushParams push{ P };
  // Full rebuild: cell keys, radix sort, cell ranges, counts, starts, capacity check, the
  // old list kept, fill, gather lists, history carried over.
  dispatchIndirect(cb, "cell_keys", &push, sizeof(push), IND_FULL_PARTICLES);
  for (std::uint32_t pass = 0; pass < sortPasses_; ++pass) {
    const bool even = pass % 2 == 0;
    const PushSort sort{ P,
                         even ? params_.keysA : params_.keysB, even ? params_.valuesA : params_.valuesB,
                         even ? params_.keysB : params_.keysA, even ? params_.valuesB : params_.valuesA,
                         4 * pass, n_ };
    dispatchIndirect(cb, "sort_histogram", &sort, sizeof(sort), IND_FULL_TILES);
    dispatchIndirect(cb, "sort_scan", &sort, sizeof(sort), IND_FULL_ONE);
    dispatchIndirect(cb, "sort_scatter", &sort, sizeof(sort), IND_FULL_TILES);
  }
  const PushParamsArg clear{ P, 1, 0 };
  const PushParamsArg ranges{ P, 0, 0 };
  dispatchIndirect(cb, "cell_ranges", &clear, sizeof(clear), IND_FULL_CELLS);
  dispatchIndirect(cb, "cell_ranges", &ranges, sizeof(ranges), IND_FULL_PARTICLES);
  dispatchIndirect(cb, "neighbour_count", &push, sizeof(push), IND_FULL_PARTICLES);
  recordScan(cb, params_.fullCount, params_.fullScan, IND_FULL_SCAN, IND_FULL_ONE);
  recordScan(cb, params_.halfCount, params_.halfScan, IND_FULL_SCAN, IND_FULL_ONE);
  dispatchIndirect(cb, "pair_check", &push, sizeof(push), IND_FULL_ONE);
  dispatchIndirect(cb, "pair_copy", &push, sizeof(push), IND_FULL_COPY);
  dispatchIndirect(cb, "neighbour_fill", &push, sizeof(push), IND_FULL_PARTICLES);
  const PushParamsArg link{ P, 0, 0 };
  const PushParamsArg carry{ P, 1, 0 };
  dispatchIndirect(cb, "neighbour_link", &link, sizeof(link), IND_FULL_PARTICLES);
  dispatchIndirect(cb, "neighbour_link", &carry, sizeof(carry), IND_NEW_PAIRS);
  // Wall list (with a full rebuild, or alone when a wall moved).
  const PushParamsArg phases[4] = { { P, 0, 0 }, { P, 1, 0 }, { P, 2, 0 }, { P, 3, 0 } };
  dispatchIndirect(cb, "wall_list", &phases[0], sizeof(phases[0]), IND_WALL_PARTICLES);
  recordScan(cb, params_.wallCount, params_.wallScan, IND_WALL_SCAN, IND_WALL_ONE);
  dispatchIndirect(cb, "wall_list", &phases[1], sizeof(phases[1]), IND_WALL_ONE);
  dispatchIndirect(cb, "wall_list", &phases[2], sizeof(phases[2]), IND_WALL_COPY);
  dispatchIndirect(cb, "wall_list", &phases[3], sizeof(phases[3]), IND_WALL_PARTICLES);
}

void VulkanBackend::recordSteps(VkCommandBuffer cb, std::int64_t steps, bool resumeAtRebuild)
{
  const PushParams push{ paramsBuffer_.address };
  for (std::int64_t s = 0; s < steps; ++s) {
    if (!(s == 0 && resumeAtRebuild)) {
      dispatchItems(cb, "kick_drift", n_);
      dispatch(cb, "control", &push, sizeof(push), 1);
    }
    if (s == 0 && resumeAtRebuild) {
      recordRebuild(cb);
    }
    dispatchIndirect(cb, "pair_forces", &push, sizeof(push), IND_PAIRS);
    if (bonds_ > 0) {
      dispatchItems(cb, "bond_forces", bonds_);
    }
    dispatchItems(cb, "gather", n_);
    dispatch(cb, "wall_sums", &push, sizeof(push), 1);
  }
}

// ---------------------------------------------------------------------------------------
// Stepping

void VulkanBackend::runOnHost(std::int64_t steps)
{
  sync();
  host_->run(steps);
  upload();
}

void VulkanBackend::run(std::int64_t steps)
{
  if (steps <= 0) {
    return;
  }
  setStageParameters();
  if (servoNeedsParticles()) {
    runOnHost(steps);
    return;
  }
  synced_ = false;
  std::int64_t remaining = steps;
  bool resume = false;
  const vk::Api& api = device_->api();
  while (remaining > 0) {
    // Steps per submission follow the rebuild interval: a submission that halts for a
    // rebuild after d steps is followed by ones of about d + 1 steps (the halted rest of a
    // command buffer still costs its empty dispatches); one that completes doubles.
    const std::int64_t submitted = std::min(remaining, batch_);
    VkCommandBuffer cb = device_->begin();
    api.vkCmdUpdateBuffer(cb, paramsBuffer_.buffer, 0, sizeof(vk::Params), &params_);
    // A new submission: no step done, not halted.
    api.vkCmdFillBuffer(cb, control_->buffer, 4 * CTL_HALTED, 4, 0);
    api.vkCmdFillBuffer(cb, control_->buffer, 4 * CTL_STEPS_DONE, 4, 0);
    api.vkCmdFillBuffer(cb, control_->buffer, 4 * CTL_REBUILDS, 4, 0);
    device_->barrier(cb);
    recordSteps(cb, submitted, resume);
    recordControlReadback(cb);
    device_->endSubmitWait(cb);
    std::uint32_t ctl[CTL_COUNT];
    readControlReadback(ctl);
    const std::int64_t done = ctl[CTL_STEPS_DONE];
    rebuilds_ += ctl[CTL_REBUILDS];
    pairs_ = ctl[CTL_PAIRS];
    adjacency_ = ctl[CTL_ADJACENCY];
    wallEntries_ = ctl[CTL_WALL_ENTRIES];
    remaining -= done;
    resume = false;
    if (ctl[CTL_HALTED] == HALT_REBUILD) {
      // Step `done` of the submission needs a rebuild (its kick, drift and wall control
      // are done): resume it at its rebuild.
      resume = true;
      batch_ = std::max<std::int64_t>(4, std::min<std::int64_t>(kMaxStepsPerSubmission, done + 2));
    } else if (ctl[CTL_HALTED] != 0) {
      // A list outgrew its buffers at step `done`, before anything was overwritten: grow,
      // and resume that step at its rebuild.
      grow(ctl[CTL_HALTED] == HALT_PAIRS, ctl[CTL_HALTED] == HALT_WALLS, ctl[CTL_NEED_PAIRS],
           ctl[CTL_NEED_WALLS]);
      ++growths_;
      resume = true;
    } else if (done != submitted) {
      throw std::logic_error("VulkanBackend: a submission stopped without a reason");
    } else {
      batch_ = std::min<std::int64_t>(kMaxStepsPerSubmission, 2 * batch_);
    }
  }
  model_.clock.step += steps;
}

const ContactState& VulkanBackend::sync()
{
  if (!synced_) {
    download();
    synced_ = true;
  }
  return host_->state();
}

void VulkanBackend::countDissipation(bool on)
{
  countDissipation_ = on;
  params_.countDissipation = on ? 1u : 0u;
  host_->countDissipation(on); // (a step run on the host counts too)
  if (on) {
    const vk::Api& api = device_->api();
    device_->submit([&](VkCommandBuffer cb) {
      api.vkCmdFillBuffer(cb, array("dampingWork").buffer, 0, VK_WHOLE_SIZE, 0);
      api.vkCmdFillBuffer(cb, array("breakEnergy").buffer, 0, VK_WHOLE_SIZE, 0);
    });
  }
}

StabilityReport VulkanBackend::stability()
{
  const vk::Api& api = device_->api();
  const vk::Buffer* control = control_;
  // Partial sums in two halves of partialSums: each pass reads one half, writes the other.
  const std::uint64_t half = std::uint64_t(groupsFor(n_, 1024)) + 2;
  std::uint64_t source = params_.kinetic;
  std::uint32_t count = n_;
  std::uint32_t resultIndex = 0; // element of partialSums holding the total
  device_->submit([&](VkCommandBuffer cb) {
    api.vkCmdUpdateBuffer(cb, paramsBuffer_.buffer, 0, sizeof(vk::Params), &params_);
    api.vkCmdFillBuffer(cb, control->buffer, 4 * CTL_NONFINITE, 4, ~0u);
    api.vkCmdFillBuffer(cb, control->buffer, 4 * CTL_ESCAPED, 4, 0);
    api.vkCmdFillBuffer(cb, control->buffer, 4 * CTL_FIRST_ESCAPED, 4, ~0u);
    device_->barrier(cb);
    dispatchItems(cb, "stability", n_);
    int side = 0;
    do {
      const std::uint64_t target = params_.partialSums + 8 * half * static_cast<std::uint64_t>(side);
      const PushReduce push{ paramsBuffer_.address, source, target, count, 0 };
      const std::uint32_t groups = std::max<std::uint32_t>(1, groupsFor(count, 1024));
      dispatch(cb, "reduce_sum", &push, sizeof(push), groups);
      source = target;
      count = groups;
      resultIndex = static_cast<std::uint32_t>(half * static_cast<std::uint64_t>(side));
      side = 1 - side;
    } while (count > 1);
    recordControlReadback(cb);
    VkBufferCopy c{ 8 * static_cast<std::uint64_t>(resultIndex), 512, 8 };
    api.vkCmdCopyBuffer(cb, partialSums_->buffer, staging_.buffer, 1, &c);
    // The walls (positions and reactions) for the wall work of the energy check.
    VkBufferCopy w{ 0, kWallsStagingOffset, 8 * 6 * WALL_STRIDE };
    api.vkCmdCopyBuffer(cb, walls_->buffer, staging_.buffer, 1, &w);
  });
  std::uint32_t ctl[CTL_COUNT];
  readControlReadback(ctl);
  double kinetic = 0.0;
  std::memcpy(&kinetic, static_cast<const char*>(staging_.mapped) + 512, 8);
  StabilityReport r;
  std::vector<double> walls(6 * WALL_STRIDE);
  std::memcpy(walls.data(), static_cast<const char*>(staging_.mapped) + kWallsStagingOffset, 8 * walls.size());
  for (int w = 0; w < 6; ++w) {
    const double* x = &walls[WALL_STRIDE * w];
    r.wallPosition[w] = x[WALL_POSITION];
    r.wallForce[w] = x[WALL_FORCE + model_.walls[w].axis];
  }
  if (ctl[CTL_NONFINITE] != ~0u) {
    r.firstNonFinite = static_cast<long>(ctl[CTL_NONFINITE]);
    return r;
  }
  r.escaped = ctl[CTL_ESCAPED];
  if (r.escaped > 0) {
    r.firstEscaped = static_cast<long>(ctl[CTL_FIRST_ESCAPED]);
    return r;
  }
  r.kineticEnergy = kinetic;
  return r;
}

} // namespace dem
