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
