#!/usr/bin/python3
"""Writes the import samples of this folder from the repository's own recording data/real/zara01 (UCY "Crowds by
Example", zara01: A. Lerner, Y. Chrysanthou, D. Lischinski, "Crowds by example", Computer Graphics Forum 26(3),
2007; collected and converted to metres by the OpenTraj project). Each sample holds the first ROWS rows of
obsmat.txt in another layout; the tests compare what they import with those rows.

Run from the repository root: /usr/bin/python3 tests/data/import/make_samples.py (needs numpy and h5py).
"""
import os

import h5py
import numpy as np

ROWS = 300
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..", "..", "data", "real", "zara01", "obsmat.txt")
CREDIT = ("generated from data/real/zara01/obsmat.txt, UCY \"Crowds by Example\" zara01: A. Lerner, Y. Chrysanthou, "
          "D. Lischinski, \"Crowds by example\", Computer Graphics Forum 26(3), 2007; OpenTraj (metres)")

rows = []
with open(SOURCE) as f:
    for line in f:
        v = [float(x) for x in line.split()]
        if v:
            rows.append((int(v[0]), int(v[1]), v[2], v[4]))  # frame id x y (obsmat: frame id x z y ...)
        if len(rows) == ROWS:
            break

groups = {}
with open(os.path.join(os.path.dirname(SOURCE), "groups.txt")) as f:
    for k, line in enumerate(l for l in f if l.split()):
        for i in line.split():
            groups.setdefault(int(i), k + 1)

# The benchmarks' layout: frame id x y, tab-separated, numbers written as floats.
with open(os.path.join(HERE, "zara01_frame_id_x_y.txt"), "w") as f:
    for frame, i, x, y in rows:
        f.write(f"{float(frame)!r}\t{float(i)!r}\t{x!r}\t{y!r}\n")

# Jülich/PeTrack: id frame x y z in centimetres, CRLF, a comment header stating rate and unit, rows by person.
with open(os.path.join(HERE, "zara01_petrack.txt"), "w", newline="") as f:
    f.write(f"# {CREDIT}\r\n# framerate: 25fps\r\n# x/cm y/cm z/cm\r\n# id frame x y z\r\n")
    for frame, i, x, y in sorted(rows, key=lambda r: (r[1], r[0])):
        f.write(f"{i}\t{frame}\t{x * 100!r}\t{y * 100!r}\t175.0\r\n")

# CSV: other names, another order, millimetres, a species column and a column throng does not take (speed).
with open(os.path.join(HERE, "zara01_renamed.csv"), "w") as f:
    f.write(f"# {CREDIT}\n")
    f.write("Y [mm],person,frame_number,X [mm],group,speed\n")
    for frame, i, x, y in rows:
        f.write(f"{y * 1000!r},{i},{frame},{x * 1000!r},{groups.get(i, 0)},1.3\n")

# JuPedSim/PedPy HDF5 (as JuPedSim writes it): /trajectory compound rows, fps attribute, frames from 0.
dtype = np.dtype([("frame", "<i8"), ("id", "<i8"), ("x", "<f8"), ("y", "<f8"), ("z", "<f8"), ("ox", "<f8"), ("oy", "<f8")])
table = np.array([((frame - 1) // 10, i, x, y, 0.0, 1.0, 0.0) for frame, i, x, y in rows], dtype=dtype)
with h5py.File(os.path.join(HERE, "zara01_pedpy.h5"), "w", track_order=False) as f:
    d = f.create_dataset("trajectory", data=table)
    d.attrs["fps"] = 2.5  # one frame per annotation: every 10th video frame of 25 fps
    f.attrs["credit"] = CREDIT
    f.attrs["wkt_geometry"] = "POLYGON ((-10 -10, 20 -10, 20 20, -10 20, -10 -10), (0 0, 1 0, 1 1, 0 1, 0 0))"
