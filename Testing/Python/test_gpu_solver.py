"""pvpython: DEM Load Test with GPU Solver (Vulkan; lavapipe in CI).

The GPU path gives the CPU path's output bit for bit (positions, velocities, the test
history), Solver Path says "GPU Vulkan: <device>"; with Vulkan unavailable (here:
ROCKDEM_VULKAN_DISABLE) the same stage runs on the CPU and Solver Path says why.
On a machine without a Vulkan device the fallback is checked and the test is reported as
skipped (exit status 77), saying why.
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
pack = DEMPackSource(InitialElements=400, XDimension=0.04, YDimension=0.04, ZDimension=0.06,
                     MinimumSize=0.002, MaximumSize=0.003, YoungsModulus=1e7, RandomSeed=5,
                     RollingFriction=0.1)
pack.UpdatePipeline()


def run(gpu):
    """The stage at its last frame (positions, velocities, Solver Path, contacts, Last
    Message), then back at frame 1 (the time contract: an earlier time restores the
    nearest checkpoint, replaying from it if needed, on the same path): positions."""
    stage = DEMLoadTest(Input=pack, FrameInterval=0.01, NumberOfFrames=3, GPUSolver=gpu)
    t = stage.TimestepValues[-1]
    stage.UpdatePipeline(t)
    data = servermanager.Fetch(stage)
    particles = data.GetBlock(0)
    out = [vtk_to_numpy(particles.GetPoints().GetData()).copy(),
           vtk_to_numpy(particles.GetPointData().GetArray("Velocity")).copy(),
           rockdem.read_only(stage, "SolverPath"),
           rockdem.read_only(stage, "NumberOfContacts"),
           rockdem.read_only(stage, "LastMessage")]
    stage.UpdatePipeline(stage.TimestepValues[1])
    out.append(vtk_to_numpy(servermanager.Fetch(stage).GetBlock(0).GetPoints().GetData()).copy())
    Delete(stage)
    return out


cpu = run(0)
gpu = run(1)
print("CPU Solver Path:", cpu[2])
print("GPU Solver Path:", gpu[2])
c.check(cpu[2].startswith("CPU"), "GPU Solver off: the CPU runs")
# A machine without a usable Vulkan device: the GPU request falls back for a reason about
# the machine (not about this small model, which fits any device).
FELL_BACK = "GPU requested, fell back because "
no_device = None
if FELL_BACK in gpu[2]:
    reason = gpu[2].split(FELL_BACK, 1)[1]
    if "too little device memory" not in reason and "allocating" not in reason:
        no_device = reason
if no_device is None:
    c.check(gpu[2].startswith("GPU Vulkan: "), "GPU Solver on: Solver Path names the device")
    c.check(cpu[3] > 0 and cpu[3] == gpu[3], "contacts formed, the same count on both paths (%d)" % cpu[3])
    c.check((cpu[0] == gpu[0]).all() and (cpu[1] == gpu[1]).all(),
            "positions and velocities after 3 frames are bitwise the CPU's")
    c.check((cpu[5] == gpu[5]).all() and not (gpu[5] == gpu[0]).all(),
            "back at frame 1 (the time contract on the GPU path): bitwise the CPU's frame 1")
else:
    c.check((gpu[0] == cpu[0]).all(), "no Vulkan device: the GPU request ran the CPU run")

os.environ["ROCKDEM_VULKAN_DISABLE"] = "1"
fallback = run(1)
del os.environ["ROCKDEM_VULKAN_DISABLE"]
print("fallback Solver Path:", fallback[2])
c.check(fallback[2].startswith("CPU") and "GPU requested, fell back because Vulkan is disabled" in fallback[2],
        "without Vulkan the stage runs on the CPU and Solver Path says why")
c.check((fallback[0] == cpu[0]).all(), "the fallback run is the CPU run")
c.check("GPU Solver: running on the CPU because Vulkan is disabled" in fallback[4],
        "the fallback reason is the Last Message (%r)" % fallback[4])
if no_device is not None and not c.failed:
    print("SKIPPED: no usable Vulkan device on this machine (%s); the GPU checks need one "
          "(Debian: mesa-vulkan-drivers)" % no_device)
    sys.exit(77)
c.finish()
