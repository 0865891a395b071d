#!/usr/bin/env python3
"""Writes uv_grid.png, the test texture of this lab's `uv_check` pass (python3, no packages).

A UV test grid: 8 x 8 checker cells over a colour ramp whose red grows with s and whose green
grows with t, so that every way of getting texture coordinates wrong (flipped, swapped, scaled,
shifted) shows as a different picture. 512 x 512 texels, deliberately not the size of the screen
(256 x 256) nor of the pattern target, so that code which assumes a texture size shows too.
The framework loads PNGs with their top row at t = 1 (OpenGL's convention), so t is computed
from the bottom row up. Run it from this folder: python3 make_uv_grid.py
"""
import struct
import zlib

SIZE = 512
CELLS = 8


def texel(x, row):
    s = (x + 0.5) / SIZE
    t = 1.0 - (row + 0.5) / SIZE  # row 0 is the top of the picture, t = 1
    i, j = int(s * CELLS), int(t * CELLS)
    light = 1.0 if (i + j) % 2 == 0 else 0.55
    r, g, b = 0.15 + 0.85 * s, 0.15 + 0.85 * t, 0.45
    return bytes(round(255 * c * light) for c in (r, g, b))


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


raw = b"".join(b"\x00" + b"".join(texel(x, row) for x in range(SIZE)) for row in range(SIZE))
png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)) +
       chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
with open("uv_grid.png", "wb") as f:
    f.write(png)
