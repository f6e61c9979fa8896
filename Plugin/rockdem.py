"""RockDEM helpers for pvpython and pvbatch.

Importable once the RockDEM plugin is loaded (``LoadPlugin(path, remote=False, ns=globals())``
then ``import rockdem``); also usable from a source checkout by putting ``Plugin/`` on
``sys.path``.
"""

from paraview import simple as _simple


def show_particles(source, view=None, port=0, color_by="Radius"):
    """Show a RockDEM model's particles as spheres of their true radius.

    Point Gaussian representation with the Sphere shader, scaled by the Radius point
    array with no scale function, so the drawn radius equals the particle radius (m).
    Returns the representation.
    """
    view = view or _simple.GetActiveViewOrCreate("RenderView")
    display = _simple.Show(_simple.OutputPort(source, port), view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Sphere"
    display.ScaleByArray = 1
    display.SetScaleArray = ["POINTS", "Radius"]
    display.UseScaleFunction = 0
    display.GaussianRadius = 1.0
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


def show_test_chart(load_test, view=None):
    """Plot a DEM Load Test's History (output port 1) as the DEM Test chart.

    Axial, lateral and deviator stress (MPa) against axial strain (%), and volumetric
    strain (%) on the right-hand axis. Creates an XYChartView unless one is given;
    returns the view.
    """
    view = view or _simple.CreateView("XYChartView")
    display = _simple.Show(_simple.OutputPort(load_test, 1), view, "XYChartRepresentation")
    display.UseIndexForXAxis = 0
    display.XArrayName = "Axial Strain (%)"
    display.SeriesVisibility = list(TEST_CHART_STRESSES) + [TEST_CHART_RIGHT]
    corners = []
    for name in TEST_CHART_STRESSES:
        corners += [name, "0"]
    corners += [TEST_CHART_RIGHT, "1"]
    display.SeriesPlotCorner = corners
    view.BottomAxisTitle = "Axial Strain (%)"
    view.LeftAxisTitle = "Stress (MPa)"
    view.RightAxisTitle = "Volumetric Strain (%)"
    return view
