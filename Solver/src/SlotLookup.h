// RockDEM engine (internal): a particle's slot from its stable global id.
#pragma once

#include "dem/Model.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace dem {

/// Finds a particle's slot from its global id (ids are stable, slots are storage order).
class SlotLookup {
public:
  explicit SlotLookup(const Particles& p) : sorted_(p.size())
  {
    for (std::size_t i = 0; i < p.size(); ++i) {
      sorted_[i] = { p.id[i], static_cast<std::uint32_t>(i) };
    }
    std::sort(sorted_.begin(), sorted_.end());
  }
  /// The slot of `id`, or -1 when no particle has it.
  long find(std::int64_t id) const
  {
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(id, std::uint32_t(0)));
    return (it != sorted_.end() && it->first == id) ? static_cast<long>(it->second) : -1;
  }

private:
  std::vector<std::pair<std::int64_t, std::uint32_t>> sorted_;
};

} // namespace dem
