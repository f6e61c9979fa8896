"""RockDEM helpers for pvpython and pvbatch.

Importable once the RockDEM plugin is loaded (``LoadPlugin(path, remote=False, ns=globals())``
then ``import rockdem``); also usable from a source checkout by putting ``Plugin/`` on
``sys.path``.
"""

from paraview import simple as _simple


def white_view(size, time=None, axes=True):
    """A new render view for pictures: white background (not the palette's), size [w, h]
    pixels, the view time (s) when given, the orientation axes shown or not."""
    view = _simple.CreateView("RenderView")
    view.ViewSize = list(size)
    if time is not None:
        view.ViewTime = time
    view.OrientationAxesVisibility = 1 if axes else 0
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view


def show_particles(source, view=None, port=0, color_by="Radius"):
    """Show a RockDEM model's particles as spheres of their true radius.

    The "DEM Spheres" representation (RockDEM.xml: a Point Gaussian with the Sphere
    shader, scaled by the Radius point array with no scale function), so the drawn radius
    equals the particle radius (m); RockDEM models get it by default, this sets it again
    for an output shown otherwise. Returns the representation.
    """
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    display = _simple.Show(_simple.OutputPort(source, port), view)
    # The plugin's representation: a Point Gaussian whose defaults draw a point as a sphere
    # of its Radius (Sphere shader, scaled by Radius, no scale function, Gaussian Radius 1).
    display.SetRepresentationType("DEM Spheres")
    if color_by:
        _simple.ColorBy(display, ("POINTS", color_by))
        display.RescaleTransferFunctionToDataRange(True, False)
    return display


def show_domain_box(source, view=None, port=1):
    """Show the model box (output port 1 of a model source) as a wireframe."""
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    display = _simple.Show(_simple.OutputPort(source, port), view)
    display.SetRepresentationType("Wireframe")
    display.ColorArrayName = ["POINTS", ""]
    display.AmbientColor = [0.2, 0.2, 0.2]
    display.DiffuseColor = [0.2, 0.2, 0.2]
    return display


def show_broken_bonds(source, view=None, color=(0.9, 0.0, 0.0), line_width=3.0):
    """Show a RockDEM model's broken bonds (the Bonds block's cells with Broken = 1) as
    lines of the given colour between the two particle centres. Returns the representation
    of the Threshold that selects them."""
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    broken = _simple.Threshold(Input=source, Scalars=["CELLS", "Broken"], LowerThreshold=1,
                               UpperThreshold=1, ThresholdMethod="Between")
    display = _simple.Show(broken, view)
    display.SetRepresentationType("Wireframe")
    display.ColorArrayName = ["CELLS", ""]
    display.AmbientColor = list(color)
    display.DiffuseColor = list(color)
    display.LineWidth = line_width
    return display


def read_only(proxy, name):
    """Current value of a read-only (information) property, refreshed from the server."""
    proxy.UpdatePropertyInformation()
    value = proxy.GetPropertyValue(name)
    if isinstance(value, (list, tuple)) and len(value) == 1:
        return value[0]
    return value


#: The History table columns the test chart shows (stresses on the left axis, MPa).
TEST_CHART_STRESSES = ("Axial Stress (MPa)", "Lateral Stress (MPa)", "Deviator Stress (MPa)")
#: Plotted on the right-hand axis, %.
TEST_CHART_RIGHT = "Volumetric Strain (%)"


def show_test_chart(load_test, view=None, shear_only=True):
    """Plot a DEM Load Test's History (output port 1) as the DEM Test chart.

    Axial, lateral and deviator stress (MPa) against axial strain (%), and volumetric
    strain (%) on the right-hand axis. Strains count from the start of shearing, so with
    shear_only (default) a test that has a shear stage plots only its shear rows (Stage
    2, picked by an ExtractSelection with the row query ``Stage == 2``): a triaxial
    test's consolidation rows would otherwise run to the consolidation strain and back.
    The query goes into the selection the way the GUI builds one (an AppendSelections
    of the query): ParaView 5.11's Properties panel expects that form and crashes on an
    Apply when an ExtractSelection's Selection is a bare selection source.
    In the GUI the DEM Test dock (View > DEM Test) is the chart; this helper is for
    pvbatch pictures.
    A test without shear rows (Isotropic) plots every row. The chart shows the test as
    far as it has been run (or to its last time step when it has not been run yet).
    Creates an XYChartView unless one is given; returns the view.
    """
    view = view or _simple.CreateView("XYChartView")
    times = list(load_test.TimestepValues or [])
    if times:
        # A view shows its own time (0 in a fresh pvbatch view): ask for the frame the
        # test has reached, so showing the chart does not run the test further.
        reached = float(read_only(load_test, "ModelTime") or 0.0)
        later = [t for t in times if t >= reached - 1e-12 * max(1.0, abs(reached))]
        view.ViewTime = later[0] if reached > times[0] and later else times[-1]
    history = _simple.OutputPort(load_test, 1)
    if shear_only:
        stage = fetch_history(load_test).get("Stage")
        if stage is not None and (_np().asarray(stage) == STAGE_SHEAR).any():
            history = _simple.ExtractSelection(Input=history, Selection=_row_query("Stage == %d" % STAGE_SHEAR))
    display = _simple.Show(history, view, "XYChartRepresentation")
    display.UseIndexForXAxis = 0
    display.XArrayName = "Axial Strain (%)"
    display.SeriesVisibility = list(TEST_CHART_STRESSES) + [TEST_CHART_RIGHT]
    corners = []
    for name in TEST_CHART_STRESSES:
        corners += [name, "0"]
    corners += [TEST_CHART_RIGHT, "1"]
    display.SeriesPlotCorner = corners
    colours = {"Axial Stress (MPa)": (0.84, 0.15, 0.16), "Lateral Stress (MPa)": (0.12, 0.47, 0.71),
               "Deviator Stress (MPa)": (1.0, 0.5, 0.05), TEST_CHART_RIGHT: (0.17, 0.63, 0.17)}
    display.SeriesColor = [v for name, rgb in colours.items() for v in [name] + ["%g" % c for c in rgb]]
    view.BottomAxisTitle = "Axial Strain (%)"
    view.LeftAxisTitle = "Stress (MPa)"
    view.RightAxisTitle = "Volumetric Strain (%)"
    return view


def _row_query(query):
    """A selection of table rows by a query, in the form the GUI builds: an AppendSelections
    proxy whose one input is the SelectionQuerySource (pqSelectionInputWidget reads the
    selection's Input property; a bare SelectionQuerySource has none)."""
    source = _simple.SelectionQuerySource(ElementType="Row Data", QueryString=query)
    return _simple.AppendSelections(Input=[source], Expression="s0", SelectionNames=["s0"])


# ---------------------------------------------------------------------------------------
# Analysis of load tests: history tables, elastic constants, the failure envelope.
#
# Conventions are the engine's: stresses compression positive, strains shortening
# positive, SI units (Pa, radians internally, degrees where named).
# ---------------------------------------------------------------------------------------

#: Rows of the History table whose Stage is this are the shear (loading) stage.
STAGE_SHEAR = 2

#: A time that asks a DEM Load Test for the end of its run: its last frame, or with
#: NumberOfFrames 0 the frame where the test finishes (``lt.UpdatePipeline(END_OF_RUN)``).
#: Stages downstream of a load test (DEM Cement) read it there.
END_OF_RUN = 1.0e300


def _np():
    import numpy
    return numpy


def history_to_dict(table):
    """Columns of a History table as {name: numpy array}.

    Accepts a fetched ``vtkTable`` (``servermanager.Fetch(load_test, idx=1)``) or a dict
    of columns (returned as a dict of float arrays).
    """
    np = _np()
    if isinstance(table, dict):
        return {k: np.asarray(v, dtype=float) for k, v in table.items()}
    out = {}
    for c in range(table.GetNumberOfColumns()):
        column = table.GetColumn(c)
        n = column.GetNumberOfTuples()
        out[table.GetColumnName(c)] = np.array([column.GetTuple1(r) for r in range(n)], dtype=float) \
            if n else np.zeros(0)
    return out


def fetch_history(load_test):
    """A DEM Load Test's History (output port 1) at its last update, as a dict of arrays."""
    from paraview import servermanager
    return history_to_dict(servermanager.Fetch(load_test, idx=1))


def _shear_rows(history):
    """Mask of the rows in the shear stage (all rows when there is no Stage column)."""
    np = _np()
    n = len(next(iter(history.values()))) if history else 0
    if "Stage" in history:
        mask = np.asarray(history["Stage"]) == STAGE_SHEAR
        if mask.any():
            return mask
    return np.ones(n, dtype=bool)


def fit_mohr_coulomb(confining_stresses, peak_axial_stresses):
    """Cohesion (Pa) and friction angle (degrees) of the Mohr-Coulomb envelope.

    The peaks of triaxial tests (sigma1, the peak axial stress) against their confining
    stresses (sigma3), compression positive, are fitted by least squares with the line

        sigma1 = a + b sigma3,

    which is the Mohr-Coulomb criterion written in principal stresses:

        b = (1 + sin phi) / (1 - sin phi)          so  sin phi = (b - 1) / (b + 1)
        a = 2 c cos phi / (1 - sin phi)            so  c = a (1 - sin phi) / (2 cos phi)

    (a is the unconfined compressive strength the envelope predicts). At least two
    distinct confining stresses are needed; a slope b < 1 (strength falling with
    confinement) has no Mohr-Coulomb meaning and raises ValueError.
    Returns (cohesion_Pa, friction_angle_deg).
    """
    import math
    np = _np()
    s3 = np.asarray(confining_stresses, dtype=float)
    s1 = np.asarray(peak_axial_stresses, dtype=float)
    if s3.shape != s1.shape or s3.size < 2 or np.ptp(s3) == 0.0:
        raise ValueError("fit_mohr_coulomb needs at least two distinct confining stresses "
                         "with one peak each")
    b, a = np.polyfit(s3, s1, 1)
    if b < 1.0:
        raise ValueError("slope d(sigma1)/d(sigma3) = %.4g < 1: no Mohr-Coulomb envelope" % b)
    sin_phi = (b - 1.0) / (b + 1.0)
    phi = math.asin(sin_phi)
    cohesion = a * (1.0 - sin_phi) / (2.0 * math.cos(phi))
    return float(cohesion), float(math.degrees(phi))


def mohr_coulomb_line(cohesion, friction_angle_deg):
    """(a, b) of sigma1 = a + b sigma3 for a cohesion (Pa) and friction angle (degrees)."""
    import math
    s = math.sin(math.radians(friction_angle_deg))
    c = math.cos(math.radians(friction_angle_deg))
    return 2.0 * cohesion * c / (1.0 - s), (1.0 + s) / (1.0 - s)


def elastic_constants(history, axis="Z", lower=0.10, upper=0.50):
    """Young's modulus (Pa) and Poisson's ratio from an unconfined compression history.

    history: a fetched History vtkTable or a dict of columns with ``Axial Stress (Pa)``,
    ``Strain X/Y/Z`` and, from histories written since it exists, ``Gauge Strain``. Uses
    the shear-stage rows before the peak whose axial stress lies between ``lower`` and
    ``upper`` (fractions) of the peak axial stress:

    - the axial strain is the Gauge Strain, the specimen's own strain (from the spread of
      its particle centres along the axis, as the laboratory's gauges on the specimen read
      it), where every row in the window has one; otherwise (older histories) the platen
      strain ``Strain <axis>``, which also holds the compliance of the grains' contacts
      with the platens (Documentation/Press.md, "Gauge Strain") and so reads E and nu low;
    - E is the slope of the least-squares line axial stress = E x axial strain + const
      through those rows (with exactly linear data it is the secant modulus);
    - the lateral strain is the mean of the two other axes' strains; strains in the
      table are shortening positive, so a bulging specimen has negative lateral strain,
      and nu = - d(lateral strain) / d(axial strain), again a least-squares slope. In
      unconfined compression there are no side walls: the lateral strains follow the
      spread of the particle centres (Documentation/Press.md, Measurements).

    Returns (youngs_modulus_Pa, poissons_ratio). Raises ValueError with fewer than two
    rows in the window.
    """
    np = _np()
    h = history_to_dict(history)
    axis = axis.upper()
    others = [a for a in "XYZ" if a != axis]
    stress = h["Axial Stress (Pa)"]
    strain = h["Strain " + axis]
    lateral = 0.5 * (h["Strain " + others[0]] + h["Strain " + others[1]])
    rows = np.nonzero(_shear_rows(h))[0]
    if rows.size == 0:
        raise ValueError("no shear-stage rows in the history")
    gauge = h.get("Gauge Strain")
    stress, strain, lateral = stress[rows], strain[rows], lateral[rows]
    ipeak = int(np.argmax(stress))
    peak = stress[ipeak]
    window = (np.arange(stress.size) <= ipeak) & (stress >= lower * peak) & (stress <= upper * peak)
    if window.sum() < 2:
        raise ValueError("only %d history rows between %g and %g of the peak (%.4g Pa): sample "
                         "more often (Sample Interval) or load more slowly" % (window.sum(), lower, upper, peak))
    if gauge is not None and np.all(np.isfinite(gauge[rows][window])):
        strain = gauge[rows]
    e_mod = np.polyfit(strain[window], stress[window], 1)[0]
    nu = -np.polyfit(strain[window], lateral[window], 1)[0]
    return float(e_mod), float(nu)


def peak_values(history):
    """Peak axial stress and peak deviator stress (Pa) over the shear-stage rows."""
    np = _np()
    h = history_to_dict(history)
    rows = _shear_rows(h)
    if not rows.any():
        return 0.0, 0.0
    return float(np.max(h["Axial Stress (Pa)"][rows])), float(np.max(h["Deviator Stress (Pa)"][rows]))


def compressive_to_tensile_ratio(ucs, tensile_strength):
    """UCS over tensile strength (both magnitudes, Pa); rock is typically 10-20."""
    if tensile_strength == 0:
        raise ValueError("tensile strength is zero")
    return abs(ucs) / abs(tensile_strength)


def _filter(name):
    """The paraview.simple-style constructor of a filter loaded by the plugin (LoadPlugin
    puts them in the caller's namespace, not in paraview.simple)."""
    from paraview import servermanager
    return _simple._create_func(name, servermanager.filters)


def run_test(model_source, mode, stop_when_done=True, progress=None, stop_below=None, **props):
    """Create a DEM Load Test on model_source, run it, and return (proxy, history dict).

    mode: 'Off', 'Compression', 'Tension', 'Triaxial', 'Isotropic' or 'Brazilian'. props are DEM Load
    Test properties (StrainRate, MaxStrain, ConfiningStress, FrameInterval,
    NumberOfFrames, SampleInterval, TimestepSafety, Gravity, ...). For a press mode the
    Gravity defaults to zero (a laboratory press test has none). When FrameInterval and
    NumberOfFrames are not given, 20 frames spanning 1.05 x MaxStrain / StrainRate of model
    time are used (plus as much again for a Triaxial consolidation).

    The test is run to the end of its run (its last frame, or with NumberOfFrames 0 the
    frame where it finishes); with stop_when_done (default) it is advanced frame by frame
    and stops at the first frame where Stage is 'done'. progress, when given, is called with
    (frame, proxy) after each frame. With stop_below (a fraction, e.g. 0.5) it also stops
    at the first frame where the magnitude of Axial Stress has fallen below stop_below x
    the magnitude of Peak Stress: the specimen has failed, and the rest of Max Strain
    need not be run. The History (port 1) is fetched into a dict of numpy arrays.
    """
    props = dict(props)
    if mode != "Off":
        props.setdefault("Gravity", [0.0, 0.0, 0.0])
    if "FrameInterval" not in props and "NumberOfFrames" not in props and mode != "Off":
        rate = props.get("StrainRate", 0.1)
        duration = 1.05 * props.get("MaxStrain", 0.02) / rate
        frames = 20
        if mode == "Triaxial":
            frames = 40
            duration *= 2.0
        props["FrameInterval"] = duration / frames
        props["NumberOfFrames"] = frames
    test = _filter("DEMLoadTest")(Input=model_source, Mode=mode, **props)
    if stop_when_done and mode != "Off":
        # Frame by frame. The list is read again after every frame: once the stage has run
        # its frames are the model's times, and with NumberOfFrames 0 it grows as needed.
        test.UpdatePipeline(0.0)
        k = 1
        while k < len(test.TimestepValues or []):
            test.UpdatePipeline(list(test.TimestepValues)[k])
            if progress:
                progress(k, test)
            if read_only(test, "Stage") == "done":
                break
            if stop_below is not None and abs(read_only(test, "AxialStress")) < \
                    stop_below * abs(read_only(test, "PeakStress")):
                break
            k += 1
    else:
        # The end of the run (with NumberOfFrames 0: where the test finishes).
        test.UpdatePipeline(END_OF_RUN)
        if progress:
            progress(len(test.TimestepValues or [0.0]) - 1, test)
    status = read_only(test, "Status")
    if test.GetDataInformation().GetNumberOfPoints() == 0:
        raise RuntimeError("DEM Load Test (%s) gave no output: %s" % (mode, status))
    return test, fetch_history(test)


def ucs_test(cemented_source, axis="Z", **props):
    """Unconfined compression: returns a dict with ucs (Pa, Peak Stress), E (Pa), nu,
    the broken bonds, the proxy and the history. props go to run_test."""
    test, history = run_test(cemented_source, "Compression", Axis=axis, **props)
    result = {"proxy": test, "history": history, "ucs": float(read_only(test, "PeakStress")),
              "broken_bonds": int(read_only(test, "BrokenBonds")), "bonds": int(read_only(test, "Bonds"))}
    try:
        result["E"], result["nu"] = elastic_constants(history, axis)
    except ValueError:
        result["E"], result["nu"] = float("nan"), float("nan")
    return result


def tension_test(cemented_source, axis="Z", **props):
    """Direct tension: returns a dict with tensile_strength (Pa, magnitude of the largest
    pull), the broken bonds, the proxy and the history. props go to run_test."""
    np = _np()
    test, history = run_test(cemented_source, "Tension", Axis=axis, **props)
    rows = _shear_rows(history)
    pull = float(-np.min(history["Axial Stress (Pa)"][rows])) if rows.any() else 0.0
    peak = abs(float(read_only(test, "PeakStress")))
    return {"proxy": test, "history": history, "tensile_strength": max(pull, peak),
            "broken_bonds": int(read_only(test, "BrokenBonds")), "bonds": int(read_only(test, "Bonds"))}


def brazilian_test(cemented_disc, axis="Y", **props):
    """Brazilian (indirect tensile) test of a cemented disc (DEM Specimen, Shape Disc):
    two flat platens squeeze it along ``axis`` (across the disc's axis). Returns a dict with
    brazilian_strength (Pa, 2 P / (pi D t) at the peak load), diameter and thickness (m),
    load (N) and displacement (m) arrays of the shearing rows, the broken bonds, the proxy
    and the history. props go to run_test (StrainRate, MaxStrain, ...; stop_below=0.5
    stops once the load has fallen below half its peak)."""
    np = _np()
    props.setdefault("stop_below", 0.5)
    test, history = run_test(cemented_disc, "Brazilian", Axis=axis, **props)
    rows = _shear_rows(history)
    # The history's Axial Stress is the Brazilian stress 2 P / (pi D t) and its strain the
    # platen displacement over D (Documentation/Press.md, "Brazilian test").
    strain = history["Strain %s" % axis][rows]
    stress = history["Axial Stress (Pa)"][rows]
    diameter = float(read_only(test, "DiscDiameter"))
    thickness = float(read_only(test, "DiscThickness"))
    load = stress * np.pi * diameter * thickness / 2.0
    return {"proxy": test, "history": history,
            "brazilian_strength": float(read_only(test, "BrazilianStrength")),
            "diameter": diameter, "thickness": thickness, "load": load, "displacement": strain * diameter,
            "broken_bonds": int(read_only(test, "BrokenBonds")), "bonds": int(read_only(test, "Bonds"))}


def triaxial_series(cemented_source, confining_stresses, delete=True, progress=None, **props):
    """Triaxial tests on one cemented model at each confining stress, and the envelope.

    props go to run_test (Mode Triaxial), e.g. Confinement="Membrane" for a cylinder carved
    by DEM Specimen (Documentation/Specimens.md, "The flexible membrane"). Returns (results, (cohesion_Pa,
    friction_angle_deg)) with results a list of dicts: confining (Pa), peak_axial
    (sigma1 at failure, Pa), peak_deviator (Pa), broken_bonds, history. The envelope is
    fit_mohr_coulomb over (confining, peak_axial); it is (nan, nan) when it cannot be
    fitted (fewer than two tests, or strength falling with confinement). With delete
    (default) each test's proxy is deleted after its history is fetched.
    """
    results = []
    for s3 in confining_stresses:
        test, history = run_test(cemented_source, "Triaxial", ConfiningStress=float(s3),
                                 progress=progress, **props)
        peak_axial, peak_dev = peak_values(history)
        results.append({"confining": float(s3), "peak_axial": peak_axial, "peak_deviator": peak_dev,
                        "broken_bonds": int(read_only(test, "BrokenBonds")), "history": history,
                        "stage": read_only(test, "Stage")})
        if delete:
            _simple.Delete(test)
        else:
            results[-1]["proxy"] = test
    try:
        envelope = fit_mohr_coulomb([r["confining"] for r in results], [r["peak_axial"] for r in results])
    except ValueError:
        envelope = (float("nan"), float("nan"))
    return results, envelope


# ---------------------------------------------------------------------------------------
# Fractures (DEM Fractures To DFN; Documentation/Fractures.md).
# ---------------------------------------------------------------------------------------

#: Colours of the fracture sets (Set 0 tensile, 1 shear, 2 inherited), RGB 0-1.
FRACTURE_SET_COLORS = ((0.85, 0.15, 0.15), (0.15, 0.35, 0.85), (0.2, 0.7, 0.2))


def _categorical_colors(array, categories, colors):
    """Make the colour map of ``array`` categorical: ``categories`` is a list of
    (value, label), ``colors`` the RGB (0-1) of each, in the same order. Returns the map."""
    lut = _simple.GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = [text for value, label in categories for text in (str(value), label)]
    lut.IndexedColors = [c for rgb in colors for c in rgb]
    return lut


def show_fractures(dfn, view=None, model=None, opacity=0.85):
    """Show the discs of a DEM Fractures To DFN (output port 0) coloured by Set.

    Tensile red, shear blue, inherited green (FRACTURE_SET_COLORS). With ``model``
    (a RockDEM model source), its particles are shown too, as spheres (show_particles),
    so the discs appear inside the specimen they came from. Returns the discs'
    representation.
    """
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    if model is not None:
        particles = show_particles(model, view, color_by=None)
        particles.Opacity = 0.25
    display = _simple.Show(_simple.OutputPort(dfn, 0), view)
    display.SetRepresentationType("Surface")
    display.Opacity = opacity
    _simple.ColorBy(display, ("CELLS", "Set"))
    _categorical_colors("Set", [(0, "Tensile"), (1, "Shear"), (2, "Inherited")], FRACTURE_SET_COLORS)
    return display


# ---------------------------------------------------------------------------------------
# Seeing inside the rock: sections, voxel models, close-up rendering
# (DEM Section, DEM Voxelize; Documentation/Sections.md).
# ---------------------------------------------------------------------------------------

#: Colours of the broken-bond traces by FailureMode (1 tension, 2 shear, 3 inherited): the
#: colours of the fracture sets they become (FRACTURE_SET_COLORS).
FAILURE_MODE_COLORS = FRACTURE_SET_COLORS


def compress_until_failure(model, fraction=0.6, **props):
    """Unconfined compression of a cemented model past its peak: a DEM Load Test (Mode
    Compression) run frame by frame until the axial stress has fallen to ``fraction`` of
    the peak stress. props go to DEM Load Test (StrainRate, MaxStrain, FrameInterval,
    NumberOfFrames, SampleInterval, ...; Gravity defaults to 0, as in a press). Returns
    (proxy, the time of that frame in s); the time is None when the last frame comes
    first (the test then stands at its last frame).
    """
    props = dict(props)
    props.setdefault("Gravity", [0.0, 0.0, 0.0])
    press = _filter("DEMLoadTest")(Input=model, Mode="Compression", **props)
    # Frame by frame, the published times read again each time: once the stage has run
    # they are the model's times (whole steps), not the k x Frame Interval known before.
    k = 1
    while k < len(press.TimestepValues or []):
        press.UpdatePipeline(list(press.TimestepValues)[k])
        peak = read_only(press, "PeakStress")
        if peak > 0 and read_only(press, "AxialStress") < fraction * peak:
            return press, list(press.TimestepValues)[k]
        k += 1
    return press, None


def specimen(model, shape="Cylinder", axis="Z", diameter=None, length=None, size=None, center=None,
             **props):
    """A DEM Specimen carved out of a dense pack (Documentation/Specimens.md).

    shape: 'Box' (give ``size``, m, 3 edge lengths), 'Cylinder' or 'Disc' (give
    ``diameter`` and ``length``, m; a disc's length is its thickness, no more than the
    diameter; in a 2D section the slab is the thickness and length is not used). axis: the
    cylinder or disc axis ('X', 'Y', 'Z'). center: the specimen's centre (m); default the
    centre of the model box. Returns the proxy (output: the carved model; read-only
    NumberOfParticles, RemovedParticles, SpecimenPorosity, LastMessage).
    """
    props = dict(props)
    props["Shape"] = shape
    props["Axis"] = axis
    if diameter is not None:
        props["Diameter"] = diameter
    if length is not None:
        props["Length"] = length
    if size is not None:
        props["Size"] = list(size)
    if center is not None:
        props["CenterOnModel"] = 0
        props["Center"] = list(center)
    proxy = _filter("DEMSpecimen")(Input=model, **props)
    proxy.UpdatePipeline()
    return proxy


def section(model, orientation="XY", origin=None, normal=None, **props):
    """A DEM Section of a RockDEM model.

    orientation: 'XY', 'XZ', 'YZ' (the reference guide's sections: planes of constant Z, Y,
    X) or 'Custom' (give ``normal``). origin: a point of the plane (m); default the centre
    of the model's bounds. props go to the proxy (TraceDistance, CircleSides). Returns the
    proxy; its outputs are port 0 the circles, port 1 the bond crossings, port 2 the
    broken-bond traces.
    """
    if normal is not None and orientation != "Custom":
        raise ValueError("a normal is only used with orientation 'Custom' (got %r)" % orientation)
    props = dict(props)
    props["Section"] = orientation
    if normal is not None:
        props["Normal"] = list(normal)
    proxy = _filter("DEMSection")(Input=model, **props)
    if origin is not None:
        proxy.Origin = list(origin)
    return proxy


def show_section(section_proxy, view=None, color_by="VonMisesStress", traces=True, crossings=False,
                 trace_width=3.0):
    """Show a DEM Section: the circles (port 0) as surfaces coloured by a particle array
    (``color_by``, e.g. 'VonMisesStress', 'MeanStress', 'Radius'; None for plain grey),
    with ``traces`` the broken-bond traces (port 2) as lines coloured by FailureMode (red
    tension, blue shear, green inherited), with ``crossings`` the intact bonds crossing the
    plane (port 1) as points. Returns the circles' representation."""
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    display = _simple.Show(_simple.OutputPort(section_proxy, 0), view)
    display.SetRepresentationType("Surface")
    if color_by:
        _simple.ColorBy(display, ("CELLS", color_by))
        display.RescaleTransferFunctionToDataRange(True, False)
        display.SetScalarBarVisibility(view, True)
    else:
        display.ColorArrayName = ["POINTS", ""]
    if traces:
        lines = _simple.Show(_simple.OutputPort(section_proxy, 2), view)
        lines.SetRepresentationType("Wireframe")
        lines.LineWidth = trace_width
        _simple.ColorBy(lines, ("CELLS", "FailureMode"))
        lut = _categorical_colors("FailureMode", [(1, "Tension"), (2, "Shear"), (3, "Inherited")],
                                  FAILURE_MODE_COLORS)
        lines.SetScalarBarVisibility(view, True)
        bar = _simple.GetScalarBar(lut, view)
        bar.Title = "Failure Mode"
        bar.ComponentTitle = ""
    if crossings:
        points = _simple.Show(_simple.OutputPort(section_proxy, 1), view)
        points.SetRepresentationType("Points")
        points.PointSize = 4.0
        points.ColorArrayName = ["POINTS", ""]
        points.AmbientColor = points.DiffuseColor = [0.1, 0.1, 0.1]
    return display


def voxelize(model, number_of_voxels=64, voxel_size=None, fractures=None, **props):
    """A DEM Voxelize of a RockDEM model: ``number_of_voxels`` along the longest axis, or
    cubes of ``voxel_size`` (m) when given; ``fractures``: a DFN (e.g. a DEM Fractures To
    DFN) rasterised into FractureIntensity. props go to the proxy (MemoryLimit). Returns
    the proxy (a vtkImageData: volume rendering, Contour, Slice, Save Data as .vti)."""
    props = dict(props)
    if voxel_size is not None:
        props.update(SizeBy="Voxel Size", VoxelSize=float(voxel_size))
    else:
        props.update(SizeBy="Number Of Voxels", NumberOfVoxels=int(number_of_voxels))
    if fractures is not None:
        props["Fractures"] = fractures
    return _filter("DEMVoxelize")(Input=model, **props)


def show_voxels(voxels, view=None, array="Damage", opacity=None, color_map="Inferno (matplotlib)"):
    """Volume-render an array of a DEM Voxelize (default Damage). ``opacity``: the scalar
    opacity as [value, alpha, value, alpha, ...] (default: transparent at 0 rising to 0.8
    at the array's maximum). Returns the representation."""
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    display = _simple.Show(voxels, view)
    _simple.ColorBy(display, ("POINTS", array))
    display.SetRepresentationType("Volume")
    display.RescaleTransferFunctionToDataRange(True, False)
    lut = _simple.GetColorTransferFunction(array)
    lut.ApplyPreset(color_map, True)
    pwf = _simple.GetOpacityTransferFunction(array)
    low, high = voxels.PointData[array].GetRange()
    if opacity is None:
        high = high if high > low else low + 1.0
        opacity = [low, 0.0, low + 0.15 * (high - low), 0.05, high, 0.8]
    pwf.Points = [v for k in range(0, len(opacity), 2) for v in (opacity[k], opacity[k + 1], 0.5, 0.0)]
    display.SetScalarBarVisibility(view, True)
    return display


def show_as_sphere_glyphs(source, view=None, port=0, color_by="Radius", resolution=24, shadows=False):
    """Draw a RockDEM model's particles as true spheres: ParaView's 3D Glyphs
    representation (instanced sphere meshes, lit like any surface), each scaled to its
    particle's Radius. Correct at any zoom; for close-ups and publication pictures, while
    Point Gaussian (show_particles) stays the default for large models
    (Documentation/Sections.md, "Close-up rendering"). ``resolution``: facets around a
    sphere. With ``shadows``, enable_shadows() makes the view cast shadows (the spheres on
    each other and on any other surface). Returns the representation.
    """
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    # The Particles block only: the end points of the Walls and Bonds blocks have a Radius
    # of NaN (drawn as nothing by Point Gaussian), which would give glyphs of no size and a
    # view whose bounds are not a number.
    particles = _simple.ExtractBlock(Input=_simple.OutputPort(source, port), Selectors=["/Root/Particles"])
    display = _simple.Show(particles, view)
    display.SetRepresentationType("3D Glyphs")
    display.GlyphType = "Sphere"
    display.GlyphType.ThetaResolution = resolution
    display.GlyphType.PhiResolution = resolution
    display.GlyphType.Radius = 0.5
    display.Orient = 0
    display.Scaling = 1
    display.ScaleMode = "Magnitude"
    display.SelectScaleArray = "Radius"
    display.ScaleFactor = 2.0  # the glyph sphere has diameter 1: scaled by 2 Radius
    if color_by:
        _simple.ColorBy(display, ("POINTS", color_by))
        display.RescaleTransferFunctionToDataRange(True, False)
    else:
        display.ColorArrayName = ["POINTS", ""]
    if shadows:
        display.Ambient = 0.25  # the shadowed side is not black
        enable_shadows(view)
    return display


def enable_shadows(view=None, direction=(-1.0, -0.4, 1.5), intensity=1.0, resolution=2048):
    """Make a render view cast shadows (OpenGL shadow maps, VTK's vtkShadowMapPass).

    One light shining along -``direction`` (world coordinates; default from above, the -X,
    -Y side; a spot light far out whose cone covers the scene) replaces ParaView's light
    kit; ``resolution`` is the shadow map's size in pixels (memory resolution^2 x 4
    bytes). Surfaces and true spheres (show_as_sphere_glyphs, 3D Glyphs) cast and receive
    shadows; Point Gaussian sprites cannot (their shader does not compile in the shadow
    pass): show particles as spheres first. Works where the view's renderer lives in this
    process (pvpython, pvbatch, the GUI's Python Shell with the built-in server), not
    through a remote pvserver. Debian's ParaView has no OSPRay ray tracing (Enable Ray
    Tracing is refused), so this is its way to shadows. Returns the light (a vtkLight).
    """
    import math
    from vtkmodules.vtkRenderingCore import vtkLight
    from vtkmodules.vtkRenderingOpenGL2 import (vtkCameraPass, vtkRenderPassCollection, vtkSequencePass,
                                                 vtkShadowMapPass)
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    _simple.Render(view)
    renderer = view.GetRenderer()
    bounds = renderer.ComputeVisiblePropBounds()
    centre = [0.5 * (bounds[2 * k] + bounds[2 * k + 1]) for k in range(3)]
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-12)
    norm = sum(c * c for c in direction) ** 0.5
    # A spot light far enough along the direction that its cone covers the scene (VTK's
    # shadow maps are made for positional lights).
    distance = 4.0 * size
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(True)
    light.SetFocalPoint(*centre)
    light.SetPosition(*[centre[k] + distance * direction[k] / norm for k in range(3)])
    light.SetConeAngle(2.0 * math.degrees(math.atan(size / distance)) + 10.0)
    light.SetAttenuationValues(1.0, 0.0, 0.0)
    light.SetIntensity(intensity)
    view.UseLight = 0  # the light kit would fill the shadows in
    renderer.AddLight(light)
    shadows = vtkShadowMapPass()
    shadows.GetShadowMapBakerPass().SetResolution(int(resolution))
    passes = vtkRenderPassCollection()
    passes.AddItem(shadows.GetShadowMapBakerPass())
    passes.AddItem(shadows)
    sequence = vtkSequencePass()
    sequence.SetPasses(passes)
    camera = vtkCameraPass()
    camera.SetDelegatePass(sequence)
    renderer.SetPass(camera)
    if not _SHADOWED:
        import atexit
        atexit.register(_release_shadows)  # while the OpenGL contexts still exist
    _SHADOWED.append((view, renderer, light, camera))
    _simple.Render(view)
    return light


#: Views with a shadow pass: (view, renderer, light, pass), released by disable_shadows.
_SHADOWED = []


def disable_shadows(view=None):
    """Undo enable_shadows(): the view's shadow pass and light go (their OpenGL resources
    released) and ParaView's light kit comes back. Done for every view at exit too: a pass
    still holding OpenGL resources when the windows close ends the process with an X
    error (GLXBadContext)."""
    view = view or _simple.GetActiveView()
    for entry in [e for e in _SHADOWED if e[0] is view]:
        _, renderer, light, shadow_pass = entry
        shadow_pass.ReleaseGraphicsResources(view.GetRenderWindow())
        renderer.SetPass(None)
        renderer.RemoveLight(light)
        view.UseLight = 1
        _SHADOWED.remove(entry)


def _release_shadows():
    for view in list(dict.fromkeys(e[0] for e in _SHADOWED)):
        try:
            disable_shadows(view)
        except Exception:  # the view may be gone already; nothing else to release
            pass


# ---------------------------------------------------------------------------------------
# Calibration (Plugin/rockdem_calibration.py; Documentation/Calibration.md).
# ---------------------------------------------------------------------------------------

from rockdem_calibration import (  # noqa: E402,F401
    CalibrationError, build_specimen, calibrate, load_parameters, load_rock, save_parameters, test_strains, verify)
