#!/usr/bin/env python3
"""Checks the errors `lodforge lod` writes against an independent dense
measurement: for every simplified level of every single-shape scene given,
`lodforge compare` of level 0 against that level of the output (two-sided
Hausdorff, SAMPLES area samples per direction, another seed) must stay at or
below the level's reported error (statistics JSON, times the shape's scale).
Prints a Markdown table and exits 1 if any level's error is exceeded.

usage: lod_error_check.py LODFORGE [--samples N] SCENE...
"""
import json
import os
import subprocess
import sys
import tempfile


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
        for scene in args:
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


main()
