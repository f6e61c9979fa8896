#!/usr/bin/env python3
"""Copies the GUI tests' screenshots into Documentation/images/gui/ for GUI-Walkthrough.md.

    ctest -R GUI            (in the build folder: the tests take the screenshots)
    python3 Testing/GUI/walkthrough_images.py build

Each screenshot (the whole 1600 x 1000 ParaView window) is scaled to 1200 pixels wide and
stored with a 256-colour palette to keep the repository small.
"""
import glob
import os
import sys

from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
TARGET = os.path.join(os.path.dirname(os.path.dirname(HERE)), "Documentation", "images", "gui")


def main(build):
    os.makedirs(TARGET, exist_ok=True)
    shots = sorted(glob.glob(os.path.join(build, "Testing", "GUI", "*", "[0-9][0-9]_*.png")))
    if not shots:
        sys.exit("no screenshots under %s/Testing/GUI: run ctest -R GUI first" % build)
    for path in shots:
        image = Image.open(path).convert("RGB")
        width, height = image.size
        image = image.resize((1200, round(height * 1200 / width)), Image.LANCZOS)
        image = image.quantize(colors=256, method=Image.MEDIANCUT, dither=Image.NONE)
        out = os.path.join(TARGET, os.path.basename(path))
        image.save(out, optimize=True)
        print("%s (%d kB)" % (out, os.path.getsize(out) // 1024))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "build")
