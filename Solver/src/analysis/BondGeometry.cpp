// RockDEM engine: where the bonds of a model are (see dem/BondGeometry.h).
#include "dem/BondGeometry.h"

#include "dem/Errors.h"

#include <string>
#include <unordered_map>

namespace dem {

BondGeometry bondGeometry(const Model& model)
{
  const Particles& p = model.particles;
  const Bonds& b = model.bonds;
  std::unordered_map<std::int64_t, std::size_t> slotOf;
  slotOf.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    slotOf.emplace(p.id[i], i);
  }
  BondGeometry g;
  g.slotA.resize(b.size());
  g.slotB.resize(b.size());
  g.start.resize(b.size());
  g.branch.resize(b.size());
  g.contact.resize(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    const auto a = slotOf.find(b.idA[k]);
    const auto c = slotOf.find(b.idB[k]);
    if (a == slotOf.end() || c == slotOf.end()) {
      throw InputError("Bond " + std::to_string(k) + " joins particle " +
        std::to_string(a == slotOf.end() ? b.idA[k] : b.idB[k]) + ", which is not in the model.");
    }
    const std::size_t i = a->second;
    const std::size_t j = c->second;
    g.slotA[k] = i;
    g.slotB[k] = j;
    g.start[k] = p.position[i];
    g.branch[k] = minimumImage(model.domain, p.position[i], p.position[j]);
    g.contact[k] = g.start[k] + p.radius[i] / (p.radius[i] + p.radius[j]) * g.branch[k];
  }
  return g;
}

} // namespace dem
