#!/usr/bin/env python3
"""Writes the demo's Cartesian input: a raw little-endian uint8 volume (x fastest) of a torus knotted
with Marschner-Lobb ripples, so `setup.sh demo` has data of its own to convert (no download, no
licence question). Usage: make_demo_volume.py OUT.raw N  (N^3 voxels)."""
import math
import sys


def main():
    out, n = sys.argv[1], int(sys.argv[2])
    data = bytearray(n * n * n)
    i = 0
    for k in range(n):
        z = 2.0 * k / (n - 1) - 1.0
        for j in range(n):
            y = 2.0 * j / (n - 1) - 1.0
            for x_index in range(n):
                x = 2.0 * x_index / (n - 1) - 1.0
                # Torus of radii 0.55 / 0.25 about the z axis, its density falling off smoothly.
                ring = math.hypot(x, y) - 0.55
                d = math.sqrt(ring * ring + z * z)
                ripple = 0.04 * math.cos(12.0 * math.atan2(y, x))
                value = min(1.0, max(0.0, 1.0 - (d + ripple) / 0.35))
                data[i] = int(round(255.0 * value))
                i += 1
    with open(out, "wb") as f:
        f.write(data)


if __name__ == "__main__":
    main()
