// RockDEM engine: the selectable contact law (PHYSICS.md section 1).
#pragma once

namespace dem {

/// Hertz-Mindlin (default) or linear spring-dashpot with stiffness from Young's modulus.
enum class ContactLaw { HertzMindlin = 0, Linear = 1 };

} // namespace dem
