// RockDEM engine (internal): the Vulkan backend's parameter block, the C++ twin of the
// shaders' Params (shaders/include/state.glsl), generated from the same field list
// (params_fields.h) so that the layouts agree.
#pragma once

#include <cstddef>
#include <cstdint>

namespace dem {
namespace vk {

using uint = std::uint32_t;

struct Params {
#define ROCKDEM_ADDR(type, name) std::uint64_t name;
#define ROCKDEM_SCALAR(type, name) type name;
#define ROCKDEM_ARRAY(type, name, count) type name[count];
#include "params_fields.h"
#undef ROCKDEM_ADDR
#undef ROCKDEM_SCALAR
#undef ROCKDEM_ARRAY
};

namespace detail {
// std430 puts an 8-byte member on an 8-byte boundary and a 4-byte one on a 4-byte
// boundary, as C++ does; the field list keeps the 8-byte members first.
constexpr std::size_t addressCount = 0
#define ROCKDEM_ADDR(type, name) + 1
#define ROCKDEM_SCALAR(type, name)
#define ROCKDEM_ARRAY(type, name, count)
#include "params_fields.h"
#undef ROCKDEM_ADDR
#undef ROCKDEM_SCALAR
#undef ROCKDEM_ARRAY
  ;
} // namespace detail
static_assert(offsetof(Params, dt) == 8 * detail::addressCount, "Params: addresses first");

/// Every address field of Params, with its name (the arrays of the backend).
struct AddressField {
  std::uint64_t Params::*member;
  const char* name;
};
inline const AddressField* addressFields()
{
  static const AddressField fields[] = {
#define ROCKDEM_ADDR(type, name) { &Params::name, #name },
#define ROCKDEM_SCALAR(type, name)
#define ROCKDEM_ARRAY(type, name, count)
#include "params_fields.h"
#undef ROCKDEM_ADDR
#undef ROCKDEM_SCALAR
#undef ROCKDEM_ARRAY
  };
  return fields;
}
constexpr std::size_t addressFieldCount() { return detail::addressCount; }

} // namespace vk
} // namespace dem
