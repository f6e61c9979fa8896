"""Shared set-up for RockDEM's pvpython tests: load the plugin, count checks."""
import os
import sys

from paraview.simple import LoadPlugin


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
