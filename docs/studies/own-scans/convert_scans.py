#!/usr/bin/env python3
"""Copies nuScenes LIDAR_TOP scans (.pcd.bin: five float32 per point, x y z intensity ring)
into plain folders: as they are, as binary PCD files and as binary little-endian PLY files,
keeping each file's name (and so its microsecond timestamp) and the raw 0-255 intensities,
with the ring as a uint16 field. Written with the standard library only, independently of
sgnlf's own writers, so the three folders check its readers.

    python3 convert_scans.py SRC_DIR OUT_DIR    # writes OUT_DIR/{pcdbin,pcd,ply}/
"""
import os
import shutil
import struct
import sys


def read_pcd_bin(path):
    data = open(path, "rb").read()
    if len(data) % 20:
        raise SystemExit(f"{path}: {len(data)} bytes is not a multiple of 20")
    return [struct.unpack_from("<5f", data, o) for o in range(0, len(data), 20)]


def write_pcd(path, pts):
    header = (
        "# .PCD v0.7 - Point Cloud Data file format\n"
        "VERSION 0.7\nFIELDS x y z intensity ring\nSIZE 4 4 4 4 2\nTYPE F F F F U\n"
        "COUNT 1 1 1 1 1\n"
        f"WIDTH {len(pts)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(pts)}\nDATA binary\n"
    )
    body = b"".join(struct.pack("<4fH", x, y, z, i, int(r)) for x, y, z, i, r in pts)
    with open(path, "wb") as f:
        f.write(header.encode("ascii") + body)


def write_ply(path, pts):
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment converted from nuScenes .pcd.bin\n"
        f"element vertex {len(pts)}\n"
        "property float x\nproperty float y\nproperty float z\nproperty float intensity\n"
        "property ushort ring\nend_header\n"
    )
    body = b"".join(struct.pack("<4fH", x, y, z, i, int(r)) for x, y, z, i, r in pts)
    with open(path, "wb") as f:
        f.write(header.encode("ascii") + body)


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    src, out = sys.argv[1:]
    names = sorted(n for n in os.listdir(src) if n.endswith(".pcd.bin"))
    if not names:
        raise SystemExit(f"{src}: no .pcd.bin files")
    for sub in ("pcdbin", "pcd", "ply"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    for n in names:
        stem = n[: -len(".pcd.bin")]
        pts = read_pcd_bin(os.path.join(src, n))
        shutil.copyfile(os.path.join(src, n), os.path.join(out, "pcdbin", n))
        write_pcd(os.path.join(out, "pcd", stem + ".pcd"), pts)
        write_ply(os.path.join(out, "ply", stem + ".ply"), pts)
    print(f"{len(names)} scans into {out}/pcdbin, {out}/pcd and {out}/ply")


if __name__ == "__main__":
    main()
