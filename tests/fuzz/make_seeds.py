#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (tests/fuzz/corpus/<target>/): small valid inputs of each
kind the reader distinguishes, and slightly broken ones near each of its checks, so the fuzzer starts
next to every branch instead of having to find the formats' magic and field names itself.

    python3 tests/fuzz/make_seeds.py [build-fuzz/fuzz/fuzz_make_vdb_seeds]

The .vdb seeds need OpenVDB to write them: pass the seed tool built with FCC_FUZZ=ON to rewrite them too.
The files are deterministic except the .vdb seeds' UUIDs."""
import gzip
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def save(target, name, data):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def gz(data):
    return gzip.compress(data, mtime=0)


# --- NRRD ----------------------------------------------------------------------------------------------

def nrrd(fields, data=b"", magic="NRRD0004", newline="\n"):
    text = magic + newline + "".join(f + newline for f in fields) + newline
    return text.encode() + data


def nrrd_seeds():
    u8 = bytes(range(24))
    base = ["type: uchar", "dimension: 3", "sizes: 2 3 4", "encoding: raw"]
    save("nrrd", "attached_u8.nrrd", nrrd(base, u8))
    floats = struct.pack(">8f", *[0.5 * i for i in range(8)])
    save("nrrd", "attached_gzip_f32_big.nrrd",
         nrrd(["type: float", "dimension: 3", "sizes: 2 2 2", "endian: big", "encoding: gzip",
               "spacings: 1 2 nan", "space origin: (1,2,3)"], gz(floats)))
    shorts = struct.pack("<8h", *range(-4, 4))
    save("nrrd", "detached_self_byte_skip.nrrd",
         nrrd(["# the data file is this file; its last 16 bytes are the voxels", "type: short", "dimension: 3",
               "sizes: 2 2 2", "endian: little", "encoding: raw", "data file: volume.nrrd", "byte skip: -1",
               "space: left-posterior-superior", "space directions: (1,0,0) (0,-2,0) (0,0,0.5)"], shorts))
    lines = ["type: int8", "dimension: 3", "sizes: 2 2 1", "encoding: raw", "data file: ./volume.nrrd",
             "line skip: 8"]
    save("nrrd", "detached_line_skip.nrrd", nrrd(lines, b"\x01\x02\xfd\xfe"))
    doubles = struct.pack("<2d", 1.0, -2.0)
    save("nrrd", "crlf_comments_double.nrrd",
         nrrd(["# comment", "Type: Double", "dimension: 3", "sizes: 1 1 2", "endian: little", "encoding: raw",
               "kinds: domain domain domain", "my key:=my value", "space directions: none (0,1,0) (0,0,3)"],
              doubles, newline="\r\n"))
    save("nrrd", "u16_gz_spelling.nrrd",
         nrrd(["type: unsigned  short int", "dimension: 3", "sizes: 2 1 1", "endian: little", "encoding: gz",
               "byte skip: 2"], gz(b"\xff\xff\x01\x00\x02\x00")))
    # Slightly broken, each next to one check.
    save("nrrd", "bad_short_data.nrrd", nrrd(base, u8[:20]))
    save("nrrd", "bad_truncated_gzip.nrrd",
         nrrd(["type: uchar", "dimension: 3", "sizes: 4 4 4", "encoding: gzip"], gz(bytes(64))[:-9]))
    save("nrrd", "bad_not_aligned.nrrd",
         nrrd(["type: uchar", "dimension: 3", "sizes: 1 1 1", "encoding: raw",
               "space directions: (1,1,0) (0,1,0) (0,0,1)"], b"\x07"))
    save("nrrd", "bad_dimension_4.nrrd", nrrd(["type: uchar", "dimension: 4", "sizes: 1 1 1 1", "encoding: raw"], b"\0"))
    save("nrrd", "bad_data_file_list.nrrd",
         nrrd(["type: uchar", "dimension: 3", "sizes: 1 1 2", "encoding: raw", "data file: LIST"]) + b"a.raw\nb.raw\n")
    save("nrrd", "bad_huge_sizes.nrrd",
         nrrd(["type: double", "dimension: 3", "sizes: 2147483647 2147483647 8", "endian: big", "encoding: raw"], b"\0" * 8))


# --- NIfTI-1 -------------------------------------------------------------------------------------------

def nifti(dims, datatype, bitpix, data, big=False, vox_offset=352.0, slope=0.0, inter=0.0, qform=0, sform=0,
          magic=b"n+1\0", sizeof_hdr=348, extension=b"\0\0\0\0"):
    e = ">" if big else "<"
    h = bytearray(348)
    struct.pack_into(e + "i", h, 0, sizeof_hdr)
    struct.pack_into(e + "8h", h, 40, *(list(dims) + [1] * (8 - len(dims))))
    struct.pack_into(e + "hh", h, 70, datatype, bitpix)
    struct.pack_into(e + "8f", h, 76, 1.0, 0.5, 2.0, -1.5, 1.0, 1.0, 1.0, 1.0)
    struct.pack_into(e + "fff", h, 108, vox_offset, slope, inter)
    struct.pack_into(e + "hh", h, 252, qform, sform)
    struct.pack_into(e + "3f", h, 268, 10.0, 20.0, 30.0)
    struct.pack_into(e + "12f", h, 280, 1, 0, 0, -5, 0, 1, 0, -6, 0, 0, 1, -7)
    h[344:348] = magic
    return bytes(h) + extension + data


def nifti_seeds():
    save("nifti", "le_u8.nii", nifti([3, 2, 3, 4], 2, 8, bytes(range(24))))
    save("nifti", "be_i16_scaled_qform.nii",
         nifti([3, 2, 2, 1], 4, 16, struct.pack(">4h", -2, -1, 1, 2), big=True, slope=2.0, inter=1.0, qform=1))
    save("nifti", "f32_sform.nii.gz", gz(nifti([3, 1, 2, 2], 16, 32, struct.pack("<4f", 0.5, 1, 2, 4), sform=2)))
    ext = struct.pack("<4B", 1, 0, 0, 0) + struct.pack("<ii", 16, 4) + b"abcdefgh"
    save("nifti", "f64_dim4_extension.nii",
         nifti([4, 1, 1, 2, 1], 64, 64, struct.pack("<2d", 1.5, -2.5), vox_offset=368.0, extension=ext))
    save("nifti", "u16_i8_u32.nii", nifti([3, 2, 1, 1], 512, 16, struct.pack("<2H", 1, 65535)))
    save("nifti", "be_u32_gz.nii.gz", gz(nifti([3, 1, 1, 2], 768, 32, struct.pack(">2I", 1, 2 ** 31), big=True)))
    save("nifti", "i8.nii", nifti([3, 1, 1, 3], 256, 8, b"\x80\x00\x7f"))
    save("nifti", "i32_nan_slope.nii", nifti([3, 1, 1, 1], 8, 32, struct.pack("<i", -7), slope=float("nan")))
    # Slightly broken.
    save("nifti", "bad_two_file_magic.nii", nifti([3, 1, 1, 1], 2, 8, b"\0", magic=b"ni1\0"))
    save("nifti", "bad_nifti2.nii", nifti([3, 1, 1, 1], 2, 8, b"\0", sizeof_hdr=540))
    save("nifti", "bad_short_data.nii", nifti([3, 4, 4, 4], 2, 8, bytes(60)))
    save("nifti", "bad_rgb24.nii", nifti([3, 1, 1, 1], 128, 24, b"\0\0\0"))
    save("nifti", "bad_dim0_2.nii", nifti([2, 4, 4], 2, 8, bytes(16)))
    save("nifti", "bad_vox_offset.nii", nifti([3, 1, 1, 1], 2, 8, b"\0", vox_offset=100.0))
    save("nifti", "bad_truncated_gzip.nii.gz", gz(nifti([3, 2, 2, 2], 2, 8, bytes(8)))[:-6])
    save("nifti", "bad_truncated_header.nii", nifti([3, 1, 1, 1], 2, 8, b"")[:200])


# --- Cartesian range cache ----------------------------------------------------------------------------

# The key fuzz_cartesian_range_cache.cpp reads under (the same text there).
RANGE_KEY = (b"FCCRNG1\n/data/volume.vdb\n123456 1700000000.123456789\ndensity\n"
             b"bricks 16, blocks from -2 of 20 points, leaf slabs 2")
INT_MIN, INT_MAX = -2**31, 2**31 - 1


def fnv1a(data):
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) % 2**64
    return h


def range_cache(box_lo, box_hi, reseal, records, key=RANGE_KEY, count=None, bom=0x01020304, checksum=None):
    """The layout bytes (box, flags) and a .ccranges file: magic, byte-order mark, key, count, records
    (x, y, z, lo, hi), FNV-1a of everything before it (io/CartesianRangeCache.cpp)."""
    body = b"FCCRNG1\n" + struct.pack("<II", bom, len(key)) + key
    body += struct.pack("<Q", len(records) if count is None else count)
    for (x, y, z, lo, hi) in records:
        body += struct.pack("<3i2f", x, y, z, lo, hi)
    body += struct.pack("<Q", fnv1a(body) if checksum is None else checksum)
    return struct.pack("<6iB", *box_lo, *box_hi, 1 if reseal else 0) + body


def cartesian_range_cache_seeds():
    t = "cartesian_range_cache"
    three = [(-2, -1, 0, -1.5, 0.5), (3, -1, 0, 0.0, 0.0), (0, 2, 1, -3.0, float("inf"))]
    box = ((-2, -1, 0), (3, 2, 1))
    save(t, "three_bricks.ccranges", range_cache(*box, False, three))
    save(t, "three_bricks_resealed.ccranges", range_cache(*box, True, three))
    # CartesianBrickStore's box of a grid without data: lo > hi, and only an empty list is valid.
    save(t, "empty_box.ccranges", range_cache((INT_MAX,) * 3, (INT_MIN,) * 3, True, []))
    save(t, "one_brick_box.ccranges", range_cache((5, 5, 5), (5, 5, 5), True, [(5, 5, 5, 1.0, 2.0)]))
    # A sparse grid's legitimate box can span 2^28 bricks an axis (leaves near -2^31 and 2^31).
    far = 2**27
    save(t, "huge_box.ccranges", range_cache((-far,) * 3, (far - 1,) * 3, True,
                                             [(-far, -far, -far, 0.0, 1.0), (far - 1, far - 1, far - 1, 2.0, 3.0)]))
    save(t, "widest_box.ccranges", range_cache((INT_MIN,) * 3, (INT_MAX,) * 3, True, [(0, 0, 0, 0.0, 1.0)]))
    # Slightly broken, each next to one check.
    save(t, "bad_checksum.ccranges", range_cache(*box, False, three, checksum=12345))
    save(t, "bad_truncated.ccranges", range_cache(*box, False, three)[:-11])
    save(t, "bad_other_key.ccranges", range_cache(*box, True, three, key=RANGE_KEY.replace(b"density", b"densitz")))
    save(t, "bad_key_length.ccranges", range_cache(*box, True, three, key=RANGE_KEY[:-1]))
    save(t, "bad_byte_order.ccranges", range_cache(*box, True, three, bom=0x04030201))
    save(t, "bad_count_huge.ccranges", range_cache(*box, True, three, count=2**62 + 3))
    # 20 (2^62 + 3) is 60 modulo 2^64: the size of three records, once the count's product wraps.
    save(t, "bad_count_wraps.ccranges", range_cache((INT_MIN,) * 3, (INT_MAX,) * 3, True, three, count=2**62 + 3))
    save(t, "bad_outside_box.ccranges", range_cache((-2, -1, 0), (3, 2, 0), True, three))
    save(t, "bad_out_of_order.ccranges", range_cache(*box, True, [three[1], three[0], three[2]]))
    save(t, "bad_repeated_brick.ccranges", range_cache(*box, True, [three[0], three[0]]))
    save(t, "bad_lo_above_hi.ccranges", range_cache(*box, True, [(0, 0, 0, 2.0, 1.0)]))
    save(t, "bad_nan_range.ccranges", range_cache(*box, True, [(0, 0, 0, float("nan"), 1.0)]))
    save(t, "bad_empty_file.ccranges", struct.pack("<6iB", *box[0], *box[1], 1))


# --- raw -----------------------------------------------------------------------------------------------
# fuzz_raw reads its layout from the first 9 bytes: dims (3 x uint16 LE), type (0 u8, 1 i8, 2 u16, 3 i16,
# 4 u32, 5 i32, 6 f32, 7 f64), flags (1 big-endian, 2 a .gz name, 4 bad spacing, 16 a 2^40 header), header
# bytes; the rest is the file.

def raw(dims, type_index, flags, header, data):
    return struct.pack("<3HBBB", *dims, type_index, flags, header) + data


def raw_seeds():
    save("raw", "u8.raw", raw((2, 3, 4), 0, 0, 0, bytes(range(24))))
    save("raw", "i16_big_header.raw", raw((2, 2, 2), 3, 1, 5, b"HEAD!" + struct.pack(">8h", *range(8))))
    save("raw", "f64_gz_name.raw", raw((1, 1, 2), 7, 2, 0, gz(struct.pack("<2d", 0.25, -8.0))))
    save("raw", "u8_gzip_by_magic.raw", raw((4, 4, 4), 0, 0, 0, gz(bytes(range(64)))))
    save("raw", "u16_starts_like_gzip.raw", raw((2, 1, 1), 2, 0, 0, b"\x1f\x8b\x08\x00"))
    save("raw", "f32_i32_u32.raw", raw((1, 2, 1), 6, 0, 0, struct.pack("<2f", 1.0, float("inf"))))
    save("raw", "bad_size.raw", raw((3, 3, 3), 0, 0, 0, bytes(26)))
    save("raw", "bad_huge_dims.raw", raw((65535, 65535, 65535), 7, 0, 0, bytes(8)))
    save("raw", "bad_zero_dim.raw", raw((0, 3, 3), 0, 0, 0, bytes(9)))
    save("raw", "bad_gzip_trailing.raw", raw((2, 2, 2), 0, 0, 0, gz(bytes(9))))
    save("raw", "bad_corrupt_gzip.raw", raw((2, 2, 2), 0, 2, 0, gz(bytes(8))[:12] + b"\xff" * 8))
    save("raw", "bad_spacing.raw", raw((1, 1, 1), 0, 4, 0, b"\0"))
    save("raw", "bad_header_beyond.raw", raw((1, 1, 1), 0, 16, 0, b"\0"))


# --- transfer functions --------------------------------------------------------------------------------
# The first byte: 1 for a .json file, 0 for the text format.

def transfer_function_seeds():
    json = lambda text: b"\x01" + text.encode()
    txt = lambda text: b"\x00" + text.encode()
    save("transfer_function", "paraview.json", json(
        '[{"ColorSpace": "Diverging", "Name": "Two Tone", "NanColor": [1, 1, 0],\n'
        ' "Points": [-1, 0, 0.5, 0, 0.5, 0.25, 0.25, 0.6, 2, 0.75, 0.5, 1],\n'
        ' "RGBPoints": [-1, 0, 0, 1, 0.5, 1, 1, 1, 2, 1, 0, 0]},\n'
        ' {"Name": "No Opacity", "RGBPoints": [10, 0, 0, 0, 20, 1, 1, 1]}]\n'))
    save("transfer_function", "one_map.json", json('{"Name": "x", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}'))
    save("transfer_function", "step.json", json('[{"RGBPoints": [0, 0, 0, 0, 0, 1, 1, 1], "Points": [0, 0, 0.5, 0, 0, 1, 0.5, 0]}]'))
    save("transfer_function", "bad_midpoint.json", json('[{"RGBPoints": [0, 0, 0, 0], "Points": [0, 1, 1.5, 0]}]'))
    save("transfer_function", "bad_space.json", json('[{"ColorSpace": "CMYK", "RGBPoints": [0, 0, 0, 0]}]'))
    save("transfer_function", "bad_odd.json", json('[{"RGBPoints": [0, 0, 0, 0, 1, 1, 1]}]'))
    save("transfer_function", "bad_cut.json", json('[{"Name": "m", "RGBPoints": [0, 0, 0'))
    save("transfer_function", "ramp.txt", txt("# value r g b alpha\n\n0 0 0 0 0\n100 1 0.5 0 0.2 # warm\n100 1 1 1 0\n250 1 1 1 1\n"))
    save("transfer_function", "bad_order.txt", txt("1 0 0 0 0\n0 1 1 1 1\n"))
    save("transfer_function", "bad_fields.txt", txt("0 0 0 0\n"))


def main():
    nrrd_seeds()
    transfer_function_seeds()
    nifti_seeds()
    raw_seeds()
    cartesian_range_cache_seeds()
    if len(sys.argv) > 1:
        folder = os.path.join(HERE, "corpus", "vdb_leaf_reader")
        os.makedirs(folder, exist_ok=True)
        subprocess.run([sys.argv[1], folder], check=True)


if __name__ == "__main__":
    main()
