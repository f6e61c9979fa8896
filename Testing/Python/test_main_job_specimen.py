"""pvpython: the main job's own tested specimen can be run on (issue 18 item 4).

The specimen written by examples/main_job.py (Python.PackRendersAsSpheres, --elements 800)
comes from an unconfined compression test that threw grains out of the model box. DEM
State Reader -> DEM Load Test (Mode Off, no gravity) removes those grains with a count and
runs; before, it stopped with "particle(s) escaped the box" before the first step.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
specimen = sys.argv[1]
reader = DEMStateReader(FileName=specimen)
reader.UpdatePipeline()
n = rockdem.read_only(reader, "NumberOfParticles")
c.check(n > 0 and rockdem.read_only(reader, "Stage") == "done",
        "the tested specimen: %d particles, test %s" % (n, rockdem.read_only(reader, "Stage")))
run = DEMLoadTest(Input=reader, Gravity=[0, 0, 0], FrameInterval=1e-4, NumberOfFrames=2)
run.UpdatePipeline(2e-4)
status = rockdem.read_only(run, "Status")
message = rockdem.read_only(run, "LastMessage")
print("status:", status)
print("last message:", message)
c.check(status.startswith("t = ") and "(frame 2," in status, "it runs two frames in Mode Off")
c.check(message == "" or message.startswith("Removed "), "escaped grains, if any, are removed with a count")
c.finish()
