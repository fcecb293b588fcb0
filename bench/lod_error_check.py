#!/usr/bin/env python3
"""Checks the errors `lodforge lod` writes against an independent dense
measurement: for every simplified level of every single-shape scene given,
`lodforge compare` of level 0 against that level of the output (two-sided
Hausdorff, SAMPLES area samples per direction, another seed) must stay at or
below the level's reported error (statistics JSON, times the shape's scale).
Prints a Markdown table and exits 1 if any level's error is exceeded. A mesh
file (PLY, OBJ, OFF, STL) is first made a VRML 1.0 scene of one
IndexedFaceSet (through `lodforge simplify --ratio 1` to OBJ).

usage: lod_error_check.py LODFORGE [--samples N] SCENE_OR_MESH...
"""
import json
import os
import subprocess
import sys
import tempfile


def as_scene(lodforge, path, work):
    """The path of a VRML 1.0 scene of `path` (itself if it is a scene)."""
    if path.endswith(('.wrl', '.wrl.gz', '.iv', '.iv.gz')):
        return path
    obj = os.path.join(work, 'mesh.obj')
    subprocess.run([lodforge, 'simplify', path, '-o', obj, '--ratio', '1', '-q'], check=True)
    points, faces = [], []
    for line in open(obj):
        w = line.split()
        if w and w[0] == 'v':
            points.append(' '.join(w[1:4]))
        elif w and w[0] == 'f':
            faces.append(', '.join(str(int(x.split('/')[0]) - 1) for x in w[1:]))
    scene = os.path.join(work, os.path.splitext(os.path.basename(path))[0] + '.wrl')
    with open(scene, 'w') as out:
        out.write('#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [\n')
        out.write(''.join(p + ',\n' for p in points))
        out.write('] }\nIndexedFaceSet { coordIndex [\n')
        out.write(''.join(f + ', -1,\n' for f in faces))
        out.write('] }\n}\n')
    return scene


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    lodforge = args.pop(0)
    samples = 1000000
    if args[:1] == ['--samples']:
        samples = int(args[1])
        args = args[2:]
    exceeded = 0
    print('| scene | level | triangles | reported error | dense Hausdorff | reported / dense |')
    print('|---|---|---|---|---|---|')
    with tempfile.TemporaryDirectory() as work:
        for given in args:
            scene = as_scene(lodforge, given, work)
            out = os.path.join(work, 'out.wrl')
            stats = os.path.join(work, 'stats.json')
            subprocess.run([lodforge, 'lod', scene, '-o', out, '-q', '--stats', stats], check=True)
            shapes = json.load(open(stats))['shapes']
            if len(shapes) != 1:
                print(f'| {os.path.basename(scene)} | {len(shapes)} shapes: skipped | | | | |')
                continue
            shape = shapes[0]
            for k, level in enumerate(shape['levels'][1:], start=1):
                c = json.loads(subprocess.run(
                    [lodforge, 'compare', out, out, '--level-a', '0', '--level', str(k),
                     '--samples', str(samples), '--seed', '99', '--json', '-q'],
                    check=True, capture_output=True, text=True).stdout)
                reported = level['error'] * shape['scale']
                dense = c['hausdorff']
                ratio = reported / dense if dense > 0 else float('inf')
                if reported < dense:
                    exceeded += 1
                print(f"| {os.path.basename(scene)} | {k} | {level['triangles']} | {reported:.4g} "
                      f"| {dense:.4g} | {ratio:.3f}{' EXCEEDED' if reported < dense else ''} |",
                      flush=True)
    if exceeded:
        print(f'{exceeded} level(s) exceed their reported error', file=sys.stderr)
        sys.exit(1)


if __name__ == '__main__':
    main()
