#!/usr/bin/env python3
"""png-check.py FILE WIDTH HEIGHT: is FILE a WIDTHxHEIGHT PNG of a camera picture, not a blank
or message screen? Prints one line (size, colours covering >= 2 % of the image) and exits 0 if
so, 1 if not. The standard library only (zlib): the host may have no imaging modules.

vimc's sensor shows 75 % colour bars, so a frame of the camera has several large areas of
different colours; a blank frame has one, the "camera unavailable" screen two (ground and text).
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, ihdr = 8, [], None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    width, height, depth, ctype, _, _, interlace = ihdr
    channels = {2: 3, 6: 4}.get(ctype)
    if depth != 8 or channels is None or interlace:
        raise ValueError(f"unsupported PNG (depth {depth}, colour type {ctype}, interlace {interlace})")
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        bpp = channels
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif f == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def main():
    path, want_w, want_h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    try:
        width, height, channels, rows = read_png(path)
    except (OSError, ValueError, TypeError, zlib.error) as e:
        print(f"{path}: {e}")
        return 1
    counts = {}
    for line in rows[::2]:  # every other row and column: plenty for areas of colour
        for x in range(0, width * channels, 2 * channels):
            key = (line[x] >> 6, line[x + 1] >> 6, line[x + 2] >> 6)
            counts[key] = counts.get(key, 0) + 1
    total = sum(counts.values())
    big = sorted((n for n in counts.values() if n >= 0.02 * total), reverse=True)
    print(f"{width}x{height}, {len(big)} colours over 2 % of the image, {len(counts)} in all")
    if (width, height) != (want_w, want_h):
        print(f"expected {want_w}x{want_h}")
        return 1
    if len(big) < 4:
        print("blank or a message screen, not a camera picture")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
