#!/usr/bin/env python3
"""Writes the scale benchmark's scene: 36 distinct Stanford bunnies under
transforms in one VRML 1.0 file (about 98 MB, 2.5 M triangles).

Each bunny is the scan of ../shared/data/meshes/bun_zipper.ply with its own
deterministic displacement (up to 0.2 % of its size along a smooth field),
so no two shapes are equal and no reader or cache can share them; each sits
in a 6 x 6 grid, turned about y by its own angle.

usage: make_bunny_scene.py [BUNNY.ply] OUT.wrl
"""
import math
import os
import sys


def read_ascii_ply(path):
    with open(path) as f:
        nv = nf = 0
        for line in f:
            w = line.split()
            if w[:2] == ["element", "vertex"]:
                nv = int(w[2])
            elif w[:2] == ["element", "face"]:
                nf = int(w[2])
            elif w and w[0] == "end_header":
                break
        points = [tuple(map(float, f.readline().split()[:3])) for _ in range(nv)]
        faces = [tuple(map(int, f.readline().split()[1:4])) for _ in range(nf)]
    return points, faces


def main():
    args = sys.argv[1:]
    here = os.path.dirname(os.path.abspath(__file__))
    bunny = args[0] if len(args) == 2 else os.path.join(here, "../../shared/data/meshes/bun_zipper.ply")
    out = args[-1]
    points, faces = read_ascii_ply(bunny)
    index_text = "".join(f"{a},{b},{c},-1,\n" for a, b, c in faces)
    with open(out + ".tmp", "w") as f:
        f.write("#VRML V1.0 ascii\n# lodforge scale benchmark: 36 distinct bunnies\nSeparator {\n")
        for k in range(36):
            row, col = divmod(k, 6)
            amp = 0.0003 * (1 + k % 5)
            f.write(f"Separator {{\nTransform {{ translation {0.25 * col} 0 {0.25 * row} "
                    f"rotation 0 1 0 {0.17 * k:.4f} }}\nCoordinate3 {{ point [\n")
            f.write("".join(
                f"{x + amp * math.sin(31 * y + k):.6g} {y + amp * math.sin(29 * z + 2 * k):.6g} "
                f"{z + amp * math.sin(37 * x + 3 * k):.6g},\n" for x, y, z in points))
            f.write("] }\nIndexedFaceSet { coordIndex [\n")
            f.write(index_text)
            f.write("] }\n}\n")
        f.write("}\n")
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
