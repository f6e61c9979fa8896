// RockDEM: layout of one case of the law parity check (shaders/solver/law_parity.comp and
// Testing/Solver/TestVulkanLaws.cpp): PARITY_IN input doubles, PARITY_OUT results.
#ifndef ROCKDEM_PARITY_LAYOUT_H
#define ROCKDEM_PARITY_LAYOUT_H

#define PARITY_IN 64u
#define PARITY_OUT 72u

// Inputs
#define IN_LAW 0u
#define IN_DAMPING 1u
#define IN_FRICTION 2u
#define IN_ROLLING 3u
#define IN_YOUNG 4u
#define IN_POISSON 5u
#define IN_RA 6u
#define IN_MA 7u
#define IN_RB 8u
#define IN_MB 9u
#define IN_PLANAR 10u
#define IN_SLAB 11u
#define IN_OVERLAP 12u
#define IN_APPROACH 13u
#define IN_NORMAL 14u        // 3
#define IN_SLIP 17u          // 3
#define IN_SPRING 20u        // 3
#define IN_ROLL 23u          // 3
#define IN_ROLL_SPRING 26u   // 3
#define IN_CUNDALL_FORCE 29u
#define IN_CUNDALL_VELOCITY 30u
#define IN_CUNDALL_ALPHA 31u
#define IN_BOND_RADIUS 32u
#define IN_BOND_KN 33u
#define IN_BOND_KS 34u
#define IN_BOND_SIGMA 35u
#define IN_BOND_COHESION 36u
#define IN_BOND_TAN_PHI 37u
#define IN_BOND_FN 38u
#define IN_BOND_FS 39u       // 3
#define IN_BOND_MT 42u
#define IN_BOND_MB 43u       // 3
#define IN_BOND_VELOCITY 46u // 3
#define IN_BOND_SPIN 49u     // 3
#define IN_DT 52u
#define IN_SERVO_ELASTIC 53u
#define IN_SERVO_STIFFNESS 54u
#define IN_SERVO_AREA 55u
#define IN_SERVO_TARGET 56u
#define IN_SERVO_ALPHA 57u
#define IN_SERVO_MAX_SPEED 58u
#define IN_SERVO_SIDE 59u
#define IN_BOND_PHI 60u     // the C++ side: friction angle (rad); IN_BOND_TAN_PHI = std::tan of it
#define IN_BOND_BETA 61u    // Moment Contribution factor
#define IN_BOND_SOFTENING 62u // Softening Ratio
#define IN_BOND_DAMAGE 63u    // tension-softening damage before the step

// Results
#define OUT_PAIR 0u            // 6: PairProperties
#define OUT_CONSTANTS 6u       // 3
#define OUT_WALL 9u            // 6
#define OUT_WALL_CONSTANTS 15u // 3
#define OUT_NORMAL_STIFFNESS 18u
#define OUT_RESPONSE 19u       // 4 (overlap > 0 only)
#define OUT_TANGENTIAL 23u     // 3
#define OUT_SPRING 26u         // 3
#define OUT_ROLLING 29u        // 3
#define OUT_ROLL_SPRING 32u    // 3
#define OUT_ROTATED 35u        // 3
#define OUT_CUNDALL 38u
#define OUT_SECTION 39u        // 3
#define OUT_BOND_STATE 42u     // 8: Fn, Fs, Mt, Mb
#define OUT_STRESSES 50u       // 3
#define OUT_FAILURE 53u
#define OUT_SERVO 54u
#define OUT_SOFTENED_FAILURE 55u // softenedBondFailure
#define OUT_DAMAGE 56u           // the damage after it
#define OUT_BOND_ENERGY 57u      // bondStoredEnergy of the stepped bond
#define OUT_DAMPING_WORK 58u     // cundallDampingWork: force IN_BOND_FS, velocity IN_BOND_VELOCITY,
                                 // torque IN_BOND_MB, spin IN_BOND_SPIN, alpha IN_CUNDALL_ALPHA, IN_DT

#endif
