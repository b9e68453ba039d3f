#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_npz (docs/fuzzing.md) with Python's own
zipfile module, the one numpy.savez uses, so the seeds (and the test in
tests/io/read_npz_test.cpp that reads them) come from another ZIP writer than
the tests' own. Python's standard library only: no numpy needed.

    fuzz/make_npz_seeds.py fuzz/corpus/fuzz_npz
"""
import struct
import sys
import zipfile


def npy(descr, shape, data, fortran=False, major=1):
    dims = ", ".join(str(d) for d in shape) + ("," if len(shape) == 1 else "")
    header = "{'descr': '%s', 'fortran_order': %s, 'shape': (%s), }" % (descr, fortran, dims)
    prefix = 10 if major == 1 else 12
    header += " " * ((64 - (prefix + len(header) + 1) % 64) % 64) + "\n"
    size = struct.pack("<H" if major == 1 else "<I", len(header))
    return b"\x93NUMPY" + bytes([major, 0]) + size + header.encode("latin1") + data


def f8(values):
    return struct.pack("<%dd" % len(values), *values)


def main(out):
    # An SMPL-like set of arrays, stored (numpy.savez).
    with zipfile.ZipFile(out + "/smpl_like_stored.npz", "w", zipfile.ZIP_STORED) as z:
        z.writestr("v_template.npy", npy("<f8", (4, 3), f8([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1])))
        z.writestr("f.npy", npy("<u4", (4, 3), struct.pack("<12I", 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3)))
        z.writestr("kintree_table.npy", npy("<i8", (2, 2), struct.pack("<4q", 4294967295, 0, 0, 1)))
        z.writestr("weights.npy", npy("<f4", (4, 2), struct.pack("<8f", 1, 0, 0.5, 0.5, 0, 1, 0.25, 0.75)))
    # Every other dtype, Fortran order and header versions 2 and 3, deflated
    # (numpy.savez_compressed).
    with zipfile.ZipFile(out + "/dtypes_deflated.npz", "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("i4.npy", npy("<i4", (3,), struct.pack("<3i", -1, 0, 7)))
        z.writestr("u8.npy", npy("<u8", (2,), struct.pack("<2Q", 1, 2**40), major=2))
        z.writestr("u1.npy", npy("|u1", (2, 2), bytes([1, 2, 3, 4]), fortran=True, major=3))
        z.writestr("b1.npy", npy("|b1", (2,), bytes([0, 1])))
        z.writestr("scalar.npy", npy("<f8", (), f8([2.5])))
    # numpy's large-array path: zf.open(name, "w", force_zip64=True).
    with zipfile.ZipFile(out + "/zip64_deflated.npz", "w", zipfile.ZIP_DEFLATED) as z:
        with z.open("a.npy", "w", force_zip64=True) as f:
            f.write(npy("<f8", (2, 3), f8([1.5, -2.25, 3.0, 4.0, 5.0, 6.0])))
        with z.open("fortran.npy", "w", force_zip64=True) as f:
            f.write(npy("<f8", (2, 3), f8([1, 4, 2, 5, 3, 6]), fortran=True))


if __name__ == "__main__":
    main(sys.argv[1])
