#!/usr/bin/env python3
# Reads a PNG (8-bit RGB or RGBA, any filter; standard library only) and prints, as JSON, the
# number of pixels whose colour is close to R,G,B and their mean column and row; or, with --tiles,
# per tile of a grid the pixels that differ from the background.
# With --bbox, the box of the pixels that differ from the background (the top-left pixel).
# usage: png_probe.py FILE.png R G B [TOLERANCE] | png_probe.py FILE.png --tiles COLUMNS ROWS |
#        png_probe.py FILE.png --bbox
import json, struct, sys, zlib

def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise SystemExit(f'{path}: not a PNG')
    at, idat = 8, b''
    while at < len(data):
        (n,) = struct.unpack('>I', data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + n]
        at += 12 + n
        if kind == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', body[:10])
        elif kind == b'IDAT':
            idat += body
    if depth != 8 or ctype not in (2, 6):
        raise SystemExit(f'{path}: only 8-bit RGB/RGBA is read here')
    bpp = 3 if ctype == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows

def colour_mode(path, want, tol):
    w, h, bpp, rows = read_png(path)
    count = sx = sy = 0
    for y, line in enumerate(rows):
        for x in range(w):
            px = line[x * bpp:x * bpp + 3]
            if all(abs(px[k] - want[k]) <= tol for k in range(3)):
                count, sx, sy = count + 1, sx + x, sy + y
    print(json.dumps({'width': w, 'height': h, 'count': count,
                      'x': sx / count if count else None, 'y': sy / count if count else None}))


def tiles_mode(path, cols, nrows):
    """Per tile of a cols x nrows grid: how many pixels differ from the background (the picture's
    top-left pixel), their mean column and row inside the tile, and a digest of the tile."""
    w, h, bpp, rows = read_png(path)
    bg = bytes(rows[0][0:3])
    tw, th = w // cols, h // nrows
    tiles = []
    for ty in range(nrows):
        for tx in range(cols):
            drawn = sx = sy = 0
            digest = zlib.crc32(b''.join(bytes(rows[ty * th + y][tx * tw * bpp:(tx + 1) * tw * bpp]) for y in range(th)))
            for y in range(th):
                line = rows[ty * th + y]
                for x in range(tw):
                    if bytes(line[(tx * tw + x) * bpp:(tx * tw + x) * bpp + 3]) != bg:
                        drawn, sx, sy = drawn + 1, sx + x, sy + y
            tiles.append({'drawn': drawn, 'x': sx / drawn if drawn else None, 'y': sy / drawn if drawn else None,
                          'digest': digest})
    print(json.dumps({'width': w, 'height': h, 'tiles': tiles}))


def bbox_mode(path):
    w, h, bpp, rows = read_png(path)
    bg = bytes(rows[0][0:3])
    xs, ys = [], []
    for y, line in enumerate(rows):
        for x in range(w):
            if bytes(line[x * bpp:x * bpp + 3]) != bg:
                xs.append(x)
                ys.append(y)
    box = [min(xs), min(ys), max(xs), max(ys)] if xs else None
    print(json.dumps({'width': w, 'height': h, 'bbox': box,
                      'bbox_width': box[2] - box[0] + 1 if box else 0, 'bbox_height': box[3] - box[1] + 1 if box else 0}))


if __name__ != '__main__':
    pass  # imported for read_png
elif len(sys.argv) == 3 and sys.argv[2] == '--bbox':
    bbox_mode(sys.argv[1])
elif len(sys.argv) == 5 and sys.argv[2] == '--tiles':
    tiles_mode(sys.argv[1], int(sys.argv[3]), int(sys.argv[4]))
else:
    colour_mode(sys.argv[1], [int(v) for v in sys.argv[2:5]], int(sys.argv[5]) if len(sys.argv) > 5 else 60)
