// RockDEM engine (internal): the headless Vulkan compute device (see VulkanDevice.h).
#include "backends/vulkan/VulkanDevice.h"

#include "dem/EmbeddedShaders.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace dem {
namespace vk {
namespace {

std::string resultName(VkResult r)
{
  switch (r) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory";
    case VK_ERROR_INITIALIZATION_FAILED: return "initialization failed";
    case VK_ERROR_DEVICE_LOST: return "device lost";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "no compatible Vulkan driver";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "feature not present";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "extension not present";
    case VK_ERROR_LAYER_NOT_PRESENT: return "layer not present";
    case VK_ERROR_TOO_MANY_OBJECTS: return "too many objects";
    default: break;
  }
  return "VkResult " + std::to_string(static_cast<int>(r));
}

void check(VkResult r, const char* what)
{
  if (r != VK_SUCCESS) {
    throw Unavailable(std::string(what) + " failed (" + resultName(r) + ")");
  }
}

const char* environment(const char* name)
{
  const char* v = std::getenv(name);
  return (v && *v) ? v : nullptr;
}

bool environmentFlag(const char* name)
{
  const char* v = environment(name);
  return v && std::strcmp(v, "0") != 0;
}

std::mutex gOpenMutex;
std::weak_ptr<Device> gDevice;

} // namespace

std::vector<std::uint32_t> withoutContraction(const std::uint32_t* words, std::size_t count)
{
  constexpr std::uint32_t OpDecorate = 71;
  constexpr std::uint32_t NoContraction = 42;
  std::vector<std::uint32_t> decorations;
  std::size_t insertAt = 0;
  std::size_t at = 5; // after the header
  while (at < count) {
    const std::uint32_t length = words[at] >> 16;
    const std::uint32_t opcode = words[at] & 0xffffu;
    if (length == 0 || at + length > count) {
      break; // malformed: leave the module as it is
    }
    // Type declarations (OpTypeVoid .. OpTypeForwardPointer) start after the annotations.
    if (insertAt == 0 && opcode >= 19 && opcode <= 39) {
      insertAt = at;
    }
    switch (opcode) {
      case 127: // OpFNegate
      case 129: // OpFAdd
      case 131: // OpFSub
      case 133: // OpFMul
      case 136: // OpFDiv
      case 140: // OpFRem
      case 141: // OpFMod
      case 142: // OpVectorTimesScalar
      case 143: // OpMatrixTimesScalar
      case 144: // OpVectorTimesMatrix
      case 145: // OpMatrixTimesVector
      case 146: // OpMatrixTimesMatrix
      case 147: // OpOuterProduct
      case 148: // OpDot
        if (length >= 3) {
          decorations.insert(decorations.end(), { (3u << 16) | OpDecorate, words[at + 2], NoContraction });
        }
        break;
      default:
        break;
    }
    at += length;
  }
  std::vector<std::uint32_t> out(words, words + count);
  if (insertAt > 0 && !decorations.empty()) {
    out.insert(out.begin() + static_cast<std::ptrdiff_t>(insertAt), decorations.begin(), decorations.end());
  }
  return out;
}

std::shared_ptr<Device> Device::open()
{
  std::lock_guard<std::mutex> lock(gOpenMutex);
  if (environmentFlag("ROCKDEM_VULKAN_DISABLE")) {
    throw Unavailable("Vulkan is disabled by ROCKDEM_VULKAN_DISABLE");
  }
  if (std::shared_ptr<Device> existing = gDevice.lock()) {
    return existing;
  }
  std::shared_ptr<Device> device(new Device);
  device->create();
  gDevice = device;
  return device;
}

void Device::create()
{
  library_ = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library_) {
    throw Unavailable("no Vulkan loader (libvulkan.so.1 not found)");
  }
  api_.vkGetInstanceProcAddr =
    reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library_, "vkGetInstanceProcAddr"));
  if (!api_.vkGetInstanceProcAddr) {
    throw Unavailable("the Vulkan loader has no vkGetInstanceProcAddr");
  }
  api_.vkCreateInstance = reinterpret_cast<PFN_vkCreateInstance>(
    api_.vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
  if (!api_.vkCreateInstance) {
    throw Unavailable("the Vulkan loader has no vkCreateInstance");
  }
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "RockDEM";
  app.pEngineName = "RockDEM";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ici{};
  ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ici.pApplicationInfo = &app;
  const VkResult created = api_.vkCreateInstance(&ici, nullptr, &instance_);
  if (created != VK_SUCCESS) {
    throw Unavailable("no Vulkan driver (vkCreateInstance: " + resultName(created) + ")");
  }
#define ROCKDEM_VK_LOAD(name)                                                                  \
  api_.name = reinterpret_cast<PFN_##name>(api_.vkGetInstanceProcAddr(instance_, #name));     \
  if (!api_.name) {                                                                            \
    throw Unavailable("the Vulkan loader has no " #name);                                     \
  }
  ROCKDEM_VK_FUNCTIONS(ROCKDEM_VK_LOAD)
#undef ROCKDEM_VK_LOAD

  std::uint32_t count = 0;
  api_.vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  if (count == 0) {
    throw Unavailable("no Vulkan device");
  }
  std::vector<VkPhysicalDevice> devices(count);
  api_.vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  devices.resize(count);

  // Candidates in order of preference: discrete, integrated, virtual, CPU (or the one
  // ROCKDEM_VULKAN_DEVICE names); the first that has every feature is used.
  std::vector<std::size_t> order(devices.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    order[i] = i;
  }
  auto rank = [&](std::size_t i) {
    VkPhysicalDeviceProperties p;
    api_.vkGetPhysicalDeviceProperties(devices[i], &p);
    switch (p.deviceType) {
      case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
      case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
      case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
      case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
      default: return 4;
    }
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rank(a) < rank(b); });
  if (const char* chosen = environment("ROCKDEM_VULKAN_DEVICE")) {
    const long index = std::strtol(chosen, nullptr, 10);
    if (index < 0 || index >= static_cast<long>(devices.size())) {
      throw Unavailable("ROCKDEM_VULKAN_DEVICE = " + std::string(chosen) + " is not a device index (0 to " +
                        std::to_string(devices.size() - 1) + ")");
    }
    order.assign(1, static_cast<std::size_t>(index));
  }
  const bool noFp64 = environmentFlag("ROCKDEM_VULKAN_SIMULATE_NO_FP64");
  std::string reasons;
  for (std::size_t i : order) {
    VkPhysicalDevice pd = devices[i];
    VkPhysicalDeviceProperties props;
    api_.vkGetPhysicalDeviceProperties(pd, &props);
    VkPhysicalDeviceVulkan12Features f12{};
    f12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    VkPhysicalDeviceFeatures2 f2{};
    f2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    f2.pNext = &f12;
    std::string missing;
    if (props.apiVersion < VK_API_VERSION_1_2) {
      missing = "Vulkan 1.2";
    } else {
      api_.vkGetPhysicalDeviceFeatures2(pd, &f2);
      if (!f2.features.shaderFloat64 || noFp64) {
        missing = "double precision in shaders (shaderFloat64)";
      } else if (!f2.features.shaderInt64) {
        missing = "64-bit integers in shaders (shaderInt64)";
      } else if (!f12.bufferDeviceAddress) {
        missing = "buffer device addresses (bufferDeviceAddress)";
      }
    }
    std::uint32_t families = 0;
    api_.vkGetPhysicalDeviceQueueFamilyProperties(pd, &families, nullptr);
    std::vector<VkQueueFamilyProperties> fam(families);
    api_.vkGetPhysicalDeviceQueueFamilyProperties(pd, &families, fam.data());
    long compute = -1;
    for (std::uint32_t q = 0; q < families; ++q) {
      if (fam[q].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        compute = q;
        break;
      }
    }
    if (missing.empty() && compute < 0) {
      missing = "a compute queue";
    }
    if (!missing.empty()) {
      reasons += (reasons.empty() ? "" : "; ") + std::string(props.deviceName) + " has no " + missing;
      continue;
    }
    physical_ = pd;
    queueFamily_ = static_cast<std::uint32_t>(compute);
    name_ = props.deviceName;
    maxGroupsX_ = props.limits.maxComputeWorkGroupCount[0];
    maxStorageRange_ = props.limits.maxStorageBufferRange;
    break;
  }
  if (physical_ == VK_NULL_HANDLE) {
    throw Unavailable(reasons.empty() ? std::string("no usable Vulkan device") : reasons);
  }

  api_.vkGetPhysicalDeviceMemoryProperties(physical_, &memoryProperties_);
  for (std::uint32_t h = 0; h < memoryProperties_.memoryHeapCount; ++h) {
    if (memoryProperties_.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
      memoryBytes_ = std::max<std::uint64_t>(memoryBytes_, memoryProperties_.memoryHeaps[h].size);
    }
  }
  VkPhysicalDeviceMaintenance3Properties m3{};
  m3.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES;
  VkPhysicalDeviceProperties2 p2{};
  p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  p2.pNext = &m3;
  api_.vkGetPhysicalDeviceProperties2(physical_, &p2);
  maxAllocation_ = m3.maxMemoryAllocationSize;
  if (const char* simulated = environment("ROCKDEM_VULKAN_SIMULATE_MEMORY")) {
    memoryBytes_ = std::strtoull(simulated, nullptr, 10);
  }
  if (const char* fail = environment("ROCKDEM_VULKAN_FAIL_ALLOCATION")) {
    failAllocation_ = std::strtoll(fail, nullptr, 10);
  }

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{};
  qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan12Features enable12{};
  enable12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  enable12.bufferDeviceAddress = VK_TRUE;
  VkPhysicalDeviceFeatures2 enable{};
  enable.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  enable.pNext = &enable12;
  enable.features.shaderFloat64 = VK_TRUE;
  enable.features.shaderInt64 = VK_TRUE;
  VkDeviceCreateInfo dci{};
  dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  dci.pNext = &enable;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  check(api_.vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
  api_.vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  VkCommandPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queueFamily_;
  check(api_.vkCreateCommandPool(device_, &pci, nullptr, &pool_), "vkCreateCommandPool");
  VkFenceCreateInfo fci{};
  fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  check(api_.vkCreateFence(device_, &fci, nullptr, &fence_), "vkCreateFence");
}

Device::~Device()
{
  if (device_) {
    api_.vkQueueWaitIdle(queue_);
    for (auto& p : pipelines_) {
      api_.vkDestroyPipeline(device_, p.second.pipeline, nullptr);
      api_.vkDestroyPipelineLayout(device_, p.second.layout, nullptr);
    }
    if (fence_) {
      api_.vkDestroyFence(device_, fence_, nullptr);
    }
    if (pool_) {
      api_.vkDestroyCommandPool(device_, pool_, nullptr);
    }
    api_.vkDestroyDevice(device_, nullptr);
  }
  if (instance_ && api_.vkDestroyInstance) {
    api_.vkDestroyInstance(instance_, nullptr);
  }
  if (library_) {
    dlclose(library_);
  }
}

namespace {
std::uint32_t memoryType(const VkPhysicalDeviceMemoryProperties& props, std::uint32_t allowed,
                         VkMemoryPropertyFlags wanted)
{
  for (std::uint32_t t = 0; t < props.memoryTypeCount; ++t) {
    if ((allowed & (1u << t)) && (props.memoryTypes[t].propertyFlags & wanted) == wanted) {
      return t;
    }
  }
  return UINT32_MAX;
}
} // namespace

void Device::allocateAndBind(Buffer& b, VkDeviceSize size, std::uint32_t type, const void* next,
                             const char* what)
{
  VkMemoryAllocateInfo mai{};
  mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  mai.pNext = next;
  mai.allocationSize = size;
  mai.memoryTypeIndex = type;
  VkResult r = VK_ERROR_OUT_OF_DEVICE_MEMORY; // the failure ROCKDEM_VULKAN_FAIL_ALLOCATION asks for
  if (++allocations_ != failAllocation_) {
    r = api_.vkAllocateMemory(device_, &mai, nullptr, &b.memory);
  }
  if (r != VK_SUCCESS) {
    api_.vkDestroyBuffer(device_, b.buffer, nullptr);
    b.buffer = VK_NULL_HANDLE;
    throw Unavailable("allocating " + std::to_string(b.bytes) + " bytes of " + what + " memory failed (" +
                      resultName(r) + ")");
  }
  const VkResult bound = api_.vkBindBufferMemory(device_, b.buffer, b.memory, 0);
  if (bound != VK_SUCCESS) {
    destroy(b);
    check(bound, "vkBindBufferMemory");
  }
}

Buffer Device::createBuffer(VkDeviceSize bytes)
{
  Buffer b;
  b.bytes = std::max<VkDeviceSize>(bytes, 16);
  if (b.bytes > maxAllocation_) {
    throw Unavailable("an array of " + std::to_string(b.bytes) + " bytes exceeds the device's largest allocation (" +
                      std::to_string(maxAllocation_) + " bytes)");
  }
  VkBufferCreateInfo bci{};
  bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bci.size = b.bytes;
  bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
    VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(api_.vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  api_.vkGetBufferMemoryRequirements(device_, b.buffer, &req);
  std::uint32_t type = memoryType(memoryProperties_, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type == UINT32_MAX) {
    type = memoryType(memoryProperties_, req.memoryTypeBits, 0);
  }
  VkMemoryAllocateFlagsInfo flags{};
  flags.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO;
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  allocateAndBind(b, req.size, type, &flags, "device");
  VkBufferDeviceAddressInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO;
  ai.buffer = b.buffer;
  b.address = api_.vkGetBufferDeviceAddress(device_, &ai);
  return b;
}

Buffer Device::createStaging(VkDeviceSize bytes)
{
  Buffer b;
  b.bytes = std::max<VkDeviceSize>(bytes, 16);
  VkBufferCreateInfo bci{};
  bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bci.size = b.bytes;
  bci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(api_.vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  api_.vkGetBufferMemoryRequirements(device_, b.buffer, &req);
  const std::uint32_t type = memoryType(memoryProperties_, req.memoryTypeBits,
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (type == UINT32_MAX) {
    api_.vkDestroyBuffer(device_, b.buffer, nullptr);
    throw Unavailable("the device has no host-visible coherent memory");
  }
  allocateAndBind(b, req.size, type, nullptr, "staging");
  check(api_.vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

void Device::destroy(Buffer& b)
{
  if (b.mapped) {
    api_.vkUnmapMemory(device_, b.memory);
  }
  if (b.buffer) {
    api_.vkDestroyBuffer(device_, b.buffer, nullptr);
  }
  if (b.memory) {
    api_.vkFreeMemory(device_, b.memory, nullptr);
  }
  b = Buffer();
}

const Pipeline& Device::pipeline(const shaders::SpirvModule& module, std::uint32_t pushBytes)
{
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = pipelines_.find(module.name);
  if (found != pipelines_.end()) {
    return found->second;
  }
  const std::vector<std::uint32_t> code = withoutContraction(module.words, module.count);
  VkShaderModuleCreateInfo smci{};
  smci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  smci.codeSize = code.size() * sizeof(std::uint32_t);
  smci.pCode = code.data();
  VkShaderModule shader = VK_NULL_HANDLE;
  check(api_.vkCreateShaderModule(device_, &smci, nullptr, &shader), "vkCreateShaderModule");
  Pipeline p;
  p.pushBytes = pushBytes;
  VkPushConstantRange range{};
  range.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  range.offset = 0;
  range.size = pushBytes;
  VkPipelineLayoutCreateInfo plci{};
  plci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  plci.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;
  plci.pPushConstantRanges = &range;
  VkResult r = api_.vkCreatePipelineLayout(device_, &plci, nullptr, &p.layout);
  if (r != VK_SUCCESS) {
    api_.vkDestroyShaderModule(device_, shader, nullptr);
    check(r, "vkCreatePipelineLayout");
  }
  VkComputePipelineCreateInfo cpci{};
  cpci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  cpci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  cpci.stage.module = shader;
  cpci.stage.pName = "main";
  cpci.layout = p.layout;
  r = api_.vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &cpci, nullptr, &p.pipeline);
  api_.vkDestroyShaderModule(device_, shader, nullptr);
  if (r != VK_SUCCESS) {
    api_.vkDestroyPipelineLayout(device_, p.layout, nullptr);
    check(r, (std::string("vkCreateComputePipelines (") + module.name + ")").c_str());
  }
  return pipelines_.emplace(module.name, p).first->second;
}

VkCommandBuffer Device::begin()
{
  VkCommandBufferAllocateInfo cbai{};
  cbai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  cbai.commandPool = pool_;
  cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cbai.commandBufferCount = 1;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  check(api_.vkAllocateCommandBuffers(device_, &cbai, &cb), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(api_.vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
  return cb;
}

void Device::endSubmitWait(VkCommandBuffer cb)
{
  VkResult r = api_.vkEndCommandBuffer(cb);
  if (r == VK_SUCCESS) {
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    r = api_.vkQueueSubmit(queue_, 1, &si, fence_);
    if (r == VK_SUCCESS) {
      r = api_.vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX);
      api_.vkResetFences(device_, 1, &fence_);
    }
  }
  api_.vkFreeCommandBuffers(device_, pool_, 1, &cb);
  check(r, "a Vulkan submission");
}

void Device::barrier(VkCommandBuffer cb) const
{
  VkMemoryBarrier mb{};
  mb.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
    VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  api_.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
    0, 1, &mb, 0, nullptr, 0, nullptr);
}

} // namespace vk
} // namespace dem
