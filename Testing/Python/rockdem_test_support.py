"""Shared set-up for RockDEM's pvpython tests: load the plugin, count checks."""
import os
import sys

from paraview.simple import LoadPlugin
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow


def load_rockdem(ns):
    plugin = os.environ.get("ROCKDEM_PLUGIN")
    if not plugin or not os.path.exists(plugin):
        sys.exit("ROCKDEM_PLUGIN must name the built RockDEM plugin (got %r)" % plugin)
    LoadPlugin(plugin, remote=False, ns=ns)


class Checks:
    """Counts checks; fails the process at the end if any failed."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, condition, what):
        if condition:
            self.passed += 1
            print("ok   - " + what)
        else:
            self.failed += 1
            print("FAIL - " + what)

    def finish(self):
        print("%d passed, %d failed" % (self.passed, self.failed))
        sys.exit(1 if self.failed or not self.passed else 0)


class Messages:
    """What reaches Output Messages (the output window's messages, observed)."""

    def __init__(self):
        self.text = []
        vtkOutputWindow.GetInstance().AddObserver(vtkCommand.MessageEvent, self.on_message)

    @calldata_type(VTK_STRING)
    def on_message(self, caller, event, text):
        self.text.append(text)

    def GetOutput(self):
        return "".join(self.text)

    def Flush(self):
        self.text = []
