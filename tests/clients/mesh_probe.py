#!/usr/bin/env python3
# Reads the meshes of an OBJ file or of our VRML97 output (IndexedFaceSets with triangles) and
# prints, as JSON: vertex and triangle counts, the signed volume (positive when faces point
# outward), the bounding box, and with --vertices every vertex as [x, y, z] or [x, y, z, r, g, b].
# usage: mesh_probe.py FILE.obj|FILE.wrl [--vertices]
import json, re, sys

path = sys.argv[1]
text = open(path).read()
points, tris, colours = [], [], []
if path.endswith('.obj'):
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == 'v':
            points.append([float(v) for v in f[1:4]])
        elif f and f[0] == 'f':
            idx = [int(v.split('/')[0]) - 1 for v in f[1:]]
            tris += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
else:
    def numbers(block):
        return [float(v) for v in re.split(r'[\s,]+', block.strip()) if v]
    for shape in re.finditer(r'IndexedFaceSet \{(.*?)\n  \}', text, re.S):
        body, base = shape.group(1), len(points)
        pts = numbers(re.search(r'point \[([^\]]*)\]', body).group(1))
        points += [pts[i:i + 3] for i in range(0, len(pts), 3)]
        c = re.search(r'color \[([^\]]*)\]', body)
        if c:
            cs = numbers(c.group(1))
            colours += [cs[i:i + 3] for i in range(0, len(cs), 3)]
        face = []
        for v in numbers(re.search(r'coordIndex \[([^\]]*)\]', body).group(1)):
            if v < 0:
                tris += [[face[0] + base, face[k] + base, face[k + 1] + base] for k in range(1, len(face) - 1)]
                face = []
            else:
                face.append(int(v))
volume = 0.0
for a, b, c in tris:
    p, q, r = points[a], points[b], points[c]
    volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])) / 6
out = {'vertices': len(points), 'triangles': len(tris), 'volume': volume,
       'bbox': [min(p[k] for p in points) for k in range(3)] + [max(p[k] for p in points) for k in range(3)] if points else []}
if '--vertices' in sys.argv:
    out['points'] = [p + colours[i] if len(colours) == len(points) else p for i, p in enumerate(points)]
print(json.dumps(out))
