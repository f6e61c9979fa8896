"""pvpython: the virtual press of DEM Load Test (issue "Virtual press").

Reference guide "Loading the model", "The DEM Test chart", "Keeping the results";
Documentation/LoadTest.md. On a small grown specimen without gravity:
(a) Isotropic: Stage reaches done and every face holds the Confining Stress within 2 %;
(b) Triaxial: Stage goes consolidate -> shear and the side faces hold the confining stress
    within 2 % through shear;
(c) output port 1 (History) has the engine's columns plus the plot columns, SaveData writes
    it as CSV with a header, and History File writes it too;
(d) Mode Off restores the six walls at the box;
(e) a bad setting is named in Status and gives no output;
(f) cemented specimen, unconfined compression: the axial stress peaks and bonds break;
    Suggested Strain Rate is known before the run.
"""
import csv
import shutil
import time
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, Messages, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

ENGINE_COLUMNS = [
    "Time (s)", "Step", "Strain X", "Strain Y", "Strain Z", "Volumetric Strain",
    "Stress X- (Pa)", "Stress X+ (Pa)", "Stress Y- (Pa)", "Stress Y+ (Pa)", "Stress Z- (Pa)",
    "Stress Z+ (Pa)", "Sigma XX (Pa)", "Sigma YY (Pa)", "Sigma ZZ (Pa)", "Sigma XY (Pa)",
    "Sigma YZ (Pa)", "Sigma ZX (Pa)", "Axial Stress (Pa)", "Lateral Stress (Pa)",
    "Deviator Stress (Pa)", "Broken In Tension", "Broken In Shear", "Unbalanced Force Ratio",
    "Inertial Number", "Stage", "Mean Stress (Pa)", "Gauge Strain"]
PLOT_COLUMNS = ["Axial Strain (%)", "Volumetric Strain (%)", "Axial Stress (MPa)",
                "Lateral Stress (MPa)", "Deviator Stress (MPa)"]
FACES = ["Stress X- (Pa)", "Stress X+ (Pa)", "Stress Y- (Pa)", "Stress Y+ (Pa)",
         "Stress Z- (Pa)", "Stress Z+ (Pa)"]
SIGMA3 = 1e5
DT = 0.002  # s per frame


def table_of(proxy, t):
    """The History table (port 1) at time t, as {column: [values]}."""
    proxy.UpdatePipeline(t)
    table = servermanager.Fetch(proxy, idx=1)
    proxy.UpdatePropertyInformation()  # attribute access reads the cached information
    return {table.GetColumnName(c): [table.GetColumn(c).GetValue(r) for r in range(table.GetNumberOfRows())]
            for c in range(table.GetNumberOfColumns())}, [table.GetColumnName(c) for c in range(table.GetNumberOfColumns())]


def run_until(proxy, stage, frames):
    """Advance frame by frame until Stage is stage (or the frames run out); stages seen."""
    seen = []
    for f in range(frames + 1):
        proxy.UpdatePipeline(f * DT)
        s = rockdem.read_only(proxy, "Stage")
        if not seen or seen[-1] != s:
            seen.append(s)
        if s == stage:
            return f * DT, seen
    return None, seen


c = Checks()
T0 = time.time()
messages = Messages()
tmp = tempfile.mkdtemp(prefix="rockdem_press_")
pack = DEMPackSource(InitialElements=700, XDimension=0.02, YDimension=0.02, ZDimension=0.02,
                     MinimumSize=0.0008, MaximumSize=0.0011, YoungsModulus=1e8, RandomSeed=1)
pack.InvokeCommand("GrowElements")
pack.UpdatePipeline()

# (a) Isotropic.
history_file = os.path.join(tmp, "history_file.csv")
iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=SIGMA3,
                  FrameInterval=DT, NumberOfFrames=60, SampleInterval=100, HistoryFile=history_file)
c.check(len(iso.TimestepValues) == 61, "publishes 61 frames")
t_done, stages = run_until(iso, "done", 60)
c.check(t_done is not None, "Isotropic: Stage reaches done (stages %s, at t = %s s)" % (stages, t_done))
c.check(stages[0] == "consolidate", "Isotropic starts in consolidate")
t_iso = t_done if t_done is not None else 60 * DT
cols, names = table_of(iso, t_iso)
last = {n: cols[n][-1] for n in names}
for face in FACES:
    c.check(abs(last[face] - SIGMA3) <= 0.02 * SIGMA3, "Isotropic: %s = %.5g Pa within 2 %% of 1e5" % (face, last[face]))
c.check(abs(rockdem.read_only(iso, "LateralStress") - SIGMA3) <= 0.02 * SIGMA3
        and abs(rockdem.read_only(iso, "AxialStress") - SIGMA3) <= 0.02 * SIGMA3,
        "read-only Axial Stress %.5g Pa and Lateral Stress %.5g Pa" % (iso.AxialStress, iso.LateralStress))
for name in ("AxialStrain", "VolumetricStrain", "DeviatorStress", "PeakStress", "InertialNumber", "SuggestedStrainRate"):
    c.check(isinstance(rockdem.read_only(iso, name), float), "read-only %s = %.4g" % (name, rockdem.read_only(iso, name)))
c.check(iso.SuggestedStrainRate > 0.0, "Suggested Strain Rate %.4g 1/s is positive" % iso.SuggestedStrainRate)
c.check(iso.VolumetricStrain > 0.0, "consolidation compacts the specimen (volumetric strain %.4g)" % iso.VolumetricStrain)

# (c) the History table: columns, derived columns, time stamp, CSV.
c.check(names == ENGINE_COLUMNS + PLOT_COLUMNS, "History columns: engine's then plot columns: %s" % names)
c.check(len(cols["Time (s)"]) > 3, "History has %d rows" % len(cols["Time (s)"]))
c.check(all(abs(a - 100.0 * b) < 1e-12 for a, b in zip(cols["Axial Strain (%)"], cols["Strain Z"])),
        "Axial Strain (%) is 100 x Strain Z (Axis Z)")
c.check(all(abs(a - 1e-6 * b) < 1e-15 for a, b in zip(cols["Deviator Stress (MPa)"], cols["Deviator Stress (Pa)"])),
        "Deviator Stress (MPa) is Deviator Stress (Pa) / 1e6")
table = servermanager.Fetch(iso, idx=1)
info = OutputPort(iso, 1).GetDataInformation()
c.check(table.IsA("vtkTable"), "port 1 is a vtkTable")
# Frames are whole steps: the stamp is the model's time of the frame asked for, which the
# stage publishes once it has run (within half a step per frame of k x Frame Interval).
frame_time = list(iso.TimestepValues)[int(round(t_iso / DT))]
c.check(abs(frame_time - t_iso) <= 0.5 * rockdem.read_only(iso, "Timestep") * round(t_iso / DT),
        "published frame time %.8g s is the model's time of frame %d" % (frame_time, round(t_iso / DT)))
c.check(iso.GetDataInformation().DataInformation.GetTime() == frame_time,
        "port 0 stamped with the frame time")
c.check(info.DataInformation.GetTime() == frame_time, "port 1 stamped with the frame time %.8g s" % frame_time)

saved = os.path.join(tmp, "saved.csv")
SaveData(saved, proxy=OutputPort(iso, 1))
with open(saved, newline="") as f:
    rows = list(csv.reader(f))
c.check(rows and rows[0] == names, "SaveData CSV header equals the column names: %s" % (rows[0] if rows else None))
c.check(len(rows) - 1 == len(cols["Time (s)"]), "SaveData CSV has one line per row (%d)" % (len(rows) - 1))


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b)) + 1e-300


c.check(all(close(float(v), cols[n][r - 1], 1e-4) for r in range(1, len(rows)) for n, v in zip(rows[0], rows[r])),
        "SaveData CSV values round-trip within the printed precision")
c.check(os.path.exists(history_file) and not os.path.exists(history_file + ".tmp"),
        "History File written (no temporary left)")
with open(history_file, newline="") as f:
    rows = list(csv.reader(f))
c.check(rows and rows[0] == names, "History File header equals the column names")
c.check(len(rows) - 1 == len(cols["Time (s)"]) and
        all(float(v) == cols[n][r - 1] for r in range(1, len(rows)) for n, v in zip(rows[0], rows[r])),
        "History File values round-trip exactly")

# The chart helper.
view = rockdem.show_test_chart(iso)
disp = GetDisplayProperties(OutputPort(iso, 1), view)
c.check(view.GetXMLName() == "XYChartView" and disp.XArrayName == "Axial Strain (%)" and disp.UseIndexForXAxis == 0,
        "show_test_chart: line chart against Axial Strain (%)")
c.check(sorted(disp.SeriesVisibility) == sorted(PLOT_COLUMNS[1:]), "chart series: %s" % list(disp.SeriesVisibility))
Delete(view)

print("elapsed %.1f s" % (time.time() - T0))
# (b) Triaxial on the same pack.
tri = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Triaxial", ConfiningStress=SIGMA3, StrainRate=0.5,
                  MaxStrain=0.02, FrameInterval=DT, NumberOfFrames=60, SampleInterval=100)
t_shear, stages = run_until(tri, "shear", 60)
c.check(t_shear is not None and stages[0] == "consolidate", "Triaxial: Stage goes %s" % " -> ".join(stages))
t_end = min(60 * DT, (t_shear or 0.0) + 10 * DT)
cols, names = table_of(tri, t_end)
shear_rows = [r for r, s in enumerate(cols["Stage"]) if s == 2]
c.check(len(shear_rows) >= 3, "Triaxial: %d history rows during shear" % len(shear_rows))
worst = max([abs(cols[face][r] - SIGMA3) / SIGMA3 for r in shear_rows for face in FACES[:4]] or [1.0])
c.check(worst <= 0.02, "Triaxial: side faces X-/X+/Y-/Y+ within 2 %% of 1e5 through shear (worst %.3g %%)" % (100 * worst))
c.check(cols["Deviator Stress (Pa)"][shear_rows[-1]] > 0 if shear_rows else False,
        "Triaxial: deviator stress rises in shear (%.4g Pa)" % (cols["Deviator Stress (Pa)"][shear_rows[-1]] if shear_rows else 0))
print("triaxial at %.4g s: stage %s, axial %.5g Pa, lateral %.5g Pa, deviator %.5g Pa, peak %.5g Pa" % (
    t_end, tri.Stage, tri.AxialStress, tri.LateralStress, tri.DeviatorStress, tri.PeakStress))
peak_row = max(cols["Axial Stress (Pa)"])
c.check(tri.PeakStress >= peak_row * (1 - 1e-12) and tri.PeakStress > SIGMA3,
        "Peak Stress %.5g Pa is the largest sampled axial stress (%.5g Pa)" % (tri.PeakStress, peak_row))

# The chart of a triaxial test plots the shear rows only (strains count from the start
# of shear), and asks for the frame the test reached, not a later one.
step_before = rockdem.read_only(tri, "ModelTime")
view = rockdem.show_test_chart(tri)
shown = [p for p in GetSources().values() if p.GetXMLName() == "ExtractSelection"]
plotted = servermanager.Fetch(shown[-1]) if shown else None
plotted_stage = [plotted.GetColumnByName("Stage").GetValue(r) for r in range(plotted.GetNumberOfRows())] if plotted else []
c.check(plotted_stage and set(plotted_stage) == {2.0} and len(plotted_stage) == len(shear_rows),
        "triaxial chart plots the %d shear rows only (of %d)" % (len(plotted_stage), len(cols["Stage"])))
c.check(rockdem.read_only(tri, "ModelTime") == step_before, "showing the chart did not run the test further")
Delete(view)

print("elapsed %.1f s" % (time.time() - T0))
# (d) Mode Off restores the six walls at the box.
tri.Mode = "Off"
tri.UpdatePipeline(DT)
model = servermanager.Fetch(tri)
fd = model.GetFieldData()
walls = fd.GetArray("WallState")
origin = [fd.GetArray("DomainOrigin").GetValue(k) for k in range(3)]
size = [fd.GetArray("DomainSize").GetValue(k) for k in range(3)]
ok = walls is not None and walls.GetNumberOfTuples() == 6
for w in range(6 if ok else 0):
    axis, side, position, _, active = walls.GetTuple(w)[:5]
    expected = origin[int(axis)] + (size[int(axis)] if side else 0.0)
    ok = ok and active == 1.0 and abs(position - expected) < 1e-12
c.check(ok, "Mode Off: six active walls at the box")
c.check(rockdem.read_only(tri, "Stage") == "idle", "Mode Off: Stage idle")

# (e) bad input is named; no output.
tri.Mode = "Compression"
tri.ServoAlpha = 2.0
tri.UpdatePipeline(DT)
status = rockdem.read_only(tri, "Status")
c.check("Servo Alpha" in status, "bad Servo Alpha is named: %s" % status)
c.check(tri.GetDataInformation().GetNumberOfPoints() == 0, "and there is no output")
c.check(OutputPort(tri, 1).GetDataInformation().DataInformation.GetNumberOfRows() == 0, "nor a history")
tri.ServoAlpha = 0.5
tri.Mode = "Triaxial"
tri.ConsolidationDamping = 1.0  # valid range [0, 1)
tri.UpdatePipeline(DT)
status = rockdem.read_only(tri, "Status")
c.check("Consolidation Damping = 1 is out of range: valid range is [0, 1)" in status,
        "bad Consolidation Damping is named with its value and range: %s" % status)
c.check(tri.GetDataInformation().GetNumberOfPoints() == 0, "and there is no output")
tri.ConsolidationDamping = 0.7

print("elapsed %.1f s" % (time.time() - T0))
# (f) cemented specimen, unconfined compression through the pipeline (a short run: the
# bonds shorten the timestep; the full test to failure is Testing/Solver/TestLoadTest.cpp).
cement = DEMCement(Input=iso, BondModulus=1e8, TensileStrength=1e6, Cohesion=2e6)
# The input has run (as after Apply on DEM Cement in the GUI) before the stage is made: the
# stage's information pass then sees the cemented model.
cement.UpdatePipeline()
press = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], Mode="Compression", StrainRate=1.0, MaxStrain=0.01,
                    FrameInterval=0.00025, NumberOfFrames=2, SampleInterval=50)
# Suggested Strain Rate before the run (the input has data; the stage has not stepped):
# inertial number 2.5e-5 (cemented) at the estimated peak, UCS ~ 0.35 x max(Tensile,
# Cohesion) x bond/grain area = 0.7e6 Pa: about 2.5e-5 / (1.9e-3 m x sqrt(2650 / 2.3e5)) = 0.12 1/s
# (Documentation/SpeedAccuracy.md).
press.UpdatePipelineInformation()
ahead = rockdem.read_only(press, "SuggestedStrainRate")
c.check(0.05 < ahead < 0.3, "Suggested Strain Rate before the run: %.4g 1/s (expected about 0.12)" % ahead)
messages.Flush()
cols, names = table_of(press, 0.0005)
# The specimen is 8.8 mean grain diameters across (700 grains grown in a 20 mm box to a mean
# diameter of 2.3 mm): narrower than the 11.9 from which the atlas measured Young's modulus
# converged, so the stage's start warns with what the atlas measured at the nearest width (9.0).
said = messages.GetOutput()
c.check("DEM Load Test: The specimen is 8.8 mean grain diameters across" in said
        and "a specimen 9 across measured the UCS" in said
        and "at least 11.9 across" in said,
        "Output Messages: the resolution advice for a cemented specimen narrower than 11.9 across: %s"
        % said[said.find("The specimen is"):][:160])
c.check(rockdem.read_only(press, "SuggestedStrainRate") >= ahead * (1 - 1e-9),
        "after two frames it is refined, never lower: %.4g 1/s" % press.SuggestedStrainRate)
axial = cols["Axial Stress (Pa)"]
c.check(rockdem.read_only(press, "Bonds") > 0, "the compressed specimen is cemented (%d bonds)" % press.Bonds)
c.check(press.Stage == "shear" and len(axial) > 1, "Compression: stage shear, %d history rows" % len(axial))
c.check(press.AxialStress > 0 and press.PeakStress >= max(axial) * (1 - 1e-12) > 0,
        "Compression: axial stress %.4g Pa, Peak Stress %.4g Pa" % (press.AxialStress, press.PeakStress))
c.check(max(cols["Lateral Stress (Pa)"]) == 0.0 and press.LateralStress == 0.0, "unconfined: no lateral stress")
c.check(press.InertialNumber > 0, "Inertial Number %.3g" % press.InertialNumber)
print("elapsed %.1f s" % (time.time() - T0))
shutil.rmtree(tmp, ignore_errors=True)
c.finish()
