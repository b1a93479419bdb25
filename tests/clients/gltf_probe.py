#!/usr/bin/env python3
# Reads a .glb (standard library only) and prints, as JSON, its node and mesh counts and, per
# animation channel, the node it drives, the property, the interpolation and the key times and
# values read from the binary chunk. usage: gltf_probe.py FILE.glb
import json, struct, sys

data = open(sys.argv[1], 'rb').read()
magic, version, length = struct.unpack('<III', data[:12])
if magic != 0x46546C67 or length != len(data):
    raise SystemExit(f'{sys.argv[1]}: not a glTF binary of {len(data)} bytes')
at, doc, binary = 12, None, b''
while at < len(data):
    n, kind = struct.unpack('<II', data[at:at + 8])
    body = data[at + 8:at + 8 + n]
    if kind == 0x4E4F534A: doc = json.loads(body)
    elif kind == 0x004E4942: binary = body
    at += 8 + n

def accessor(k):
    a = doc['accessors'][k]
    v = doc['bufferViews'][a['bufferView']]
    width = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4}[a['type']]
    if a['componentType'] != 5126:
        raise SystemExit('only float accessors are read here')
    start = v.get('byteOffset', 0) + a.get('byteOffset', 0)
    flat = struct.unpack_from(f'<{a["count"] * width}f', binary, start)
    return [list(flat[i:i + width]) if width > 1 else flat[i] for i in range(0, len(flat), width)]

channels = []
for anim in doc.get('animations', []):
    for c in anim['channels']:
        s = anim['samplers'][c['sampler']]
        channels.append({'node': c['target']['node'], 'path': c['target']['path'],
                         'interpolation': s.get('interpolation', 'LINEAR'),
                         'times': accessor(s['input']), 'values': accessor(s['output'])})
print(json.dumps({'nodes': len(doc.get('nodes', [])), 'meshes': len(doc.get('meshes', [])),
                  'children': {i: n.get('children', []) for i, n in enumerate(doc.get('nodes', []))},
                  'channels': channels}))
