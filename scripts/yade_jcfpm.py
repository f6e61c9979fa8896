"""YADE JCFpm's side of the bonded-rock comparison (scripts/benchmark_yade_jcfpm.sh).

  yade -jT -n -x scripts/yade_jcfpm.py SPECIMEN.csv PARAMS.json HISTORY.csv [--no-stiffness-match]

Runs in YADE 2023.02a (Debian package `yade`), not in RockDEM: YADE is a peer measured
against, not a dependency.

The same grains as RockDEM (SPECIMEN: "x,y,z,Radius", written by scripts/yade_rockdem.py),
the same parameters (PARAMS, JSON; dt from RockDEM's probe):
- material JCFpmMat: density; tensileStrength = Tensile Strength; cohesion = Cohesion;
  frictionAngle = Friction Angle (the bond's Mohr-Coulomb slope); residualFrictionAngle =
  atan(grain friction) (the contacts after a bond broke, and new contacts);
  young = pi/2 x Bond Modulus and poisson = Bond Stiffness Ratio (JCFpm's "poisson" is
  ks/kn), so that kn = 2 young R1 R2 / (R1 + R2) equals RockDEM's bond normal stiffness
  Bond Modulus x pi min(R1,R2)^2 / (R1 + R2) for equal radii. Bonded pairs of unequal
  radii would then differ by min/max radius (JCFpm's kn is a harmonic mean of the radii,
  ours the smaller section): after the cementing step kn and ks of every bond are set
  to RockDEM's values pair by pair (--no-stiffness-match keeps JCFpm's own).
- bonds at cementing: interactionDetectionFactor = aabbEnlargeFactor = Bond Range for
  the first step (cohesiveTresholdIteration 1), then 1; crossSection = pi min(R1,R2)^2 =
  RockDEM's bond section with Bond Radius Multiplier 1; FnMax and FsMax from it.
  An independent count (scipy cKDTree, pairs with |xi - xj| <= Bond Range (Ri + Rj)) is
  printed beside JCFpm's cohesive interactions.
- loading: two frictionless walls (JCFpmMat without strength, so never cohesive) at the
  grains' extent along Z, the upper one moving down at strain_per_step x L0 / dt;
  NewtonIntegrator(damping = Settling Damping: the same non-viscous local damping);
  no gravity; dt fixed; steps steps after the cementing step.
- measured as RockDEM's press does (Documentation/Press.md): axial strain (L0 - L) / L0
  from the walls; axial stress = the mean of the two walls' forces over the lateral area,
  whose sides start at the grains' extent and follow the spread of the centres (mean
  absolute deviation), every sample steps.
Prints "run threads T particles N bonds B kdtree K steps S seconds X pstep_s Y ..." (X, Y:
the O.run of the S steps less the time of the Python sampling, which is printed as
record_seconds; with_record_pstep_s includes it) and
writes HISTORY (step, axial_strain, axial_stress_pa, broken_tension, broken_shear).
"""
import json
import math
import os
import sys
import time

import numpy as np
from scipy.spatial import cKDTree
from yade import O, utils
from yade.wrapper import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                          Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                          Ip2_JCFpmMat_JCFpmMat_JCFpmPhys, JCFpmMat, JCFpmPhys,
                          Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM, NewtonIntegrator, PyRunner)
from yade.minieigenHP import Vector3

args = [x for x in sys.argv[1:] if not x.startswith("--")]
match_stiffness = "--no-stiffness-match" not in sys.argv
if len(args) != 3:
    sys.exit(__doc__)
specimen, params, history = args
with open(params) as f:
    P = json.load(f)
data = np.loadtxt(specimen, delimiter=",", skiprows=1, ndmin=2)
xyz, rad = data[:, :3], data[:, 3]
n = len(rad)
dt, steps, sample, factor = P["dt"], int(P["steps"]), int(P["sample"]), P["bond_range"]

mat = O.materials.append(JCFpmMat(young=math.pi / 2 * P["bond_modulus"], poisson=P["bond_stiffness_ratio"],
                                  density=P["density"], frictionAngle=math.radians(P["friction_angle"]),
                                  residualFrictionAngle=math.atan(P["grain_friction"]),
                                  tensileStrength=P["tensile_strength"], cohesion=P["cohesion"], label="rock"))
platen = O.materials.append(JCFpmMat(young=1e3 * math.pi / 2 * P["bond_modulus"], poisson=P["bond_stiffness_ratio"],
                                     density=P["density"], frictionAngle=0.0, residualFrictionAngle=0.0,
                                     tensileStrength=0.0, cohesion=0.0, label="platen"))
O.bodies.append([utils.sphere(Vector3(*p), r, material=mat) for p, r in zip(xyz, rad)])
zlo, zhi = float(np.min(xyz[:, 2] - rad)), float(np.max(xyz[:, 2] + rad))
bottom = O.bodies.append(utils.wall(Vector3(0, 0, zlo), axis=2, sense=1, material=platen))
top = O.bodies.append(utils.wall(Vector3(0, 0, zhi), axis=2, sense=-1, material=platen))
L0 = zhi - zlo
lateral0 = [float(np.max(xyz[:, k] + rad) - np.min(xyz[:, k] - rad)) for k in (0, 1)]
spread0 = [float(np.mean(np.abs(xyz[:, k] - np.mean(xyz[:, k])))) for k in (0, 1)]

law = Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM(label="law")
bo1 = Bo1_Sphere_Aabb(aabbEnlargeFactor=factor)
ig2 = Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=factor)
rows = []
record_seconds = [0.0]


def record(initial=False):
    # In the PyRunner (during iteration j) j compression steps are done; the manual call
    # after the cementing step (O.iter 1) is at 0.
    start = time.perf_counter()
    pos = np.array([O.bodies[i].state.pos for i in range(n)])
    area = 1.0
    for k in (0, 1):
        area *= lateral0[k] * float(np.mean(np.abs(pos[:, k] - np.mean(pos[:, k])))) / spread0[k]
    length = O.bodies[top].state.pos[2] - O.bodies[bottom].state.pos[2]
    stress = 0.5 * (abs(O.forces.f(top)[2]) + abs(O.forces.f(bottom)[2])) / area
    rows.append((O.iter - (1 if initial else 0), (L0 - length) / L0, stress, law.nbTensCracks, law.nbShearCracks))
    record_seconds[0] += time.perf_counter() - start


O.engines = [
    ForceResetter(),
    InsertionSortCollider([bo1, Bo1_Wall_Aabb()]),
    InteractionLoop([ig2, Ig2_Wall_Sphere_ScGeom()], [Ip2_JCFpmMat_JCFpmMat_JCFpmPhys(cohesiveTresholdIteration=1)],
                    [law]),
    NewtonIntegrator(damping=P["damping"], gravity=Vector3(0, 0, 0)),
    PyRunner(iterPeriod=sample, initRun=False, command="record()"),
]
O.dt = dt

# Cementing: one step with the enlarged detection; every interaction found in it is a bond.
O.step()
bo1.aabbEnlargeFactor = -1
ig2.interactionDetectionFactor = 1
bonds = 0
for i in O.interactions:
    if i.isReal and isinstance(i.phys, JCFpmPhys) and i.phys.isCohesive:
        bonds += 1
        if match_stiffness:
            r1, r2 = rad[i.id1], rad[i.id2]
            kn = P["bond_modulus"] * math.pi * min(r1, r2) ** 2 / (r1 + r2)
            i.phys.kn = kn
            i.phys.ks = P["bond_stiffness_ratio"] * kn
pairs = cKDTree(xyz).query_pairs(2.0 * factor * float(rad.max()), output_type="ndarray")
d = np.linalg.norm(xyz[pairs[:, 0]] - xyz[pairs[:, 1]], axis=1)
kdtree = int(np.count_nonzero(d <= factor * (rad[pairs[:, 0]] + rad[pairs[:, 1]])))

# Unconfined compression: the upper wall moves down at strain_per_step per step.
O.bodies[top].state.vel = Vector3(0, 0, -P["strain_per_step"] * L0 / dt)
record(initial=True)
record_seconds[0] = 0.0  # only the samples taken during the run count
start = time.perf_counter()
O.run(steps, True)
seconds = time.perf_counter() - start
peak = max(r[2] for r in rows)
# pstep_s leaves out the Python sampling (record(), timed on its own): YADE's own cost.
stepping = seconds - record_seconds[0]
print("run threads %d particles %d bonds %d kdtree %d steps %d seconds %.6f pstep_s %.6g timestep %.6g "
      "peak %.6g broken %d tension %d shear %d record_seconds %.3f with_record_pstep_s %.6g stiffness_match %d"
      % (O.numThreads, n, bonds, kdtree, steps, stepping, n * steps / stepping, O.dt, peak,
         law.nbTensCracks + law.nbShearCracks, law.nbTensCracks, law.nbShearCracks, record_seconds[0],
         n * steps / seconds, int(match_stiffness)))
with open(history + ".tmp", "w") as f:
    f.write("step,axial_strain,axial_stress_pa,broken_tension,broken_shear\n")
    for r in rows:
        f.write("%d,%.9g,%.9g,%d,%d\n" % r)
os.replace(history + ".tmp", history)
sys.stdout.flush()
os._exit(0)
