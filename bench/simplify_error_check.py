#!/usr/bin/env python3
"""The error `lodforge simplify` reports against a dense, independent
measurement (`lodforge compare`, 2 000 000 samples): for each shared mesh,
method and ratio, the reported error over the largest distance from the
result to the input. Run from the repository root after building:

    python3 bench/simplify_error_check.py [BUILD_DIR]
"""
import json
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else 'build'
lodforge = f'{build}/lodforge'
meshes = '../shared/data/meshes/'
out = '/tmp/lodforge_error_check.ply'


def run(args):
    return json.loads(subprocess.run([lodforge] + args, capture_output=True, text=True,
                                     check=True).stdout)


print('| mesh | method | ratio | triangles | reported | dense | reported / dense |')
print('|---|---|---|---|---|---|---|')
for mesh in ['bun_zipper.ply', 'cow.obj', 'fandisk.obj', 'horse.ply', 'teapot.obj', 'igea.ply']:
    for method in ['qem', 'decimate', 'cluster']:
        for ratio in ['0.5', '0.1', '0.01']:
            s = run(['simplify', meshes + mesh, '-o', out, '--ratio', ratio, '--method', method,
                     '--json'])
            c = run(['compare', meshes + mesh, out, '--json', '--samples', '2000000'])
            dense = c['b_to_a']['max']
            q = f"{s['error'] / dense:.3f}" if dense > 0 else 'dense 0'
            print(f"| {mesh} | {method} | {ratio} | {s['output_triangles']} | {s['error']:.4g} "
                  f"| {dense:.4g} | {q} |", flush=True)
