#!/usr/bin/python3
"""Per PNG of one or more folders: the fraction of covered pixels (alpha > 0) that are clipped
white (every channel >= 254) and that are black (every channel <= 2). The measure of a
thumbnail's exposure that the README's display transform is judged by.

bench/clipped_black.py DIR [DIR ...]   (a markdown table on stdout; a column pair per folder)
Render the folders first, e.g. one PNG per asset with the bare command:
  build/bin/manylight render ASSET.gltf -o DIR/NAME.png --size 320x240
"""
import glob
import os
import sys

import numpy as np
import OpenImageIO as oiio


def fractions(path):
    p = oiio.ImageBuf(path).get_pixels(oiio.UINT8).astype(int)
    c = p[p[..., 3] > 0][:, :3]
    if len(c) == 0:
        return None
    return (c.min(axis=1) >= 254).mean() * 100, (c.max(axis=1) <= 2).mean() * 100


def main(dirs):
    names = sorted({os.path.basename(f)[:-4] for d in dirs for f in glob.glob(d + "/*.png")})
    print("| image | " + " | ".join(f"{d} clipped | {d} black" for d in dirs) + " |")
    print("|---|" + "---|---|" * len(dirs))
    for n in names:
        row = [n]
        for d in dirs:
            f = os.path.join(d, n + ".png")
            r = fractions(f) if os.path.exists(f) else None
            row += ["—", "—"] if r is None else [f"{r[0]:.1f}%", f"{r[1]:.1f}%"]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
