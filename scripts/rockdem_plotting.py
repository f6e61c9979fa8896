"""Matplotlib for the plotting scripts (plot_accuracy.py, plot_rock.py, plot_envelopes.py).

pyplot() returns matplotlib.pyplot on the Agg backend (files, no display). When the
python3 first on PATH has no matplotlib (a pyenv or venv python3, say), the script is
run again with the Debian /usr/bin/python3; without matplotlib there either, it stops
saying which package to install.
"""
import os
import sys


def pyplot():
    try:
        import matplotlib
    except ImportError:
        debian = "/usr/bin/python3"
        if os.path.exists(debian) and os.path.realpath(sys.executable) != os.path.realpath(debian):
            os.execv(debian, [debian] + sys.argv)
        sys.exit("matplotlib is missing: apt-get install python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
