"""pvbatch (under xvfb): seeing inside a failed specimen (Documentation/Sections.md).

Reference guide "Cut sections" and "Current limitations" (sections do not render, Convert
to Voxel Model produces an empty model, sprites cast no shadows and flatten when zoomed);
issue "Seeing inside the rock". A small cemented specimen (about 600 particles) is loaded
in unconfined compression until the axial stress has fallen to 60 % of its peak, then:
(a) the Particles block carries Stress / MeanStress / VonMisesStress after every DEM Load
    Test frame, and a model saved and read back (DEM State Writer / Reader) shows the same
    values bit for bit;
(b) DEM Section (XZ through the middle): circles carrying the particle arrays, bonds
    crossing, broken-bond traces coloured by FailureMode; it follows time (a frame before
    the peak has fewer traces, each output is stamped with the frame's time) and plays
    (AnimationScene.Play over the last frames leaves it at the last frame); rendered;
(c) DEM Voxelize with a square fracture (a Plane source) as its Fractures: the fields,
    solid volume, damage, fracture intensity; Contour and Slice work on it; volume
    rendering; Save Data writes a .vti that reads back with the same values; and with the
    specimen's own DFN (DEM Fractures To DFN): its disc area and sets;
(d) close-up rendering: true spheres (3D Glyphs), without and with the shadow-map pass;
    the pictures are not blank; a ball above a floor darkens the floor where its shadow
    falls (rockdem.enable_shadows);
(e) bad input: a plane that misses the model (empty, a message, no error), Voxel Size 0,
    a grid over the Memory Limit (errors naming value and limit, no output).
"""
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

T0 = time.time()
c = Checks()
tmp = tempfile.mkdtemp(prefix="rockdem_sections_")
pictures = os.environ.get("ROCKDEM_TEST_OUTPUT", tmp)
os.makedirs(pictures, exist_ok=True)


def block(data, name):
    for k in range(data.GetNumberOfBlocks()):
        if data.HasMetaData(k) and data.GetMetaData(k).Get(data.NAME()) == name:
            return data.GetBlock(k)
    return None


def not_blank(path, min_fraction=0.02):
    """Fraction of the picture's pixels that differ from its corner pixel (the background)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = reader.GetOutput().GetPointData().GetScalars()
    n = pixels.GetNumberOfTuples()
    background = pixels.GetTuple(0)
    differ = sum(1 for i in range(0, n, 7) if pixels.GetTuple(i)[:3] != background[:3])
    fraction = differ * 7.0 / n
    return fraction >= min_fraction, fraction


def pixel_brightness(path, points):
    """Mean of R, G, B (0-255) of the picture's pixels at display points (x, y)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = reader.GetOutput().GetPointData().GetScalars()
    nx = reader.GetOutput().GetDimensions()[0]
    return [sum(pixels.GetTuple(int(round(y)) * nx + int(round(x)))[:3]) / 3.0 for x, y in points]


# The failed specimen (as Testing/Python/test_fractures.py, smaller).
pack = DEMPackSource(InitialElements=600, XDimension=0.016, YDimension=0.016, ZDimension=0.016,
                     MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=3)
pack.InvokeCommand("GrowElements")
iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=2e4,
                  FrameInterval=0.002, NumberOfFrames=6, SampleInterval=200)
cement = DEMCement(Input=iso, BondModulus=2e7, TensileStrength=2e5, Cohesion=4e5, StrengthScatter=0.2,
                   GapTolerance=0.1)
press, t_stop = rockdem.compress_until_failure(cement, StrainRate=1.0, MaxStrain=0.04, FrameInterval=0.0005,
                                               NumberOfFrames=80, SampleInterval=200)
times = list(press.TimestepValues)
c.check(t_stop is not None, "the specimen fails (axial stress at 60 %% of the peak at t = %s s)" % t_stop)
t_stop = t_stop if t_stop is not None else times[-1]
t_before = times[times.index(t_stop) // 2]  # a frame half-way there, before most bonds broke
broken = rockdem.read_only(press, "BrokenBonds")
print("failed specimen: %d broken bonds at t = %.4g s (%.1f s)" % (broken, t_stop, time.time() - T0))

# (a) Particle stresses on every frame, and after a save and reload.
stress_ranges = []
for t in (t_before, t_stop):
    press.UpdatePipeline(t)
    particles = block(servermanager.Fetch(press), "Particles")
    arrays = [particles.GetPointData().GetArray(n) for n in ("Stress", "MeanStress", "VonMisesStress")]
    ok = all(a is not None for a in arrays) and arrays[0].GetNumberOfComponents() == 6
    stress_ranges.append(arrays[2].GetRange() if ok else (0, 0))
    c.check(ok and arrays[2].GetRange()[1] > 0, "frame t = %.4g s: Stress (6), MeanStress, VonMisesStress, "
            "largest von Mises %.4g Pa" % (t, stress_ranges[-1][1]))
c.check(stress_ranges[0] != stress_ranges[1], "the stresses change from frame to frame")
saved = os.path.join(tmp, "failed.rdem")
SaveData(saved, proxy=press)
original = block(servermanager.Fetch(press), "Particles").GetPointData().GetArray("Stress")
reader = DEMStateReader(FileName=saved)
reader.UpdatePipeline()
reloaded = block(servermanager.Fetch(reader), "Particles").GetPointData().GetArray("Stress")
same = reloaded is not None and reloaded.GetNumberOfTuples() == original.GetNumberOfTuples() and all(
    reloaded.GetTuple(i) == original.GetTuple(i) for i in range(original.GetNumberOfTuples()))
c.check(same, "a saved and reloaded model shows the same stresses bit for bit (%d particles)"
        % original.GetNumberOfTuples())

# (b) DEM Section through the middle, XZ.
section = rockdem.section(press, "XZ", origin=[0.008, 0.008, 0.008])
section.UpdatePipeline(t_stop)
message = rockdem.read_only(section, "LastMessage")
print("section:", message)
cut = rockdem.read_only(section, "CutParticles")
circles = servermanager.Fetch(section)
c.check(cut > 10 and circles.GetNumberOfPolys() == cut, "Section XZ cuts %d particles, one polygon each" % cut)
cd = circles.GetCellData()
c.check(all(cd.GetArray(n) is not None for n in ("Radius", "Displacement", "Stress", "VonMisesStress", "SizeClass",
                                                 "SectionRadius")),
        "the circles carry the particle arrays (Radius, Displacement, Stress, VonMisesStress, SizeClass)")
crossings = servermanager.Fetch(section, idx=1)
traces = servermanager.Fetch(section, idx=2)
n_traces = rockdem.read_only(section, "BrokenBondTraces")
c.check(crossings.GetNumberOfPoints() == rockdem.read_only(section, "CrossingBonds") > 0,
        "%d intact bonds cross the plane" % crossings.GetNumberOfPoints())
mode = traces.GetCellData().GetArray("FailureMode")
c.check(n_traces > 0 and traces.GetNumberOfLines() == n_traces and mode is not None and mode.GetRange()[0] >= 1,
        "%d broken-bond traces, FailureMode %s" % (n_traces, mode.GetRange() if mode else None))
c.check(abs(section.GetDataInformation().DataInformation.GetTime() - t_stop) < 1e-12,
        "the section is stamped with the frame time")
section.UpdatePipeline(t_before)
early = rockdem.read_only(section, "BrokenBondTraces")
c.check(early < n_traces, "the section follows time: %d traces at t = %.4g s, %d at t = %.4g s"
        % (early, t_before, n_traces, t_stop))

print("elapsed %.1f s" % (time.time() - T0))
view = CreateRenderView(ViewSize=[500, 500])
view.OrientationAxesVisibility = 0
rockdem.show_section(section, view, crossings=True)
view.CameraPosition = [0.008, -0.06, 0.008]
view.CameraFocalPoint = [0.008, 0.008, 0.008]
view.CameraViewUp = [0, 0, 1]
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
k_stop = times.index(t_stop)
scene.StartTime = times[k_stop - 3]
scene.EndTime = t_stop
scene.PlayMode = "Snap To TimeSteps"
scene.Play()
print("played, elapsed %.1f s" % (time.time() - T0))
c.check(abs(section.GetDataInformation().DataInformation.GetTime() - t_stop) < 1e-12,
        "Play over the last frames leaves the section at the last frame")
GetDisplayProperties(section, view).RescaleTransferFunctionToDataRange(False, True)  # the last frame's stresses
ResetCamera(view)
picture = os.path.join(pictures, "section.png")
SaveScreenshot(picture, view, ImageResolution=[500, 500])
ok, fraction = not_blank(picture)
c.check(ok, "the section renders in the 3D view (%.0f %% of the picture drawn): %s" % (100 * fraction, picture))
print("elapsed %.1f s" % (time.time() - T0))

# (c) DEM Voxelize with a fracture: a square through the middle (a Plane source; any
# polygonal DFN, such as DEM Fractures To DFN's discs, is rasterised the same way).
fracture = Plane(Origin=[-0.1, -0.1, 0.0081], Point1=[0.1, -0.1, 0.0081], Point2=[-0.1, 0.1, 0.0081])
voxels = rockdem.voxelize(press, number_of_voxels=12, fractures=fracture)
voxels.UpdatePipeline(t_stop)
print("elapsed %.1f s" % (time.time() - T0))
print("voxels:", rockdem.read_only(voxels, "LastMessage"))
image = servermanager.Fetch(voxels)
dims = image.GetDimensions()
c.check(image.IsA("vtkImageData") and max(dims) >= 12 and list(dims) == list(rockdem.read_only(voxels, "GridDimensions")),
        "a vtkImageData of %s voxels" % (dims,))
pd = image.GetPointData()
names = ("SolidFraction", "Bonds", "BrokenBonds", "Damage", "BrokenBondDensity", "Stress", "MeanStress",
         "DeviatoricStress", "Displacement", "FractureIntensity", "FractureSet")
c.check(all(pd.GetArray(n) is not None for n in names), "voxel arrays %s" % ", ".join(names))
spacing = image.GetSpacing()
volume = spacing[0] * spacing[1] * spacing[2]
solid = sum(pd.GetArray("SolidFraction").GetTuple1(i) for i in range(image.GetNumberOfPoints())) * volume
c.check(abs(solid - rockdem.read_only(voxels, "SolidVolume")) < 1e-9 * solid,
        "solid volume %.4g m^3 (Solid Volume read-only value)" % solid)
brokenInVoxels = sum(pd.GetArray("BrokenBonds").GetTuple1(i) for i in range(image.GetNumberOfPoints()))
c.check(0 < brokenInVoxels <= broken and pd.GetArray("Damage").GetRange()[1] > 0,
        "%d of the %d broken bonds lie in the grid; damage up to %.2f" % (
            brokenInVoxels, broken, pd.GetArray("Damage").GetRange()[1]))
area = rockdem.read_only(voxels, "FractureArea")
grid_area = dims[0] * spacing[0] * dims[1] * spacing[1]
p32 = pd.GetArray("FractureIntensity")
c.check(abs(area - grid_area) < 1e-9 * grid_area and abs(p32.GetRange()[1] - 1.0 / spacing[2]) < 1e-6 / spacing[2],
        "the fracture is rasterised: %.4g m^2 inside the grid (%.4g expected), P32 up to %.4g 1/m (1 / voxel)"
        % (area, grid_area, p32.GetRange()[1]))
contour = Contour(Input=voxels, ContourBy=["POINTS", "SolidFraction"], Isosurfaces=[0.3])
contour.UpdatePipeline(t_stop)
slice_ = Slice(Input=voxels)
slice_.SliceType.Origin = [0.008, 0.008, 0.008]
slice_.SliceType.Normal = [0, 1, 0]
slice_.UpdatePipeline(t_stop)
c.check(contour.GetDataInformation().GetNumberOfCells() > 0 and slice_.GetDataInformation().GetNumberOfCells() > 0,
        "Contour (%d cells) and Slice (%d cells) work on the voxel model" % (
            contour.GetDataInformation().GetNumberOfCells(), slice_.GetDataInformation().GetNumberOfCells()))
vti = os.path.join(tmp, "voxels.vti")
# Data Mode Binary (base64 inside each array): VTK 9.1's XML readers cannot read an
# appended-data section (raw or encoded) with Debian 12's security-updated expat
# (libexpat1 2.5.0-1+deb12u5 defers reparsing); Sections.md, "Saving a voxel model".
SaveData(vti, proxy=voxels, DataMode="Binary")
back = servermanager.Fetch(XMLImageDataReader(FileName=[vti]))
damage, damage_back = pd.GetArray("Damage"), back.GetPointData().GetArray("Damage")
c.check(back.GetDimensions() == dims and damage_back is not None and all(
    damage_back.GetTuple1(i) == damage.GetTuple1(i) for i in range(damage.GetNumberOfTuples())),
    "Save Data writes a .vti that reads back with the same Damage")
# The DFN of the specimen's own broken bonds (DEM Fractures To DFN with its defaults) on
# the Fractures input: the fracture area in the grid is the discs' polygon area (CellSize,
# independent of the filter), all inside the grid (a Margin of half the specimen), and
# FractureSet takes the discs' Set values.
dfn = DEMFracturesToDFN(Input=press)
dfn.UpdatePipeline(t_stop)
discs = servermanager.Fetch(dfn)
sizes = servermanager.Fetch(CellSize(Input=dfn, ComputeArea=1, ComputeSum=1))
disc_area = sum(sizes.GetCellData().GetArray("Area").GetTuple1(k) for k in range(sizes.GetNumberOfCells()))
dfn_voxels = rockdem.voxelize(press, number_of_voxels=12, fractures=dfn, Margin=0.5)  # room for whole discs
dfn_voxels.UpdatePipeline(t_stop)
dfn_image = servermanager.Fetch(dfn_voxels)
grid_bounds = dfn_image.GetBounds()
half = [0.5 * s for s in dfn_image.GetSpacing()]  # the image's points are the voxels' centres
inside = all(grid_bounds[2 * a] - half[a] <= discs.GetBounds()[2 * a] and
             discs.GetBounds()[2 * a + 1] <= grid_bounds[2 * a + 1] + half[a] for a in range(3))
dfn_sets = set(int(discs.GetCellData().GetArray("Set").GetTuple1(k)) for k in range(discs.GetNumberOfCells()))
fracture_set = dfn_image.GetPointData().GetArray("FractureSet")
voxel_sets = set(int(fracture_set.GetTuple1(i)) for i in range(fracture_set.GetNumberOfTuples()))
dfn_area = rockdem.read_only(dfn_voxels, "FractureArea")
c.check(discs.GetNumberOfCells() > 0 and
        inside and abs(dfn_area - disc_area) < 1e-9 * disc_area and
        voxel_sets - {-1} <= dfn_sets,
        "the specimen's DFN (%d discs, %.4g m^2, %s the grid, sets %s) is rasterised: %.4g m^2 in the grid, "
        "FractureSet %s" % (discs.GetNumberOfCells(), disc_area, "inside" if inside else "partly outside",
                            sorted(dfn_sets), dfn_area, sorted(voxel_sets)))
voxels.UpdatePipeline(t_before)
image_early = servermanager.Fetch(voxels)
c.check(image_early.GetDimensions() == dims and
        image_early.GetPointData().GetArray("Damage").GetRange()[1] <= pd.GetArray("Damage").GetRange()[1],
        "the voxel model follows time on a fixed grid (same dimensions at t = %.4g s)" % t_before)
view2 = CreateRenderView(ViewSize=[500, 500])
view2.OrientationAxesVisibility = 0
view2.ViewTime = t_stop
rockdem.show_voxels(voxels, view2, "Damage")
ResetCamera(view2)
picture = os.path.join(pictures, "voxel_damage.png")
SaveScreenshot(picture, view2, ImageResolution=[500, 500])
ok, fraction = not_blank(picture, 0.01)
c.check(ok, "the damage volume-renders (%.0f %% of the picture drawn): %s" % (100 * fraction, picture))
print("elapsed %.1f s" % (time.time() - T0))

# (d) Close-up rendering: true spheres, and with shadows.
for shadows in (False, True):
    view3 = CreateRenderView(ViewSize=[400, 400])
    view3.OrientationAxesVisibility = 0
    rockdem.show_as_sphere_glyphs(reader, view3, shadows=shadows, resolution=12)
    view3.CameraPosition = [0.05, -0.04, 0.04]
    view3.CameraFocalPoint = [0.008, 0.008, 0.007]
    view3.CameraViewUp = [0, 0, 1]
    ResetCamera(view3)
    picture = os.path.join(pictures, "spheres%s.png" % ("_shadows" if shadows else ""))
    SaveScreenshot(picture, view3, ImageResolution=[400, 400])
    ok, fraction = not_blank(picture)
    c.check(ok, "true spheres%s render (%.0f %% of the picture drawn): %s" % (
        " with shadows" if shadows else "", 100 * fraction, picture))

# Shadows are cast: a ball above a floor, lit by enable_shadows from the +X side above.
# Looking straight down, the floor where the ball's shadow falls (x < 0) is dark, its
# mirror image (x > 0) lit; with the ball hidden both are lit alike.
view4 = CreateRenderView(ViewSize=[400, 400])
view4.OrientationAxesVisibility = 0
floor = Show(Plane(Origin=[-0.04, -0.04, 0], Point1=[0.04, -0.04, 0], Point2=[-0.04, 0.04, 0]), view4)
floor.ColorArrayName = ["POINTS", ""]
ball = Show(Sphere(Center=[0, 0, 0.01], Radius=0.004, ThetaResolution=32, PhiResolution=32), view4)
ball.ColorArrayName = ["POINTS", ""]
view4.CameraPosition = [0, 0, 0.3]
view4.CameraFocalPoint = [0, 0, 0]
view4.CameraViewUp = [0, 1, 0]
view4.CameraParallelProjection = 1
ResetCamera(view4)
rockdem.enable_shadows(view4, direction=(1.0, 0.0, 1.0))
probes = []
for x in (-0.0105, 0.0105):  # the centre of the ball's shadow on the floor, and its mirror image
    view4.GetRenderer().SetWorldPoint(x, 0.0, 0.0, 1.0)
    view4.GetRenderer().WorldToDisplay()
    probes.append(view4.GetRenderer().GetDisplayPoint()[:2])
brightness = []
for visible in (1, 0):
    ball.Visibility = visible
    picture = os.path.join(pictures, "shadow_probe%s.png" % ("" if visible else "_no_ball"))
    SaveScreenshot(picture, view4, ImageResolution=[400, 400])
    brightness.append(pixel_brightness(picture, probes))
c.check(brightness[0][0] < 0.7 * brightness[0][1] and brightness[1][0] > 0.9 * brightness[1][1],
        "a ball casts its shadow on the floor: brightness %.0f in its shadow, %.0f opposite; %.0f and %.0f "
        "without the ball" % (brightness[0][0], brightness[0][1], brightness[1][0], brightness[1][1]))

# (e) Bad input.
section.Origin = [0.008, 0.5, 0.008]  # Section XZ: the plane y = 0.5 m
section.UpdatePipeline(t_stop)
message = rockdem.read_only(section, "LastMessage")
c.check("misses the model" in message and section.GetDataInformation().GetNumberOfCells() == 0,
        "a plane that misses the model: empty, and the message says so: %s" % message)
voxels.SizeBy = "Voxel Size"
voxels.VoxelSize = 0.0
voxels.UpdatePipeline(t_stop)
message = rockdem.read_only(voxels, "LastMessage")
c.check("Voxel Size = 0 m" in message and voxels.GetDataInformation().GetNumberOfPoints() == 0,
        "Voxel Size 0 is named: %s" % message)
voxels.VoxelSize = 1e-6
voxels.UpdatePipeline(t_stop)
message = rockdem.read_only(voxels, "LastMessage")
c.check("Memory Limit is 2048 MiB" in message and voxels.GetDataInformation().GetNumberOfPoints() == 0,
        "a grid over the Memory Limit is named: %s" % message)
print("elapsed %.1f s" % (time.time() - T0))
shutil.rmtree(tmp, ignore_errors=True)
# Close the views before finish() exits: pvbatch leaving through sys.exit with render
# views open ends with an X error (GLXBadContext) and a failing exit status.
for view in GetRenderViews():
    rockdem.disable_shadows(view)
    Delete(view)
c.finish()
