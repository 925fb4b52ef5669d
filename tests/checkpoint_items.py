#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""What the checkpoint files of a resumable run hold (src/io/checkpoint.hpp), read independently of btob: the line
"btob-checkpoint 1", then records [uint64 size][uint64 hash][payload]; the first payload the request's identity, each
further one a part: [uint64 n][n uint64 items][its packed bytes].  A record cut short at the end is ignored (as
btob drops it).

Usage:
  checkpoint_items.py share P N FILE...  the files of one run of P ranks over N items (NAME.checkpoint is rank 0's,
                                       NAME.checkpoint.K rank K's): every file exists, rank K's holds only items i
                                       with i mod P = K (its own share of a fresh run's cyclic split, none of another
                                       rank's), and its size is at most its header plus ceil(N / P) items at the
                                       largest bytes per item of its records (its share of the whole checkpoint)
  checkpoint_items.py once FILE...     no item is held twice over the files (a resumed run computed only the items
                                       the earlier files lacked)
Prints one line per failure and exits 1, else a summary and exits 0.
"""
import re
import struct
import sys

MAGIC = b"btob-checkpoint 1\n"


def read(path):
    """(header bytes, [(items, record bytes)]) of one file."""
    with open(path, "rb") as f:
        b = f.read()
    if not b.startswith(MAGIC):
        raise SystemExit(f"{path}: not a btob checkpoint")
    at, header, parts = len(MAGIC), None, []
    while len(b) - at >= 16:
        size, _ = struct.unpack_from("<QQ", b, at)
        if size > len(b) - at - 16:
            break
        payload = b[at + 16 : at + 16 + size]
        at += 16 + size
        if header is None:
            header = at
            continue
        (n,) = struct.unpack_from("<Q", payload, 0)
        parts.append((list(struct.unpack_from(f"<{n}Q", payload, 8)), 16 + size))
    return header or len(b), parts


def rank_of(path):
    m = re.search(r"\.checkpoint\.([0-9]+)$", path)
    return int(m.group(1)) if m else 0


def share(ranks, n, files):
    bad = []
    sizes, counts = {}, {}
    for path in files:
        header, parts = read(path)
        k = rank_of(path)
        items = [i for its, _ in parts for i in its]
        sizes[k], counts[k] = header + sum(s for _, s in parts), len(items)
        foreign = [i for i in items if i % ranks != k]
        if foreign:
            bad.append(f"{path}: holds items of another rank ({foreign[:5]}), not only its share i mod {ranks} = {k}")
        per_item = max((s / len(its) for its, s in parts if its), default=0)
        bound = header + -(-n // ranks) * per_item
        if sizes[k] > bound:
            bad.append(f"{path}: {sizes[k]} bytes, over its share of the checkpoint ({bound:.0f} bytes)")
    missing = sorted(set(range(ranks)) - set(sizes))
    if missing:
        bad.append(f"no checkpoint file of rank(s) {missing}: {files}")
    return bad, f"{len(sizes)} files of {ranks} ranks: items {counts}, bytes {sizes}"


def once(files):
    seen, bad = {}, []
    for path in files:
        for its, _ in read(path)[1]:
            for i in its:
                if i in seen:
                    bad.append(f"item {i} in {seen[i]} and {path}")
                seen[i] = path
    return bad[:5], f"{len(seen)} items, each once, in {len(files)} files"


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("share", "once"):
        raise SystemExit(__doc__)
    if sys.argv[1] == "share":
        bad, summary = share(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:])
    else:
        bad, summary = once(sys.argv[2:])
    for line in bad:
        print(line)
    if bad:
        sys.exit(1)
    print(summary)
