#!/usr/bin/env python3
"""The three ways of showing an impostor's neighbouring pictures, side by side, on the project's own crowd.

    scripts/impostor_views_picture.py [path/to/aloha] [--out docs/images/impostor_views.png]

Renders frame 49 of data/scenes/crowd_1k.json (the built-in humanoids: nothing third-party) with every impostor at
full resolution (`--far-layer 0`, as a GPU draws them) once per `--impostor-views` way (nearest, pick, blend), crops
the same stretch of the crowd from each (walkers 30 to 60 px tall), scales it 3x without filtering and writes the
three crops left to right as one PNG (docs/PERFORMANCE.md, "Twenty-seventh session"). The renders go to a temporary
folder; an existing output file is replaced only when every render succeeded. Standard library only (the PNG reader
of scripts/silhouette_coverage.py).
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from silhouette_coverage import read_png  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FRAME = 49
CROP = (500, 300, 700, 460)  # x0, y0, x1, y1 in the 1280 x 720 frame
SCALE = 3
WAYS = ("nearest", "pick", "blend")


def write_png(path, width, height, rows):
    """Writes rows of (r, g, b) tuples as an 8-bit RGB PNG."""
    raw = b"".join(b"\0" + bytes(c for pixel in row for c in pixel) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("aloha", nargs="?", default=os.path.join(ROOT, "build/release/host/tool/aloha"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs/images/impostor_views.png"))
    args = parser.parse_args()
    if not os.access(args.aloha, os.X_OK):
        sys.exit(f"{args.aloha}: not an executable (build the tool first, or give its path)")
    x0, y0, x1, y1 = CROP
    strips = []
    with tempfile.TemporaryDirectory() as tmp:
        for way in WAYS:
            png = os.path.join(tmp, way + ".png")
            command = [args.aloha, "render", os.path.join(ROOT, "data/scenes/crowd_1k.json"), "--frame", str(FRAME),
                       "--far-layer", "0", "--impostor-views", way, "--out", png, "--force"]
            done = subprocess.run(command, capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr}")
            width, height, rows = read_png(png)
            if width < x1 or height < y1:
                sys.exit(f"{png}: {width} x {height}, smaller than the crop {CROP}")
            strips.append([[p for p in row[x0:x1] for _ in range(SCALE)] for row in rows[y0:y1] for _ in range(SCALE)])
    out_rows = [sum((strip[y] for strip in strips), []) for y in range(len(strips[0]))]
    write_png(args.out, len(out_rows[0]), len(out_rows), out_rows)
    print(f"{args.out}: {' | '.join(WAYS)}, {len(out_rows[0])} x {len(out_rows)} px")


if __name__ == "__main__":
    main()
