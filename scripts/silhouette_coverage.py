#!/usr/bin/env python3
"""How much of a reference render's characters another render of the same frame covers, and the other way round.

    scripts/silhouette_coverage.py REFERENCE.png OTHER.png [OTHER2.png ...]

A pixel is a character's when it differs from the background (the reference's most common colour) by more than 24
levels summed over R, G and B, as `aloha profile --fidelity` reads it (fidelity.silhouettes, host/tool/image_compare.hpp);
this script does the same for any two renders. For each OTHER image it prints the two images' character pixel counts, the share of the
reference's character pixels with one of OTHER's within 1 px (recall: characters drawn where they stand) and the share
of OTHER's with one of the reference's within 1 px (precision: nothing drawn where nobody stands). PSNR over a whole
frame hardly sees a far crowd missing (the dark background dominates it); these see it directly
(docs/PERFORMANCE.md, "Impostors seen from above"). Reads 8-bit RGB or RGBA PNGs (aloha's own) with the standard
library only.
"""
import collections
import struct
import sys
import zlib


def read_png(path):
    """Width, height and rows of (r, g, b) tuples of an 8-bit, non-interlaced RGB or RGBA PNG."""
    try:
        data = open(path, "rb").read()
    except OSError as e:
        sys.exit(f"{path}: {e.strerror}")
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    if header is None:
        sys.exit(f"{path}: no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        sys.exit(f"{path}: only 8-bit RGB or RGBA PNGs without interlacing are read (depth {depth}, colour type {colour})")
    bpp = 4 if colour == 6 else 3
    stride = width * bpp
    raw = zlib.decompress(idat)
    rows, prev, at = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def character_mask(rows, background):
    return [[sum(abs(p[c] - background[c]) for c in range(3)) > 24 for p in row] for row in rows]


def near(mask, width, height, x, y, reach=1):
    for yy in range(max(0, y - reach), min(height, y + reach + 1)):
        row = mask[yy]
        for xx in range(max(0, x - reach), min(width, x + reach + 1)):
            if row[xx]:
                return True
    return False


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    width, height, reference_rows = read_png(sys.argv[1])
    background = collections.Counter(p for row in reference_rows for p in row).most_common(1)[0][0]
    reference = character_mask(reference_rows, background)
    ref_count = sum(map(sum, reference))
    for path in sys.argv[2:]:
        w, h, rows = read_png(path)
        if (w, h) != (width, height):
            sys.exit(f"{path}: {w} x {h} pixels, the reference is {width} x {height}")
        other = character_mask(rows, background)
        count = sum(map(sum, other))
        recall = sum(1 for y in range(height) for x in range(width) if reference[y][x] and near(other, width, height, x, y))
        precision = sum(1 for y in range(height) for x in range(width) if other[y][x] and near(reference, width, height, x, y))
        print(f"{path}: reference {ref_count} px, this {count} px ({count / max(ref_count, 1):.2f}x); reference covered "
              f"within 1 px {recall / max(ref_count, 1):.3f}; this on the reference within 1 px {precision / max(count, 1):.3f}")


if __name__ == "__main__":
    main()
