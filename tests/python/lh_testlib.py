"""Shared helpers for the python3-openvdb interoperability tests.

Each test script is run as `/usr/bin/python3 SCRIPT.py /path/to/lighthouse`, exits 0 on
success, 1 on failure (after printing every failed check) and 77 (ctest SKIP_RETURN_CODE)
when pyopenvdb or numpy is missing.
"""

import os
import struct
import subprocess
import sys
import zlib

SKIP = 77


def import_openvdb():
    """Returns (pyopenvdb, numpy), or exits 77 if either is missing."""
    try:
        import numpy
        import pyopenvdb
    except ImportError as e:
        print("SKIP: %s (needs python3-openvdb and numpy for %s)" % (e, sys.executable))
        sys.exit(SKIP)
    return pyopenvdb, numpy


def lighthouse_from_argv():
    if len(sys.argv) != 2:
        print("usage: %s /path/to/lighthouse" % sys.argv[0])
        sys.exit(2)
    exe = os.path.abspath(sys.argv[1])
    if not os.access(exe, os.X_OK):
        print("FAIL: lighthouse binary '%s' is not executable" % exe)
        sys.exit(1)
    return exe


class Checks:
    """Collects failed checks so that one run reports all of them."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.count = 0

    def check(self, condition, message):
        self.count += 1
        if not condition:
            self.failures.append(message)
            print("FAIL: " + message)
        return bool(condition)

    def equal(self, actual, expected, what):
        return self.check(actual == expected, "%s: got %r, expected %r" % (what, actual, expected))

    def close(self, actual, expected, what, tol=1e-9):
        ok = all(abs(a - e) <= tol for a, e in zip(actual, expected)) and len(actual) == len(expected)
        return self.check(ok, "%s: got %r, expected %r (tolerance %g)" % (what, tuple(actual),
                                                                           tuple(expected), tol))

    def finish(self):
        if self.failures:
            print("%s: %d of %d checks FAILED" % (self.name, len(self.failures), self.count))
            sys.exit(1)
        print("%s: all %d checks passed" % (self.name, self.count))
        sys.exit(0)


def run(cmd, cwd=None, timeout=300):
    """Runs a command with no stdin; returns CompletedProcess with text stdout/stderr."""
    return subprocess.run([str(c) for c in cmd], cwd=cwd, stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          timeout=timeout)


def describe(proc):
    return "exit %d\n--- stdout:\n%s--- stderr:\n%s" % (proc.returncode, proc.stdout, proc.stderr)


def read_png_rgb(path):
    """Decodes an 8-bit RGB (or RGBA, alpha dropped) non-interlaced PNG.

    Returns (width, height, rows) with rows[y][x] = (r, g, b) as ints in 0..255. Handles the
    five scanline filter types (None, Sub, Up, Average, Paeth).
    """
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("%s: not a PNG file" % path)
    pos = 8
    width = height = None
    idat = b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            raise ValueError("%s: bad CRC in chunk %r" % (path, kind))
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, ctype, comp, filt, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace != 0 or comp != 0 or filt != 0:
                raise ValueError("%s: only 8-bit RGB/RGBA non-interlaced PNGs are supported "
                                 "(depth %d, colour type %d, interlace %d)"
                                 % (path, depth, ctype, interlace))
            channels = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    if width is None:
        raise ValueError("%s: no IHDR chunk" % path)
    raw = zlib.decompress(idat)
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError("%s: image data has %d bytes, expected %d"
                         % (path, len(raw), height * (stride + 1)))
    rows = []
    prev = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        ftype = raw[start]
        line = bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if ftype == 0:
                pred = 0
            elif ftype == 1:
                pred = a
            elif ftype == 2:
                pred = b
            elif ftype == 3:
                pred = (a + b) // 2
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            else:
                raise ValueError("%s: unknown filter type %d in row %d" % (path, ftype, y))
            line[i] = (line[i] + pred) & 0xFF
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def write_png_rgb(path, width, height, pixel, filters=(0, 1, 2, 3, 4)):
    """Writes an 8-bit RGB PNG, cycling through `filters` row by row (tests the decoder)."""
    def paeth(a, b, c):
        p = a + b - c
        pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
        return a if pa <= pb and pa <= pc else (b if pb <= pc else c)

    raw = bytearray()
    prev = bytearray(width * 3)
    for y in range(height):
        line = bytearray()
        for x in range(width):
            line += bytes(pixel(x, y))
        ftype = filters[y % len(filters)]
        out = bytearray([ftype])
        for i in range(len(line)):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            pred = [0, a, b, (a + b) // 2, paeth(a, b, c)][ftype]
            out.append((line[i] - pred) & 0xFF)
        raw += out
        prev = line

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(raw))))
        f.write(chunk(b"IEND", b""))
