#!/usr/bin/env python3
"""Places 8-bit PNG images side by side (top-aligned, a gap between them) in one RGB PNG.

Usage: scripts/png_strip.py OUT.png IN.png[:X,Y,W,H] ... [--scale N] [--gap PX] [--vertical]

Used by scripts/readme-figure.sh for the README's figure. Python's standard library only (zlib):
reads 8-bit grey, grey+alpha, RGB and RGBA PNGs, non-interlaced, every filter type; alpha is
dropped. IN.png:X,Y,W,H takes the W x H crop at (X, Y). --scale N enlarges each input N times by
pixel replication, so single pixels stay sharp. --vertical stacks them top to bottom instead.
"""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG file")
    pos, idat, header = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        sys.exit(f"{path}: only 8-bit, non-interlaced grey/RGB(A) PNGs are supported")
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + predictor) & 255
        rows.append(line)
        previous = line
    rgb = []
    for line in rows:
        out = bytearray()
        for x in range(width):
            px = line[x * channels:(x + 1) * channels]
            out += bytes(px[:3]) if channels >= 3 else bytes([px[0]] * 3)
        rgb.append(out)
    return width, height, rgb


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def cropped(arg):
    path, _, box = arg.partition(":")
    w, h, rows = read_png(path)
    if not box:
        return w, h, rows
    x, y, cw, ch = (int(v) for v in box.split(","))
    if x < 0 or y < 0 or cw <= 0 or ch <= 0 or x + cw > w or y + ch > h:
        sys.exit(f"{arg}: the crop is not inside the {w}x{h} image")
    return cw, ch, [r[x * 3:(x + cw) * 3] for r in rows[y:y + ch]]


def main(argv):
    scale, gap, files, vertical = 1, 8, [], False
    i = 0
    while i < len(argv):
        if argv[i] == "--vertical":
            vertical = True
            i += 1
        elif argv[i] in ("--scale", "--gap"):
            value = int(argv[i + 1])
            scale, gap = (value, gap) if argv[i] == "--scale" else (scale, value)
            i += 2
        else:
            files.append(argv[i])
            i += 1
    if len(files) < 2:
        sys.exit(__doc__)
    out, images = files[0], [cropped(f) for f in files[1:]]
    scaled = []
    for w, h, rows in images:
        big = []
        for r in rows:
            line = bytearray()
            for x in range(w):
                line += r[x * 3:x * 3 + 3] * scale
            big.extend([line] * scale)
        scaled.append((w * scale, h * scale, big))
    if vertical:
        width = max(w for w, _, _ in scaled)
        height = sum(h for _, h, _ in scaled) + gap * (len(scaled) - 1)
    else:
        width = sum(w for w, _, _ in scaled) + gap * (len(scaled) - 1)
        height = max(h for _, h, _ in scaled)
    canvas = [bytearray(b"\xff" * (width * 3)) for _ in range(height)]
    x0 = y0 = 0
    for w, h, rows in scaled:
        for y in range(h):
            canvas[y0 + y][x0 * 3:(x0 + w) * 3] = rows[y]
        if vertical:
            y0 += h + gap
        else:
            x0 += w + gap
    write_png(out, width, height, canvas)


if __name__ == "__main__":
    main(sys.argv[1:])
