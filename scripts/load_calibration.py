"""The RockDEM plugin of this checkout and its calibration module, for the scripts that
test a calibration's parameter file (scripts/tension_rate.py, scripts/envelope.py).

    from load_calibration import load_calibration
    cal = load_calibration(globals())

Loads the plugin ($ROCKDEM_PLUGIN, or build/lib/paraview-plugins/RockDEM/RockDEM.so of
this checkout) into the namespace given, as LoadPlugin(..., ns=) does, and returns the
module rockdem_calibration of Plugin/.
"""
import os
import sys

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load_calibration(ns):
    from paraview.simple import LoadPlugin
    plugin = os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")
    LoadPlugin(plugin, remote=False, ns=ns)
    sys.path.insert(0, os.path.join(SOURCE_DIR, "Plugin"))
    import rockdem_calibration
    return rockdem_calibration
