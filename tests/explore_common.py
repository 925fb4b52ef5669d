# SPDX-License-Identifier: GPL-3.0-or-later
"""Starting and stopping `btob explore` for the explorer's tests (explore_server.py, explore_browser.py)."""
import os
import re
import signal
import subprocess


def start_server(btob, export_dir, cwd=None, threads=None):
    """Starts `btob explore --no-browser --port 0`; returns the process and the base URL it printed."""
    cmd = [os.path.abspath(btob), "explore", "--no-browser", "--port", "0", "--export", export_dir]
    if threads:
        cmd += ["--threads", str(threads)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=cwd)
    for line in proc.stdout:
        m = re.search(r"serving (http://\S+)/ ", line)
        if m:
            return proc, m.group(1)
    proc.wait()
    raise RuntimeError(f"btob explore did not start (exit {proc.returncode})")


def stop_server(proc):
    """SIGINT, as Ctrl-C: the server stops and exits 0."""
    proc.send_signal(signal.SIGINT)
    try:
        rest = proc.communicate(timeout=30)[0]
    except subprocess.TimeoutExpired:
        proc.kill()
        raise
    assert proc.returncode == 0, f"btob explore exited {proc.returncode}: {rest}"


def png_indices(data):
    """Decodes an 8-bit colour-mapped PNG (what the explorer sends) with the standard library: (width, height,
    rows of palette indices, palette).  An independent route from libpng, which wrote it."""
    import struct
    import zlib
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, palette = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 3), f"bit depth {depth}, colour type {colour}: expected 8-bit indexed"
        elif kind == b"PLTE":
            palette = [tuple(body[i:i + 3]) for i in range(0, n, 3)]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    rows, prev = [], bytes(w)
    for y in range(h):
        f, line = raw[y * (w + 1)], bytearray(raw[y * (w + 1) + 1:(y + 1) * (w + 1)])
        for x in range(w):  # PNG filters (one byte per pixel: the left neighbour is x - 1)
            a = line[x - 1] if x else 0
            b, c = prev[x], (prev[x - 1] if x else 0)
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(list(line))
        prev = bytes(line)
    return w, h, rows, palette
