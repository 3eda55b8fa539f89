#!/usr/bin/python3
"""An animated GIF from PNG pictures, in the order given (Pillow, Debian's python3-pil).

Usage: scripts/animate.py --out FILE.gif [--fps N] PICTURE.png...
`cdbench snapshot --frames A:B:STEP --out FILE.gif` runs it on the pictures it wrote. The GIF is
written beside FILE under a temporary name and renamed, so a stopped run leaves no partial GIF.
"""

import argparse
import os
import sys
from pathlib import Path


def main(argv=None):
    p = argparse.ArgumentParser(prog="animate.py", description="animated GIF from PNG pictures")
    p.add_argument("--out", type=Path, required=True, metavar="FILE.gif")
    p.add_argument("--fps", type=int, default=10, help="pictures per second (default 10)")
    p.add_argument("pictures", nargs="+", type=Path, metavar="PICTURE.png")
    args = p.parse_args(argv)
    if not 1 <= args.fps <= 60:
        print(f"animate.py: --fps {args.fps}: expected 1..60", file=sys.stderr)
        return 2
    try:
        from PIL import Image
    except ImportError:
        print("animate.py: Pillow is not installed (Debian: apt-get install python3-pil)", file=sys.stderr)
        return 2
    frames = []
    for path in args.pictures:
        try:
            with Image.open(path) as im:
                # 256 colours per frame, chosen for that frame, without dithering: flat shading
                # compresses far better than dithered noise and looks the same at this size.
                frames.append(im.convert("RGB").quantize(colors=256, dither=Image.Dither.NONE))
        except OSError as e:
            print(f"animate.py: {path}: cannot read ({e})", file=sys.stderr)
            return 2
    tmp = args.out.with_name(args.out.name + f".tmp.{os.getpid()}")
    try:
        frames[0].save(tmp, format="GIF", save_all=True, append_images=frames[1:],
                       duration=round(1000 / args.fps), loop=0)
        os.replace(tmp, args.out)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        print(f"animate.py: {args.out}: cannot write ({e})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
