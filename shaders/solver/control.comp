#version 460
// RockDEM step, part 2 (one invocation): wall control (dem::controlWalls: servo law,
// platen, at rest), wall motion, and what to rebuild this step (CpuBackend::step: the
// neighbour list when a particle moved half the skin, else the wall list when a wall moved
// half the skin or was switched on or off). A step that needs a rebuild halts the
// submission (HALT_REBUILD) with the indirect dispatch arguments of the rebuild kernels
// written: the host resumes it at its rebuild. Steps without one (most of them) then cost
// six dispatches.
#include "geometry.glsl"
#include "servo_law.glsl"
layout(local_size_x = 1) in;
layout(push_constant) uniform Push { Params p; } push;

double wallValue(Params p, uint w, uint field)
{
  return p.walls.v[WALL_STRIDE * w + field];
}

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  const double dt = p.dt;
  if (p.testRunning != 0u) {
    const int a = int(p.axis);
    // The specimen's size: between the walls (the host runs a servo on the device only
    // when every axis it needs is walled, or is the slab of a 2D section).
    double length[3];
    for (int k = 0; k < 3; ++k) {
      if ((p.lengthFromWalls & (1u << k)) != 0u) {
        length[k] = wallValue(p, uint(2 * k + 1), WALL_POSITION) - wallValue(p, uint(2 * k), WALL_POSITION);
      } else {
        length[k] = p.sizeZ; // the slab of a 2D section
      }
    }
    const double maxSpeed = 0.002LF * p.smallestRadius / dt;
    for (uint w = 0u; w < 6u; ++w) {
      const int axis = int(w / 2u);
      const int side = int(w % 2u);
      const bool isActive = wallValue(p, w, WALL_ACTIVE) != 0.0LF;
      const bool servo = isActive && (p.servoAll != 0u || (p.servoSides != 0u && axis != a));
      double velocity;
      if (servo) {
        const int b = (axis + 1) % 3;
        const int c = (axis + 2) % 3;
        const double area = length[b] * length[c];
        velocity = servoWallVelocity(wallValue(p, w, WALL_ELASTIC), wallValue(p, w, WALL_STIFFNESS), area,
                                     p.confiningStress, p.servoAlpha, dt, maxSpeed, side);
      } else if (p.platenMoving != 0u && axis == a && side == 1) {
        velocity = p.platenVelocity;
      } else {
        velocity = 0.0LF;
      }
      p.walls.v[WALL_STRIDE * w + WALL_VELOCITY] = velocity;
    }
  }
  for (uint w = 0u; w < 6u; ++w) {
    p.walls.v[WALL_STRIDE * w + WALL_POSITION] =
      wallValue(p, w, WALL_POSITION) + wallValue(p, w, WALL_VELOCITY) * dt;
  }
  const bool stale = p.ctl.v[CTL_STALE] != 0u;
  p.ctl.v[CTL_STALE] = 0u;
  bool wallsMoved = false;
  const double limit = 0.5LF * p.skin;
  for (uint w = 0u; w < 6u; ++w) {
    const bool isActive = wallValue(p, w, WALL_ACTIVE) != 0.0LF;
    const bool isActiveAtBuild = wallValue(p, w, WALL_ACTIVE_AT_BUILD) != 0.0LF;
    if (isActive != isActiveAtBuild ||
        (isActive && !(abs(wallValue(p, w, WALL_POSITION) - wallValue(p, w, WALL_POSITION_AT_BUILD)) <= limit))) {
      wallsMoved = true;
    }
  }
  const uint mode = stale ? MODE_FULL : (wallsMoved ? MODE_WALLS : MODE_NONE);
  p.ctl.v[CTL_MODE] = mode;
  const uint n = p.n;
  const uint scanBlocks = (n + 1u + SCAN_BLOCK - 1u) / SCAN_BLOCK;
  const bool full = mode == MODE_FULL;
  const bool walls = mode != MODE_NONE;
  setItems(p, IND_FULL_PARTICLES, full ? n : 0u);
  setGroups(p, IND_FULL_TILES, full ? p.sortTiles : 0u);
  setItems(p, IND_FULL_CELLS, full ? p.totalCells : 0u);
  setGroups(p, IND_FULL_SCAN, full ? scanBlocks : 0u);
  setGroups(p, IND_FULL_ONE, full ? 1u : 0u);
  setItems(p, IND_FULL_COPY, 0u);  // set by the capacity check
  setItems(p, IND_NEW_PAIRS, 0u);  // set by the capacity check
  setItems(p, IND_WALL_PARTICLES, walls ? n : 0u);
  setGroups(p, IND_WALL_SCAN, walls ? scanBlocks : 0u);
  setGroups(p, IND_WALL_ONE, walls ? 1u : 0u);
  setItems(p, IND_WALL_COPY, 0u);  // set by the capacity check
  if (mode != MODE_NONE) {
    p.ctl.v[CTL_HALTED] = HALT_REBUILD;
  }
}
