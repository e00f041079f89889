#!/usr/bin/env python3
"""Check a viewer snapshot: it must exist, be a PNG, and not be blank.

Usage: check_snapshot.py PNG [--expect-red] [--expect-rope] [--expect-drawn] [--min-rope-height F]

Blank means fewer than 1 % of the pixels differ from the most common colour (a window that
drew nothing, or only its background). --expect-red also requires the red panel of a missing
exercise: at least 2 % of the pixels strongly red (r > 150, g < 60, b < 60). --expect-rope
requires the masses and springs, drawn in force colours from green to red: at least 300
saturated green-to-red pixels (max(r, g) > 140, b < 90, |r - g| > 60) and no red panel.
--expect-drawn requires the scene itself instead of a missing-exercise panel (shaded cloth is
not in saturated force colours): no red panel.
--min-rope-height F requires the rope's force-coloured pixels (left of the control panel, which
starts at 70 % of the width) to span at least F of the window's height: the camera frames the
rope instead of showing it small in a large box.
Only the standard library: zlib for the data, struct for the chunks, PNG filters by hand.
"""
import struct
import sys
import zlib
from collections import Counter


def read_png(path):
    """Return (width, height, rows) with rows a list of bytes objects of RGB(A) pixels."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, header = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    width, height, depth, color, _, _, interlace = header
    if depth != 8 or color not in (2, 6) or interlace != 0:
        raise ValueError(f"{path}: expected 8-bit RGB or RGBA without interlacing")
    bpp = 3 if color == 2 else 4
    raw = zlib.decompress(b"".join(idat))
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, bpp, rows


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 1
    path, expect_red, expect_rope = sys.argv[1], "--expect-red" in sys.argv[2:], "--expect-rope" in sys.argv[2:]
    expect_drawn = "--expect-drawn" in sys.argv[2:]
    min_height = float(sys.argv[sys.argv.index("--min-rope-height") + 1]) if "--min-rope-height" in sys.argv else 0.0
    try:
        width, height, bpp, rows = read_png(path)
    except (OSError, ValueError, zlib.error) as e:
        print(f"FAIL: {e}")
        return 1

    pixels = Counter()
    red = 0
    rope = 0
    rope_rows = []  # rows holding force-coloured pixels of the scene (left of the panel)
    for y, row in enumerate(rows):
        for i in range(0, len(row), bpp):
            r, g, b = row[i], row[i + 1], row[i + 2]
            pixels[(r, g, b)] += 1
            if r > 150 and g < 60 and b < 60:
                red += 1
            if max(r, g) > 140 and b < 90 and abs(r - g) > 60:
                rope += 1
                if i // bpp < 0.7 * width and (not rope_rows or rope_rows[-1] != y):
                    rope_rows.append(y)
    total = width * height
    common, count = pixels.most_common(1)[0]
    differing = 1.0 - count / total
    print(f"{path}: {width}x{height}, {differing:.1%} of the pixels differ from the most common colour "
          f"{common}, {red / total:.1%} strongly red, {rope} pixels in force colours")
    ok = True
    if differing < 0.01:
        print("FAIL: the snapshot is blank")
        ok = False
    if expect_red and red < 0.02 * total:
        print("FAIL: no red panel of a missing exercise in the snapshot")
        ok = False
    if expect_rope and (rope < 300 or red >= 0.02 * total):
        print("FAIL: no rope in force colours, or a missing-exercise panel, in the snapshot")
        ok = False
    rope_height = (rope_rows[-1] - rope_rows[0] + 1) / height if rope_rows else 0.0
    if min_height > 0:
        print(f"the rope spans {rope_height:.0%} of the window's height")
        if rope_height < min_height:
            print(f"FAIL: the rope spans less than {min_height:.0%} of the window's height: the camera does not frame it")
            ok = False
    if expect_drawn and red >= 0.02 * total:
        print("FAIL: a missing-exercise panel instead of the scene in the snapshot")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
