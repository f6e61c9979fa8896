"""pvpython: pack -> DEM Load Test (Mode Off) settles under gravity.

Time contract (DESIGN.md): the stage publishes its frames; advancing the animation time
advances the model; going back and forward again reproduces identical output (bit for
bit); the porosity after settling is lower than before.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

c = Checks()
pack = DEMPackSource(InitialElements=600, XDimension=0.06, YDimension=0.06, ZDimension=0.12,
                     MinimumSize=0.002, MaximumSize=0.004, YoungsModulus=1e7, RandomSeed=2)
pack.UpdatePipeline()
before = rockdem.read_only(pack, "CurrentPorosity")

settle = DEMLoadTest(Input=pack, FrameInterval=0.05, NumberOfFrames=8)
times = list(settle.TimestepValues)
c.check(len(times) == 9 and abs(times[-1] - 0.4) < 1e-12, "publishes 9 frames 0.05 s apart: %s" % times)


def state_at(t):
    settle.UpdatePipeline(t)
    data = servermanager.Fetch(settle)
    particles = data.GetBlock(0)
    return (data.GetFieldData().GetArray("Time").GetValue(0),
            vtk_to_numpy(particles.GetPoints().GetData()).copy(),
            vtk_to_numpy(particles.GetPointData().GetArray("Velocity")).copy())


t1, x1, v1 = state_at(0.1)
t4, x4, v4 = state_at(0.4)
c.check(abs(t1 - 0.1) < 0.01 and abs(t4 - 0.4) < 0.01, "model clock follows the frames (%.4f, %.4f s)" % (t1, t4))
after = rockdem.read_only(settle, "CurrentPorosity")
c.check(after < before, "settled porosity %.4f is lower than the packed %.4f" % (after, before))
c.check(rockdem.read_only(settle, "NumberOfContacts") > 0, "contacts formed")
c.check(rockdem.read_only(settle, "Timestep") <= rockdem.read_only(settle, "CriticalTimestep") * 0.1 + 1e-15,
        "timestep is Timestep Safety x critical")
c.check("CPU" in rockdem.read_only(settle, "SolverPath"), "status says which path ran")
print("status:", rockdem.read_only(settle, "Status"))

# Back and forward again: identical, bit for bit.
tb, xb, vb = state_at(0.1)
c.check(tb == t1 and (xb == x1).all() and (vb == v1).all(), "going back to 0.1 s reproduces the output exactly")
tf, xf, vf = state_at(0.4)
c.check(tf == t4 and (xf == x4).all() and (vf == v4).all(), "going forward to 0.4 s again reproduces it exactly")

# The animation scene drives it like any time-aware source.
scene = GetAnimationScene()
c.check(scene.PlayMode == "Snap To TimeSteps", "a pipeline built by a script animates by its time steps")
dt = rockdem.read_only(settle, "Timestep")
published = list(settle.TimestepValues)
c.check(abs(scene.EndTime - published[-1]) < 1e-15 and abs(published[-1] - 0.4) <= 0.5 * dt * 8,
        "the animation scene ends at the last frame, %.9g s: 8 frames of whole steps (%d steps of %.4g s)" % (
            scene.EndTime, rockdem.read_only(settle, "FrameSteps"), dt))
c.check(all(abs(t - k * rockdem.read_only(settle, "FrameSteps") * dt) <= 1e-12 * t for k, t in enumerate(published)),
        "published times are k x Frame Steps x Timestep (the model's times)")
scene.AnimationTime = 0.2
now = scene.TimeKeeper.Time
settle.UpdatePipeline(now)
t2 = servermanager.Fetch(settle).GetFieldData().GetArray("Time").GetValue(0)
c.check(abs(t2 - 0.2) < 0.01, "animation time 0.2 s shows the model at %.4f s" % t2)

# A parameter change discards the cache and reruns.
settle.SettlingDamping = 0.3
t, x, v = state_at(0.1)
c.check(not (x == x1).all(), "changing Settling Damping reruns the settling")

# Bad input: named, no output, ParaView keeps running.
settle.FrameInterval = -1.0
settle.UpdatePipeline(0.0)
c.check("Frame Interval" in rockdem.read_only(settle, "Status"), "bad Frame Interval is named: %s" % rockdem.read_only(settle, "Status"))
c.finish()
