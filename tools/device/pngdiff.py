#!/usr/bin/env python3
"""Pixels that differ between two 8-bit PNG images of one size (fccvdb render's), with the standard
library alone (the GPU machine has no imaging modules): the count, their bounding box, the largest
channel difference, and the first few. A measurement tool for the device scripts."""
import struct, sys, zlib


def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f'{path}: not a PNG')
    pos, idat, width = 8, b'', 0
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            width, height, depth, colour, _, _, interlace = struct.unpack('>IIBBBBB', body)
            if depth != 8 or colour not in (0, 2, 4, 6) or interlace:
                sys.exit(f'{path}: only 8-bit, non-interlaced PNGs')
            channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else (b if pb <= pc else c))) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


wa, ha, ca, a = read_png(sys.argv[1])
wb, hb, cb, b = read_png(sys.argv[2])
if (wa, ha, ca) != (wb, hb, cb):
    sys.exit('different sizes')
bad, box, worst, first = 0, [wa, ha, -1, -1], 0, []
for y in range(ha):
    for x in range(wa):
        pa, pb = a[y][x * ca:(x + 1) * ca], b[y][x * ca:(x + 1) * ca]
        if pa != pb:
            bad += 1
            box = [min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
            worst = max(worst, max(abs(p - q) for p, q in zip(pa, pb)))
            if len(first) < 8:
                first.append(f'({x},{y}) {list(pa)} {list(pb)}')
print(f'{bad} of {wa * ha} pixels differ' + (f', in x {box[0]}-{box[2]} y {box[1]}-{box[3]}, by at most {worst}/255; ' + '; '.join(first) if bad else ''))
