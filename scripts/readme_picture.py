#!/usr/bin/env python3
"""The README's picture: the playground's shaded image beside the same shading with the ray-traced
irradiance truth in place of the estimate (penumbra-playground --reference writes both).

  scripts/readme_picture.py [--playground build/playground/penumbra-playground] [--out docs/images/boxes_truth.png]

Renders `boxes` at 512x512 with 16x16 rays a pixel, crops both images to the boxes and their shadows,
and writes them side by side. Prints the playground's error lines, which the README's caption quotes.
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

CROP = (slice(160, 440), slice(40, 470))  # rows, columns of the 512x512 image: the boxes and their shadows


def read_png(path):
    """An 8-bit RGB, non-interlaced PNG (what the playground writes) as an array of rows."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if (depth, colour, interlace) != (8, 2, 0):
                sys.exit(f"{path}: only 8-bit RGB without interlacing is read here")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, 1 + 3 * width)
    out = np.zeros((height, 3 * width), np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        up = out[y - 1] if y else np.zeros(3 * width, np.int32)
        if kind == 0:
            row = line
        elif kind == 2:
            row = (line + up) & 255
        else:  # 1 sub, 3 average, 4 Paeth: each byte depends on the one three to its left
            row = np.zeros(3 * width, np.int32)
            for x in range(3 * width):
                left = row[x - 3] if x >= 3 else 0
                upper_left = up[x - 3] if x >= 3 else 0
                if kind == 1:
                    predictor = left
                elif kind == 3:
                    predictor = (left + up[x]) // 2
                else:
                    p = left + up[x] - upper_left
                    pa, pb, pc = abs(p - left), abs(p - up[x]), abs(p - upper_left)
                    predictor = left if pa <= pb and pa <= pc else up[x] if pb <= pc else upper_left
                row[x] = (line[x] + predictor) & 255
        out[y] = row
    return out.astype(np.uint8).reshape(height, width, 3)


def write_png(path, image):
    height, width, _ = image.shape
    raw = b"".join(b"\x00" + image[y].tobytes() for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path + ".tmp", "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    os.replace(path + ".tmp", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--playground", default="build/playground/penumbra-playground")
    parser.add_argument("--out", default="docs/images/boxes_truth.png")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        run = subprocess.run([args.playground, "--headless", "--scene", "boxes", "--size", "512x512", "--reference",
                              "--samples", "16", "--out", os.path.join(work, "boxes.png")],
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"error: {args.playground} failed:\n{run.stderr}")
        print("\n".join(line for line in run.stdout.splitlines() if "MAE" in line or "false light" in line))
        estimate = read_png(os.path.join(work, "boxes.png"))[CROP]
        truth = read_png(os.path.join(work, "boxes.reference.png"))[CROP]
    gap = np.full((estimate.shape[0], 6, 3), 255, np.uint8)
    write_png(args.out, np.concatenate([estimate, gap, truth], axis=1))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
