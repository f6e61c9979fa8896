#version 460
// RockDEM wall list (CpuBackend::rebuildWallContacts): one entry per particle and active
// wall whose gap, at the positions of the last neighbour build, is below the skin; sorted
// by (slot, wall). push.phase 0: count each particle's entries (entry N stays 0).
// 1 (one invocation): capacity check (HALT_WALLS), new counts, the walls' positions at
// the build, indirect arguments. 2: keep the old list and install the new starts (one
// invocation per item of max(old entries, N + 1)). 3: fill each particle's entries:
// constants, a cleared state, and the history of the same contact in the old list when
// it was touching or loaded.
#include "geometry.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform Push { Params p; uint phase; } push;

double wallValue(Params p, uint w, uint field)
{
  return p.walls.v[WALL_STRIDE * w + field];
}

/// Whether particle i is a candidate for wall w.
bool nearWall(Params p, uint i, uint w)
{
  const uint axis = w / 2u;
  const double side = (w % 2u) == 0u ? 1.0LF : -1.0LF;
  const double gap = (p.positionAtBuild.v[3u * i + axis] - wallValue(p, w, WALL_POSITION)) * side - p.radius.v[i];
  return wallValue(p, w, WALL_ACTIVE) != 0.0LF && gap < p.skin;
}

void main()
{
  Params p = push.p;
  if (halted(p)) {
    return;
  }
  const uint i = itemIndex();
  if (push.phase == 0u) {
    if (i < p.n) {
      uint count = 0u;
      for (uint w = 0u; w < 6u; ++w) {
        count += nearWall(p, i, w) ? 1u : 0u;
      }
      p.wallCount.v[i] = count;
    }
  } else if (push.phase == 1u) {
    if (i != 0u) {
      return;
    }
    const uint entries = p.wallScan.v[p.n];
    if (entries > p.wallCapacity) {
      p.ctl.v[CTL_NEED_WALLS] = entries;
      p.ctl.v[CTL_HALTED] = HALT_WALLS;
      return;
    }
    const uint old = p.ctl.v[CTL_WALL_ENTRIES];
    p.ctl.v[CTL_OLD_WALLS] = old;
    p.ctl.v[CTL_WALL_ENTRIES] = entries;
    for (uint w = 0u; w < 6u; ++w) {
      p.walls.v[WALL_STRIDE * w + WALL_POSITION_AT_BUILD] = wallValue(p, w, WALL_POSITION);
      p.walls.v[WALL_STRIDE * w + WALL_ACTIVE_AT_BUILD] = wallValue(p, w, WALL_ACTIVE);
    }
    setItems(p, IND_WALL_COPY, max(old, p.n + 1u));
  } else if (push.phase == 2u) {
    if (i <= p.n) {
      p.oldWallStart.v[i] = p.wallStart.v[i];
      p.wallStart.v[i] = p.wallScan.v[i];
    }
    if (i < p.ctl.v[CTL_OLD_WALLS]) {
      p.oldWallIndex.v[i] = p.wallIndex.v[i];
      p.oldWallTouching.v[i] = p.wallTouching.v[i];
      store3(p.oldWallSpring, i, load3(p.wallSpring, i));
      if (p.rolling != 0u) {
        store3(p.oldWallRolling, i, load3(p.wallRolling, i));
      }
    }
  } else {
    if (i >= p.n) {
      return;
    }
    const ContactModel cm = contactModel(p, false, 0u);
    const bool rolling = p.rolling != 0u;
    uint e = p.wallStart.v[i];
    const uint oldFirst = p.oldWallStart.v[i];
    const uint oldLast = p.oldWallStart.v[i + 1u];
    for (uint w = 0u; w < 6u; ++w) {
      if (!nearWall(p, i, w)) {
        continue;
      }
      p.wallSlot.v[e] = i;
      p.wallIndex.v[e] = w;
      storeConstants(p.wallConstants, e, contactConstants(cm,
        wallProperties(cm, p.radius.v[i], massOf(p, i), p.planar != 0u, p.sizeZ)));
      uint touching = 0u;
      dvec3 spring = dvec3(0.0LF);
      dvec3 roll = dvec3(0.0LF);
      for (uint o = oldFirst; o < oldLast; ++o) {
        if (p.oldWallIndex.v[o] != w) {
          continue;
        }
        const dvec3 oldSpring = load3(p.oldWallSpring, o);
        const dvec3 oldRoll = rolling ? load3(p.oldWallRolling, o) : dvec3(0.0LF);
        if (p.oldWallTouching.v[o] != 0u || !isZero3(oldSpring) || (rolling && !isZero3(oldRoll))) {
          touching = p.oldWallTouching.v[o];
          spring = oldSpring;
          roll = oldRoll;
        }
      }
      p.wallTouching.v[e] = touching;
      store3(p.wallSpring, e, spring);
      if (rolling) {
        store3(p.wallRolling, e, roll);
      }
      store3(p.wallForce, e, dvec3(0.0LF));
      p.wallNormal.v[e] = 0.0LF;
      p.wallStiffness.v[e] = 0.0LF;
      p.wallElastic.v[e] = 0.0LF;
      ++e;
    }
  }
}
