"""pvpython: DEM Load Test time stepping, estimates and stopping (Documentation/LoadTest.md,
"Time" and "How long a stage runs"); the pack's presses in a saved state; a stage resumed
from its checkpoint (Documentation/StateFile.md).

(a) frames are whole steps: a Frame Interval shorter than one timestep is an error naming
    both; a longer one is snapped (and said so), and every published time is the model's
    elapsed time at that frame; a request for k x Frame Interval reaches frame k; filters
    downstream of the stage (and the time keeper) list the model's times once it has run;
(b) Number Of Frames above 100,000 (1e9) is an error naming the range, and publishing the
    time steps does not grow the process;
(c) before it steps, a stage says how long it is: Estimated Steps and Estimated Run Time
    (and a warning when long), without stepping;
(d) Ctrl-C (SIGINT) stops a long frame between batches, and pvpython keeps running: the
    output is the last whole frame, the Status says so, and the stage stays stopped;
(e) Number Of Frames 0: a test runs until Stage done, its frames end there, and the
    estimate was close; Mode Off runs until the model has settled;
(f) a saved state records Add/Grow (Commands) and rebuilds the same pack;
(g) Resume From Checkpoint: the same stage takes its end from the checkpoint (bitwise the
    computed one); after an upstream change the checkpoint is ignored.
"""
import os
import resource
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, Messages, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
T0 = time.time()

messages = Messages()


def said(text):
    """Whether Output Messages got a line with text since the last call."""
    found = text in messages.GetOutput()
    messages.Flush()
    return found


pack = DEMPackSource(InitialElements=300, XDimension=0.02, YDimension=0.02, ZDimension=0.03,
                     MinimumSize=0.001, MaximumSize=0.0015, YoungsModulus=1e7, RandomSeed=5)
pack.UpdatePipeline()

# (a) Frames are whole steps.
lt = DEMLoadTest(Input=pack)
lt.UpdatePipeline(0.0)
dt = lt.Timestep
c.check(lt.FrameSteps == 100 and len(lt.TimestepValues) > 1 and lt.TimestepValues[1] == 100 * dt,
        "Frame Interval 0: frames of Steps Per Batch (100) steps, published at 100 x %.4g s" % dt)
lt.FrameInterval = 0.7 * dt
lt.UpdatePipeline(0.0)
status = lt.Status
c.check("Frame Interval" in status and "shorter than one timestep" in status,
        "a Frame Interval of 0.7 steps is refused, naming both: %s" % status[:110])
lt.FrameInterval = 2.7 * dt
lt.NumberOfFrames = 6
messages.Flush()
lt.UpdatePipeline(0.0)
c.check(lt.FrameSteps == 3 and said("snapped to whole steps"),
        "Frame Interval 2.7 steps is snapped to 3 steps, and Output Messages say so")
published = list(lt.TimestepValues)
c.check(len(published) == 7 and all(abs(t - k * 3 * dt) <= 1e-15 * (k + 1) for k, t in enumerate(published)),
        "the published times are k x 3 x timestep")
lt.UpdatePipeline(published[5])
elapsed = lt.ModelTime  # the pack starts at time 0
c.check(abs(elapsed - published[5]) <= 1e-12 * published[5] and
        lt.GetDataInformation().DataInformation.GetTime() == published[5],
        "frame 5 is stamped %.9g s and the model is there: %.9g s" % (published[5], elapsed))
lt.UpdatePipeline(4 * 2.7 * dt)
c.check(lt.GetDataInformation().DataInformation.GetTime() == published[4],
        "a request for 4 x Frame Interval (%.6g s) reaches frame 4 (%.6g s)" % (4 * 2.7 * dt, published[4]))
Delete(lt)

# (a') Filters downstream of a stage, created before it has run (so they first copied
# k x Frame Interval), list the model's times once it has: two DEM filters (ParaView's own
# filters list no times), the time keeper (which lists a filter's times in place of its
# input's), and a ParaView filter shows a frame at its model time.
lt = DEMLoadTest(Input=pack, FrameInterval=2.7 * dt, NumberOfFrames=6)
dfn = DEMFracturesToDFN(Input=lt)
cut = DEMSection(Input=lt)
after = PassArrays(Input=lt)
c.check(list(dfn.TimestepValues)[1] == 2.7 * dt, "before the run a filter after the stage lists k x Frame Interval")
lt.UpdatePipeline(list(lt.TimestepValues)[3])
model_times = list(lt.TimestepValues)
c.check(model_times[1] == 3 * dt, "after a frame the stage lists the model's times (3 steps a frame)")
c.check(list(dfn.TimestepValues) == model_times and list(cut.TimestepValues) == model_times,
        "the filters downstream list the same model times (DFN %s, Section %s, stage %s)"
        % (list(dfn.TimestepValues)[1], list(cut.TimestepValues)[1], model_times[1]))
keeper = list(GetTimeKeeper().TimestepValues)
c.check(model_times[3] in keeper and all(t in model_times for t in keeper),
        "the time keeper lists the model's times, none of the k x Frame Interval grid")
after.UpdatePipeline(model_times[3])
c.check(after.GetDataInformation().DataInformation.GetTime() == model_times[3],
        "a ParaView filter downstream shows the frame at its model time")
for proxy in (after, cut, dfn, lt):
    Delete(proxy)

# (b) 1e9 frames: refused, nothing materialised.
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
huge = DEMLoadTest(Input=pack, FrameInterval=0.002, NumberOfFrames=1000000000)
huge.UpdatePipeline(0.0)
grown_mb = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024.0
c.check("Number Of Frames = 1000000000 is out of range" in huge.Status and "100000" in huge.Status,
        "Number Of Frames 1e9 is refused, naming the range: %s" % huge.Status[:100])
c.check(grown_mb < 200.0 and not huge.TimestepValues, "and nothing was materialised (the process grew %.0f MB)" % grown_mb)
Delete(huge)

# (c) A stage says how long it is before it steps.
messages.Flush()
long_stage = DEMLoadTest(Input=pack, FrameInterval=1.0e6, NumberOfFrames=1)
long_stage.UpdatePipeline(0.0)
steps = long_stage.EstimatedSteps
c.check(abs(steps - round(1.0e6 / dt)) <= 1.0 and long_stage.EstimatedRunTime > 3600.0 and long_stage.ModelTime == 0.0,
        "Frame Interval 1e6 s: Estimated Steps %.4g, Estimated Run Time %.3g s, known before a step is taken" % (
            steps, long_stage.EstimatedRunTime))
c.check("particle-steps/s" in messages.GetOutput() and "It can be stopped" in messages.GetOutput(),
        "and a warning in Output Messages says so before it runs")
messages.Flush()

# (d) Ctrl-C stops it between batches.
# From another process: ParaView holds Python's lock while the stage steps.
subprocess.Popen(["sh", "-c", "sleep 1; kill -INT %d" % os.getpid()])
started = time.time()
long_stage.UpdatePipeline(1.0e6)
took = time.time() - started
c.check(took < 30.0 and "interrupted (Ctrl-C)" in long_stage.Status,
        "Ctrl-C stopped the 1e6 s frame after %.1f s, and pvpython kept running" % took)
c.check(long_stage.ModelTime == 0.0 and long_stage.GetDataInformation().DataInformation.GetTime() == 0.0,
        "the output is the last whole frame (t = %g s): %s" % (long_stage.ModelTime, long_stage.Status[:90]))
started = time.time()
long_stage.UpdatePipeline(2.0e6)
c.check(time.time() - started < 5.0 and "interrupted" in long_stage.Status,
        "the stopped stage stays stopped (a script's loop over frames ends too)")
Delete(long_stage)
print("elapsed %.1f s" % (time.time() - T0))

# (e) Number Of Frames 0: until the test finishes; Mode Off: until settled.
press = DEMLoadTest(Input=pack, Mode="Compression", Gravity=[0, 0, 0], StrainRate=2.0, MaxStrain=0.004,
                    FrameInterval=0.0002)
press.UpdatePipeline(0.0)
estimate = press.EstimatedSteps
press.UpdatePipeline(rockdem.END_OF_RUN)
done_time = press.GetDataInformation().DataInformation.GetTime()
frames = list(press.TimestepValues)
steps_run = round(done_time / press.Timestep)
c.check(press.Stage == "done" and rockdem.read_only(press, "Finished") == 1 and frames[-1] == done_time,
        "Number Of Frames 0: the test ran until Stage done, and its frames end there (%d frames, %.6g s)" % (
            len(frames) - 1, done_time))
c.check(0.8 <= steps_run / estimate <= 1.25,
        "Estimated Steps %.0f was within 25 %% of the %d steps the test took" % (estimate, steps_run))
settle = DEMLoadTest(Input=pack, FrameInterval=0.005)
settle.UpdatePipeline(rockdem.END_OF_RUN)
c.check(rockdem.read_only(settle, "Finished") == 1 and "settled" in settle.Status and settle.UnbalancedForceRatio < 0.01,
        "Mode Off, Number Of Frames 0: ran until settled (unbalanced force ratio %.3g, %d frames)" % (
            settle.UnbalancedForceRatio, len(settle.TimestepValues) - 1))
Delete(press)
print("elapsed %.1f s" % (time.time() - T0))

# (f) The pack's presses are recorded in a saved state.
work = tempfile.mkdtemp(prefix="rockdem_time_")
grown = DEMPackSource(registrationName="Grown", InitialElements=200, XDimension=0.02, YDimension=0.02,
                      ZDimension=0.02, MinimumSize=0.001, MaximumSize=0.0015, RandomSeed=2)
grown.InvokeCommand("AddElements")
grown.InvokeCommand("GrowElements")
grown.UpdatePipeline()
count, porosity = grown.NumberOfElements, grown.CurrentPorosity
SaveState(os.path.join(work, "pack.pvsm"))
ResetSession()
load_rockdem(globals())
LoadState(os.path.join(work, "pack.pvsm"))
again = FindSource("Grown")
again.UpdatePipeline()
c.check(again.Commands == "AG" and again.NumberOfElements == count and again.CurrentPorosity == porosity,
        "the saved state recorded Add/Grow (Commands %s) and rebuilt the same pack: %d elements, porosity %.6g" % (
            again.Commands, again.NumberOfElements, again.CurrentPorosity))

# (g) Resume From Checkpoint.
checkpoint = os.path.join(work, "settle.rdem")
first = DEMLoadTest(Input=again, FrameInterval=0.002, NumberOfFrames=8, CheckpointFile=checkpoint)
first.UpdatePipeline(rockdem.END_OF_RUN)
computed = vtk_to_numpy(servermanager.Fetch(first).GetBlock(0).GetPoints().GetData()).copy()
c.check(os.path.exists(checkpoint + ".stage"), "the checkpoint has its record beside it (settle.rdem.stage)")
Delete(first)
messages.Flush()
second = DEMLoadTest(Input=again, FrameInterval=0.002, NumberOfFrames=8, CheckpointFile=checkpoint)
second.UpdatePipeline(rockdem.END_OF_RUN)
resumed = vtk_to_numpy(servermanager.Fetch(second).GetBlock(0).GetPoints().GetData()).copy()
c.check(said("taken from the Checkpoint File") and (resumed == computed).all(),
        "the same stage took frame 8 from its checkpoint, bitwise the computed one")
again.RandomSeed = 3
second.UpdatePipeline(rockdem.END_OF_RUN)
c.check(said("holds another run"), "after an upstream change the checkpoint is ignored (and said so)")
print("elapsed %.1f s" % (time.time() - T0))
c.finish()
