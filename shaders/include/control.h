// RockDEM: indices into the Vulkan backend's control arrays, shared by the shaders
// (state.glsl) and the C++ side (backends/vulkan/VulkanBackend.cpp).
#ifndef ROCKDEM_CONTROL_H
#define ROCKDEM_CONTROL_H

// ctl[] (uint)
#define CTL_STALE 0u           // a particle moved half the skin since the build (this step)
#define CTL_MODE 1u            // rebuild this step: 0 none, 1 neighbours and walls, 2 walls only
#define CTL_HALTED 2u          // 0, or why the submission stopped (HALT_*)
#define CTL_PAIRS 3u           // pairs in the neighbour list
#define CTL_ADJACENCY 4u       // entries in the gather lists (2 x pairs)
#define CTL_WALL_ENTRIES 5u    // entries in the particle-wall list
#define CTL_NEED_PAIRS 6u      // at a halt: pairs the rebuild needs
#define CTL_NEED_WALLS 7u      // at a halt: wall entries the rebuild needs
#define CTL_STEPS_DONE 8u      // steps completed in this submission
#define CTL_OLD_PAIRS 9u       // pairs of the list being replaced
#define CTL_OLD_WALLS 10u      // wall entries of the list being replaced
#define CTL_REBUILDS 11u       // neighbour rebuilds in this submission
#define CTL_NONFINITE 12u      // stability: first slot with a non-finite value (or ~0u)
#define CTL_ESCAPED 13u        // stability: particles outside the walls
#define CTL_FIRST_ESCAPED 14u  // stability: first of them (or ~0u)
#define CTL_COUNT 16u

#define HALT_PAIRS 1u          // the new pair list does not fit: grow, resume at the rebuild
#define HALT_WALLS 2u          // the new wall list does not fit: grow, resume at the rebuild
#define HALT_REBUILD 3u        // this step needs a rebuild: resume at the rebuild

#define MODE_NONE 0u
#define MODE_FULL 1u
#define MODE_WALLS 2u

// walls[] (double): 16 per wall
#define WALL_STRIDE 16u
#define WALL_POSITION 0u
#define WALL_VELOCITY 1u
#define WALL_ACTIVE 2u
#define WALL_FORCE 3u          // 3 components
#define WALL_STIFFNESS 6u
#define WALL_ELASTIC 7u
#define WALL_CONTACTS 8u
#define WALL_POSITION_AT_BUILD 9u
#define WALL_ACTIVE_AT_BUILD 10u

// clock[] (double)
#define CLOCK_TIME 0u

// indirect[] (uint): VkDispatchIndirectCommand triples
#define IND_FULL_PARTICLES 0u  // full rebuild: one invocation per particle
#define IND_FULL_TILES 3u      // full rebuild: one workgroup per sort tile
#define IND_FULL_CELLS 6u      // full rebuild: one invocation per cell
#define IND_FULL_SCAN 9u       // full rebuild: one workgroup per scan block of N + 1
#define IND_FULL_ONE 12u       // full rebuild: one workgroup
#define IND_FULL_COPY 15u      // full rebuild: max(old pairs, N + 1) invocations
#define IND_WALL_PARTICLES 18u // wall rebuild (also with a full one)
#define IND_WALL_SCAN 21u
#define IND_WALL_ONE 24u
#define IND_WALL_COPY 27u      // max(old wall entries, N + 1) invocations
#define IND_PAIRS 30u          // one invocation per pair (set at each rebuild)
#define IND_NEW_PAIRS 33u      // full rebuild: one invocation per new pair
#define IND_COUNT 36u

#define GROUP_SIZE 64u         // invocations per workgroup of the per-item kernels
#define DISPATCH_X 32768u      // most workgroups along x; more go along y
#define SCAN_BLOCK 1024u       // items per workgroup of the scans (256 x 4)
#define SORT_TILE 1024u        // items per workgroup of the radix sort (256 x 4)

#endif
