#!/usr/bin/env python3
"""Two glTF binaries that should be one: the same JSON and integer data, and float data that differs
in at most 0.1% of the values, each by at most 1e-6 of the scene's size (the browser build's C
library computes a few of the mesher's double-precision functions, cos and acos in the QEF's
eigen solver, one ulp apart from glibc's). Prints the differences; exit status 1 past that bound.
usage: glb_close.py NATIVE.glb WASM.glb"""
import array
import json
import struct
import sys

SIZES = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4}


def load(path):
    b = open(path, 'rb').read()
    n = struct.unpack('<I', b[12:16])[0]
    return json.loads(b[20:20 + n]), b[20 + n + 8:]


def main():
    (ja, ba), (jb, bb) = load(sys.argv[1]), load(sys.argv[2])
    if ja != jb:
        print('the glTF JSON differs')
        return 1
    floats = differ = 0
    worst = 0.0
    size = 1e-30
    for acc in ja.get('accessors', []):
        if 'max' in acc and acc['type'] == 'VEC3' and acc['componentType'] == 5126:
            size = max(size, max(h - l for h, l in zip(acc['max'], acc['min'])))
    for acc in ja.get('accessors', []):
        view = ja['bufferViews'][acc['bufferView']]
        start = view.get('byteOffset', 0) + acc.get('byteOffset', 0)
        count = SIZES.get(acc['type'], 16) * acc['count']
        width = 2 if acc['componentType'] in (5122, 5123) else 1 if acc['componentType'] in (5120, 5121) else 4
        raw_a, raw_b = ba[start:start + width * count], bb[start:start + width * count]
        if acc['componentType'] != 5126:
            if raw_a != raw_b:
                print('integer data differs')
                return 1
            continue
        fa, fb = array.array('f', raw_a), array.array('f', raw_b)
        floats += count
        for x, y in zip(fa, fb):
            if x != y:
                differ += 1
                worst = max(worst, abs(x - y))
    ok = differ <= floats / 1000 and worst <= 1e-6 * size
    print(f'{differ} of {floats} floats differ, at most by {worst:.3g} (scene size {size:.3g})')
    return 0 if ok else 1


sys.exit(main())
