// RockDEM engine: where the bonds of a model are (see dem/BondGeometry.h).
#include "dem/BondGeometry.h"

#include "../SlotLookup.h"
#include "dem/Errors.h"

#include <string>

namespace dem {

BondGeometry bondGeometry(const Model& model)
{
  const Particles& p = model.particles;
  const Bonds& b = model.bonds;
  const SlotLookup slots(p);
  BondGeometry g;
  g.slotA.resize(b.size());
  g.slotB.resize(b.size());
  g.start.resize(b.size());
  g.branch.resize(b.size());
  g.contact.resize(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    const long a = slots.find(b.idA[k]);
    const long c = slots.find(b.idB[k]);
    if (a < 0 || c < 0) {
      throw InputError("Bond " + std::to_string(k) + " joins particle " + std::to_string(a < 0 ? b.idA[k] : b.idB[k]) +
                       ", which is not in the model.");
    }
    const std::size_t i = static_cast<std::size_t>(a);
    const std::size_t j = static_cast<std::size_t>(c);
    g.slotA[k] = i;
    g.slotB[k] = j;
    g.start[k] = p.position[i];
    g.branch[k] = minimumImage(model.domain, p.position[i], p.position[j]);
    g.contact[k] = g.start[k] + p.radius[i] / (p.radius[i] + p.radius[j]) * g.branch[k];
  }
  return g;
}

} // namespace dem
