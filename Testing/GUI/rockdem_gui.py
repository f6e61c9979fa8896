"""Helpers for RockDEM's GUI tests, imported in the ParaView GUI's Python shell.

The event files (*.xml, ParaView's recorded-test format) drive the real GUI: menus, the
Properties panel, Apply, the VCR controls, file dialogs. Between the events they run lines
of Python in the GUI's Python shell (command ``executeCommand``) that call these helpers to
check what the GUI shows and to take screenshots of the whole window. The checks are
written to checks.txt in the test's output folder; run_gui_test.py reads them.
"""
import os
import time

from paraview import simple

OUT = os.environ.get("ROCKDEM_GUI_OUT", ".")
#: Where the test's input files are (a state file, a saved state), run_gui_test.py --data-dir.
DATA = os.environ.get("ROCKDEM_GUI_DATA", ".")
_t0 = [time.time()]


def _write(line):
    with open(os.path.join(OUT, "checks.txt"), "a") as f:
        f.write(line + "\n")


def _record_exception(kind, value, trace, _previous=__import__("sys").excepthook):
    """A Python line that raises fails the test, with the exception in checks.txt."""
    import traceback
    _write("FAIL - Python raised %s" % "".join(traceback.format_exception_only(kind, value)).strip())
    _previous(kind, value, trace)


__import__("sys").excepthook = _record_exception


def check(condition, what):
    """Records one check: 'ok - what' or 'FAIL - what'."""
    _write(("ok   - " if condition else "FAIL - ") + what)
    return bool(condition)


def note(what):
    """Records a line that is not a check (a measurement, a value)."""
    _write("note - " + str(what))


def shot(name):
    """Saves a screenshot of the whole screen (the ParaView window) as OUT/name.png."""
    from PIL import ImageGrab
    path = os.path.join(OUT, name + ".png")
    ImageGrab.grab().save(path)
    return path


def source(name):
    """The pipeline source registered under name (as the Pipeline Browser shows it)."""
    proxy = simple.FindSource(name)
    if proxy is None:
        raise LookupError("no source named %r (sources: %s)" % (name, [k[0] for k in simple.GetSources()]))
    return proxy


def value(proxy, name):
    """A property's current value; read-only values as they are now (pulled again)."""
    proxy.UpdatePropertyInformation()
    v = proxy.GetPropertyValue(name)
    return v[0] if isinstance(v, (list, tuple)) and len(v) == 1 else v


def start_clock():
    _t0[0] = time.time()


def seconds():
    """Seconds since start_clock()."""
    return time.time() - _t0[0]


def finish():
    """The last line of a test: run_gui_test.py requires it (the events all played)."""
    _write("done")
