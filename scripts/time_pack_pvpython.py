"""Times RockDEM on a pack file through the user's path, for scripts/benchmark_mono_pack.sh.

  pvpython scripts/time_pack_pvpython.py PACK --steps N --threads T [--repeat R] [--frames F]

The pack ("# key value" header, "id type diameter density x y z" rows; see
scripts/liggghts_deck.py) is written as a CSV of x, y, z, Radius and read as ParaView
reads any point table: CSV Reader -> Table To Points -> DEM Model From Points (the pack's
box, not Fit To Input; its material) -> DEM Load Test, Mode Off, Settling Damping 0 (no
Cundall damping, like LIGGGHTS), Requested Timestep = the pack's timestep (Timestep
Safety 0.2, so that 5e-6 s on 1 mm grains is accepted), frames of N steps. Timed: the
UpdatePipeline of the F frames after the first (F = 1 by default; each is N steps and the
frame's output; the first frame holds the solver's set-up, as LIGGGHTS's "Loop time"
leaves out its set-up). --steps 1 --frames 30 measures what a frame costs besides its
steps. Prints one line per run: "run K threads T steps S seconds X pstep_s Y contacts C
timestep DT frames F path P" (X for the F frames); ROCKDEM_PLUGIN names the built plugin.
"""
import argparse
import os
import sys
import tempfile
import time

from paraview.simple import CSVReader, Delete, LoadPlugin, TableToPoints  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("pack")
ap.add_argument("--steps", type=int, default=2000)
ap.add_argument("--threads", type=int, default=1)
ap.add_argument("--repeat", type=int, default=1)
ap.add_argument("--frames", type=int, default=1, help="frames timed after the first (>= 1)")
a = ap.parse_args()
if a.frames < 1 or a.steps < 1:
    sys.exit("--frames (%d) and --steps (%d) must be at least 1" % (a.frames, a.steps))

plugin = os.environ.get("ROCKDEM_PLUGIN")
if not plugin or not os.path.exists(plugin):
    sys.exit("ROCKDEM_PLUGIN must name the built RockDEM plugin (got %r)" % plugin)
LoadPlugin(plugin, remote=False, ns=globals())
import rockdem  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from liggghts_deck import read_pack  # noqa: E402

header, lines = read_pack(a.pack)
hdr = {k: [float(x) for x in v] for k, v in header.items() if k in (
    "box", "timestep", "density", "youngs_modulus", "poissons_ratio", "restitution", "friction", "gravity")}
rows = [line.split() for line in lines]
g = lambda k: hdr[k][0]
xlo, xhi, ylo, yhi, zlo, zhi = hdr["box"]
dt = g("timestep")
csv = tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False)
csv.write("x,y,z,Radius\n")
for r in rows:
    csv.write("%s,%s,%s,%.17g\n" % (r[4], r[5], r[6], 0.5 * float(r[2])))
csv.close()

for run in range(a.repeat):
    table = CSVReader(FileName=[csv.name])
    points = TableToPoints(Input=table, XColumn="x", YColumn="y", ZColumn="z")
    model = DEMModelFromPoints(Input=points, FitToInput=0, OriginX=xlo, OriginY=ylo, OriginZ=zlo,  # noqa: F821
                               XDimension=xhi - xlo, YDimension=yhi - ylo, ZDimension=zhi - zlo,
                               Density=g("density"), YoungsModulus=g("youngs_modulus"),
                               PoissonsRatio=g("poissons_ratio"), Restitution=g("restitution"),
                               Friction=g("friction"))
    model.UpdatePipeline()
    message = rockdem.read_only(model, "LastMessage")
    if rockdem.read_only(model, "NumberOfElements") != len(rows):
        sys.exit("DEM Model From Points made %s elements of %d: %s"
                 % (rockdem.read_only(model, "NumberOfElements"), len(rows), message))
    test = DEMLoadTest(Input=model, Mode="Off", SettlingDamping=0.0, TimestepSafety=0.2,  # noqa: F821
                       RequestedTimestep=dt, Gravity=[0.0, 0.0, -g("gravity")], Threads=a.threads,
                       FrameInterval=a.steps * dt, NumberOfFrames=1 + a.frames)
    test.UpdatePipeline(a.steps * dt)  # frame 1: the solver's set-up and N steps, not timed
    start = time.perf_counter()
    for frame in range(2, 2 + a.frames):
        test.UpdatePipeline(frame * a.steps * dt)  # N more steps and the frame's output
    seconds = time.perf_counter() - start
    used = rockdem.read_only(test, "Timestep")
    path = rockdem.read_only(test, "SolverPath")
    contacts = rockdem.read_only(test, "NumberOfContacts")
    status = rockdem.read_only(test, "LastMessage")
    if abs(used - dt) > 1e-12 * dt:
        sys.exit("DEM Load Test ran at %g s, not the pack's %g s (%s)" % (used, dt, status))
    print("run %d threads %d steps %d seconds %.6f pstep_s %.6g contacts %s timestep %.9g frames %d path %s"
          % (run, a.threads, a.steps, seconds, len(rows) * a.steps * a.frames / seconds, contacts, used,
             a.frames, path))
    sys.stdout.flush()
    for proxy in (test, model, points, table):
        Delete(proxy)
os.unlink(csv.name)
