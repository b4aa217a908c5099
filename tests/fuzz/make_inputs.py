#!/usr/bin/python3
"""Makes the fuzz corpus (tests/fuzz/corpus) and the issue-18 reproducers (tests/fuzz/reproducers) from scratch.

    /usr/bin/python3 tests/fuzz/make_inputs.py build/release/drivers/throng

Needs Debian's python3-h5py. The files are committed: the tests read them and do not run this script; run it again
only to change them. Base files are written by throng itself (a tiny recorded dataset imported, a tiny tiling);
each reproducer is one of them with the one defect the issue reports, and reproducers/expected.tsv says what the
program must answer (command, exit code, a fragment of the message): tests/cli/test_hostile_inputs.cpp runs it.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")
REPRO = os.path.join(HERE, "reproducers")


def throng(binary, *args):
    subprocess.run([binary, "--quiet", *args], check=True, stdout=subprocess.DEVNULL)


def replace_dataset(f, path, **kwargs):
    del f[path]
    return f.create_dataset(path, **kwargs)


def patch_u64(path, old, new, start=0):
    """Replaces every little-endian u64 `old` at or after `start` by `new` (dimensions in object headers)."""
    data = bytearray(open(path, "rb").read())
    pattern, count, at = struct.pack("<Q", old), 0, data.find(struct.pack("<Q", old), start)
    while at >= 0:
        data[at:at + 8] = struct.pack("<Q", new)
        count += 1
        at = data.find(pattern, at + 8)
    assert count > 0, f"{old} not found in {path}"
    open(path, "wb").write(data)


def main(binary):
    work = tempfile.mkdtemp()
    try:
        # A tiny recorded dataset: 3 agents, 6 frames, a wall, a pillar, a walking group.
        hotel = os.path.join(work, "hotel")
        os.mkdir(hotel)
        with open(os.path.join(hotel, "obsmat.txt"), "w") as out:
            for frame in range(0, 60, 10):
                for agent in (1, 2, 3):
                    if agent == 3 and frame < 20:
                        continue
                    out.write(f"{frame} {agent} {0.4 * frame / 10 + agent} 0 {agent * 0.8} 1.0 0 0\n")
        with open(os.path.join(hotel, "map.xml"), "w") as out:
            out.write('<?xml version="1.0"?>\n<map>\n  <Line x1="-1" y1="-1" x2="6" y2="-1" thickness="3"/>\n'
                      '  <Circle x="2" y="4" radius="0.3"/>\n</map>\n')
        with open(os.path.join(hotel, "groups.txt"), "w") as out:
            out.write("1 2\n")
        base = os.path.join(work, "base.h5")
        throng(binary, "import", hotel, "-o", base)
        tiling = os.path.join(work, "tiling.h5")
        job = os.path.join(work, "tile.yaml")
        with open(job, "w") as out:
            out.write("region: {min: [0, 0], max: [6, 6], time: [0, 6]}\nlibrary: {builtin: [locomotion]}\n"
                      "obstacles: [{circle: {center: [5.5, 5.5], radius: 0.2}}]\n"
                      "characters: 3\nchains: 1\noutput: {frame_rate: 5}\n")
        throng(binary, "tile", job, "-o", tiling)

        for d in ("crowd_file", "tiling_data", "csv", "real_dataset", "import"):
            for folder in (CORPUS, REPRO):
                shutil.rmtree(os.path.join(folder, d), ignore_errors=True)
                os.makedirs(os.path.join(folder, d))

        # Corpus: the well-formed inputs the fuzzers start from.
        shutil.copy(base, os.path.join(CORPUS, "crowd_file", "imported.h5"))
        shutil.copy(tiling, os.path.join(CORPUS, "tiling_data", "tiling.h5"))
        with open(os.path.join(CORPUS, "csv", "table.csv"), "w") as out:
            out.write("time,id,x,y,z\n0,1,0,0,0\n0,2,1,0,0\n0.5,1,0.1,0,0\n0.5,2,1.1,0.05,0\n1,2,1.2,0.1,0\n")
        with open(os.path.join(CORPUS, "real_dataset", "hotel.txt"), "w") as out:
            for name in ("obsmat.txt", "map.xml", "groups.txt"):
                if name != "obsmat.txt":
                    out.write(f"\n--8<-- {name}\n")
                out.write(open(os.path.join(hotel, name)).read())

        # import_crowd reads every format by content: the samples of tests/data/import (made from data/real/zara01
        # by make_samples.py there, with their credit), cut short, a few obsmat rows, a crowd file.
        samples = os.path.join(HERE, "..", "data", "import")
        for name, lines in (("zara01_petrack.txt", 30), ("zara01_frame_id_x_y.txt", 20), ("zara01_renamed.csv", 20)):
            with open(os.path.join(samples, name), newline="") as f, \
                    open(os.path.join(CORPUS, "import", name.replace("zara01_", "")), "w", newline="") as out:
                out.writelines(f.readlines()[:lines])
        shutil.copy(os.path.join(samples, "zara01_pedpy.h5"), os.path.join(CORPUS, "import", "pedpy.h5"))
        with open(os.path.join(HERE, "..", "..", "data", "real", "zara01", "obsmat.txt")) as f, \
                open(os.path.join(CORPUS, "import", "obsmat.txt"), "w") as out:
            out.writelines(f.readlines()[:20])
        shutil.copy(base, os.path.join(CORPUS, "import", "crowd.h5"))

        expected = []

        def crowd(name, change, message, command="info {in}"):
            path = os.path.join(REPRO, "crowd_file", name)
            shutil.copy(base, path)
            change(path)
            expected.append((f"crowd_file/{name}", command, 3, message))

        # read_numeric's `count *= d` wrapped: [2^62+1][4] became a 4-element buffer read_scene read past.
        def wraps(path):
            with h5py.File(path, "r+") as f:
                replace_dataset(f, "parameters/throng/scene/obstacles/motion", shape=(2**62 + 1, 4), chunks=(1, 4),
                                dtype="f8")
        crowd("count_wraps.h5", wraps, "holds more elements than a 64-bit count")

        # A 52 KB crowd claiming 2^31 obstacle sizes grew `info` to 14.5 GB.
        def sizes(path):
            with h5py.File(path, "r+") as f:
                replace_dataset(f, "parameters/throng/scene/obstacles/size", data=np.full(4099, 0.25))
            patch_u64(path, 4099, 2**31)
        crowd("obstacle_sizes_2e31.h5", sizes, "but the file holds only")

        # External storage pulled /etc/passwd into a radius dataset (and into the output).
        def external(path):
            with h5py.File(path, "r+") as f:
                replace_dataset(f, "parameters/throng/agents/radius", shape=(3,), dtype="f8",
                                external=[("/etc/passwd", 0, 24)])
        crowd("external_storage.h5", external, "stores its data in external files")

        def external_link(path):
            with h5py.File(path, "r+") as f:
                del f["parameters/throng/agents"]
                f["parameters/throng/agents"] = h5py.ExternalLink("/etc/throng-other.h5", "/agents")
        crowd("external_link.h5", external_link, "link to another file")

        def virtual(path):
            with h5py.File(path, "r+") as f:
                shape = f["particles/trajectory/position/value"].shape
                layout = h5py.VirtualLayout(shape=shape, dtype="f8")
                layout[...] = h5py.VirtualSource("/etc/throng-other.h5", "/value", shape=shape)
                del f["particles/trajectory/position/value"]
                f.create_virtual_dataset("particles/trajectory/position/value", layout, fillvalue=0)
        crowd("virtual_positions.h5", virtual, "virtual dataset")

        # A corrupted global heap made `info` loop forever inside libhdf5 (H5HG deserialisation, reached from
        # H5Aread of a variable-length string): the first object turned into free space of size 0.
        def heap(path):
            data = bytearray(open(path, "rb").read())
            at = data.find(b"GCOL\x01")
            assert at >= 0
            data[at + 16:at + 18] = b"\x00\x00"
            data[at + 24:at + 32] = struct.pack("<Q", 0)
            open(path, "wb").write(data)
        crowd("global_heap_loop.h5", heap, "global heap collection at byte")

        # 1e4 x 1e4 positions that are never written (fill values): 2.4 GB from a few kilobytes.
        def unallocated(path):
            with h5py.File(path, "r+") as f:
                replace_dataset(f, "particles/trajectory/position/value", shape=(10000, 10000, 3), chunks=(1, 10000, 3),
                                dtype="f8", compression="gzip", fillvalue=np.nan)
        crowd("unallocated_1e4.h5", unallocated, "declares [10000][10000][3]")

        # A valid HDF5 float that is not IEEE binary64 (23-bit exponent, 40-bit mantissa): throng reads numbers in
        # standard layouts only, since libhdf5 1.10 smashed its stack converting a crafted one (see below).
        def float_fields(path):
            with h5py.File(path, "r+") as f:
                p = "particles/trajectory/position/value"
                data, attrs = f[p][...], dict(f[p].attrs)
                del f[p]
                tid = h5py.h5t.IEEE_F64LE.copy()
                tid.set_fields(63, 40, 23, 0, 40)
                tid.set_ebias(2**22 - 1)
                ds = h5py.h5d.create(f["particles/trajectory/position"].id, b"value", tid, h5py.h5s.create_simple(data.shape))
                ds.write(h5py.h5s.ALL, h5py.h5s.ALL, np.ascontiguousarray(data, dtype="f8"), mtype=h5py.h5t.NATIVE_DOUBLE)
                for k, v in attrs.items():
                    f[p].attrs[k] = v
        crowd("float_nonstandard_fields.h5", float_fields, "in a layout throng does not read")

        # A tiling file whose limit_stretch holds 100 values overflowed the stack in check-tiling and plot.
        stretch = os.path.join(REPRO, "tiling_data", "limit_stretch_100.h5")
        shutil.copy(tiling, stretch)
        with h5py.File(stretch, "r+") as f:
            g = f["parameters/throng/tiling"]
            del g.attrs["limit_stretch"]
            g.attrs["limit_stretch"] = np.full(100, 0.03)
        expected.append(("tiling_data/limit_stretch_100.h5", "check-tiling {in}", 3, "holds 100 values"))
        expected.append(("tiling_data/limit_stretch_100.h5", "plot {in} -o {out}.svg", 3, "holds 100 values"))
        # A tiling file whose obstacle step is 1e-9 m kept check-tiling busy for days (and overflowed an int).
        tiny = os.path.join(REPRO, "tiling_data", "obstacle_step_tiny.h5")
        shutil.copy(tiling, tiny)
        with h5py.File(tiny, "r+") as f:
            f["parameters/throng/tiling"].attrs["obstacle_step"] = 1e-9
        expected.append(("tiling_data/obstacle_step_tiny.h5", "check-tiling {in}", 3, "make the check test about"))

        # CSV: "1.5xyz" was read as 1.5; a 194 KB table with every row a new time and id grew to 4.6 GB.
        with open(os.path.join(REPRO, "csv", "trailing_garbage.csv"), "w") as out:
            out.write("time,id,x,y,z\n0,1,0,0,0\n0.5,1,1.5xyz,0,0\n")
        expected.append(("csv/trailing_garbage.csv", "import {in} -o {out}.h5", 3, "x '1.5xyz' is not a number"))
        with open(os.path.join(REPRO, "csv", "sparse.csv"), "w") as out:
            out.write("time,id,x,y,z\n")
            for i in range(10000):
                out.write(f"{i},{i},1,2,0\n")
        expected.append(("csv/sparse.csv", "import {in} -o {out}.h5 [ulimit -v 2000000]", 3,
                         "10000 distinct times × 10000 distinct ids × 24 bytes"))

        # obsmat: frame 1e19 became time -3.7e17 s.
        with open(os.path.join(REPRO, "real_dataset", "frame_1e19.txt"), "w") as out:
            out.write("1e19 1 0 0 0 0 0 0\n")
        expected.append(("real_dataset/frame_1e19.txt", "import {dataset} -o {out}.h5", 3, "whole numbers"))

        # Found by the fuzzers and kept as found (not made here): tiling files with an unordered fragment index, a
        # variable-length string claiming 4 GB and a layout smaller than its shape; a PedPy table whose column lies
        # past its row; a float type whose fields libhdf5 1.10 converted past a stack buffer (H5T__bit_get_d).
        expected.append(("tiling_data/type_fragments_unordered.h5", "check-tiling {in}", 3, "type_fragments not increasing"))
        # check-tiling reads no provenance (the string lies in an attribute of /parameters/throng): info does.
        expected.append(("tiling_data/vlen_length_4g.h5", "info {in}", 3, "memory allocation failed"))
        expected.append(("tiling_data/layout_smaller_than_shape.h5", "check-tiling {in}", 3, "but its layout stores 4 bytes"))
        expected.append(("import/compound_member_past_row.h5", "import {in} -o {out}.h5", 3, "of a 56-byte row"))
        expected.append(("import/float_fields_past_word.h5", "import {in} -o {out}.h5", 3, "in a layout throng does not read"))

        with open(os.path.join(REPRO, "expected.tsv"), "w") as out:
            out.write("# input\tcommand ({in}: the input, {dataset}: a folder 'hotel' holding it as obsmat.txt, {out}: an output"
                      " name; [ulimit -v KB]: run under that limit)\texit code\tmessage fragment\n")
            for row in expected:
                out.write("\t".join(str(c) for c in row) + "\n")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main(sys.argv[1])
