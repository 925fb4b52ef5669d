#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Whether two HDF5 result files hold the same datasets, bitwise.

Usage: h5_same_data.py A.h5 B.h5.  Every dataset of either file must exist in the other with the same dtype, shape
and bytes (NaN payloads and signed zeros included: the raw bytes are compared, not the values; strings by their
encoded bytes).  Attributes are
not compared: they hold provenance (dates, command lines, timings, MPI ranks) that differs between runs.  Prints
one line per difference and exits 1, or prints the number of datasets compared and exits 0.
"""
import sys

import h5py


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def raw(d):
    """The dataset's contents as bytes: the raw buffer for numbers, the encoded strings (each with its length) for
    variable-length strings, whose numpy array holds pointers to Python objects rather than the data."""
    v = d[()]
    if h5py.check_string_dtype(d.dtype) is not None or getattr(v, "dtype", None) == object:
        items = v.ravel().tolist() if hasattr(v, "ravel") else [v]
        return b"".join(len(x).to_bytes(8, "little") + (x if isinstance(x, bytes) else str(x).encode()) for x in items)
    return v.tobytes()


def main(a_path, b_path):
    bad = []
    with h5py.File(a_path, "r") as fa, h5py.File(b_path, "r") as fb:
        a, b = datasets(fa), datasets(fb)
        for name in sorted(set(a) | set(b)):
            if name not in a or name not in b:
                bad.append(f"{name}: only in {a_path if name in a else b_path}")
                continue
            x, y = a[name], b[name]
            if x.dtype != y.dtype or x.shape != y.shape:
                bad.append(f"{name}: {x.dtype}{x.shape} against {y.dtype}{y.shape}")
            elif raw(x) != raw(y):
                bad.append(f"{name}: same shape {x.shape}, different bytes")
        if not a:
            bad.append("no datasets")
    if bad:
        print("\n".join(bad))
        return 1
    print(f"{len(a)} datasets equal bitwise")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
