#!/usr/bin/env python3
"""Writes the seed corpus of the reader fuzzer, tests/data/fuzz_corpus/<reader>/: small valid files
and near-valid ones (one thing wrong each), one folder per reader, and the inputs that once broke
a reader (`regress_*`). Deterministic; rerun it after changing it and commit the files.

    python3 tools/fuzz/make_corpus.py [--out tests/data/fuzz_corpus]
"""
from __future__ import annotations

import argparse
import io
import json
import struct
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def npy_bytes(arr: np.ndarray, fortran: bool = False) -> bytes:
    buf = io.BytesIO()
    np.save(buf, np.asfortranarray(arr) if fortran else arr)
    return buf.getvalue()


def npy_with_header(header: str, payload: bytes, version: int = 1) -> bytes:
    """A .npy file with a hand-written header dict (padded to 64 bytes as numpy does)."""
    pre = 10 if version == 1 else 12
    body = header + " " * ((64 - (pre + len(header) + 1) % 64) % 64) + "\n"
    size = struct.pack("<H", len(body)) if version == 1 else struct.pack("<I", len(body))
    return b"\x93NUMPY" + bytes([version, 0]) + size + body.encode("latin-1") + payload


def png_chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png_bytes(rows, width: int, height: int, depth: int, color: int, palette: bytes = b"",
              interlace: int = 0, idat_split: int = 0) -> bytes:
    """A PNG from already packed scanlines (filter byte 0 prepended here)."""
    raw = b"".join(b"\x00" + r for r in rows)
    z = zlib.compress(raw, 9)
    out = b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, color, 0, 0, interlace))
    if palette:
        out += png_chunk(b"PLTE", palette)
    if idat_split:
        for k in range(0, len(z), idat_split):
            out += png_chunk(b"IDAT", z[k:k + idat_split])
    else:
        out += png_chunk(b"IDAT", z)
    return out + png_chunk(b"IEND", b"")


def room(h: int = 8, w: int = 10) -> np.ndarray:
    occ = np.zeros((h, w), dtype=bool)
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = True
    occ[h // 2, 2:w - 3] = True
    return occ


def write(folder: Path, name: str, data) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))


def points(out: Path) -> None:
    d = out / "points"
    write(d, "basic.txt", "0 0\n1 0\n0 1\n1 1\n0.5 0.25\n")
    write(d, "header_commas.csv", "x,y\n1.5,2\n-3e2,4\n+.5,1e-3\n")
    write(d, "comments_crlf.txt", "# motes\r\n1 2 # first\r\n\r\n3 4\r\n")
    write(d, "bom_tabs.txt", "\ufeff1\t2\n3\t4\n5\t6")
    write(d, "header_only.txt", "x y\n")
    write(d, "empty.txt", "")
    write(d, "one_point.txt", "7 7\n")
    write(d, "bad_number.txt", "1 2\n3 abc\n")
    write(d, "nan.txt", "1 2\n1 nan\n")
    write(d, "out_of_range.txt", "1e999 2\n")
    write(d, "three_fields.txt", "1 2 3\n")
    write(d, "empty_field.csv", "1,,2\n")
    write(d, "coincide.txt", "1 1\n2 2\n1 1\n")
    write(d, "hex.txt", "0x10 2\n")
    pts = np.array([[0.0, 0.0], [1.0, 0.5], [0.25, 2.0]])
    write(d, "f8.npy", npy_bytes(pts))
    write(d, "f4_fortran.npy", npy_bytes(pts.astype("<f4"), fortran=True))
    write(d, "i4_big_endian.npy", npy_bytes(np.array([[1, 2], [3, 5]], dtype=">i4")))
    write(d, "i8.npy", npy_bytes(np.array([[1, 2], [3, 5], [8, 13]], dtype="<i8")))
    write(d, "v2_header.npy", npy_with_header("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }",
                                              np.arange(4, dtype="<f8").tobytes(), version=2))
    write(d, "truncated.npy", npy_bytes(pts)[:-5])
    write(d, "shape_3d.npy", npy_bytes(np.zeros((2, 2, 2))))
    write(d, "bad_descr.npy", npy_with_header("{'descr': '<c16', 'fortran_order': False, 'shape': (1, 2), }", b"\0" * 32))
    write(d, "nan.npy", npy_bytes(np.array([[0.0, np.nan]])))


def distances(out: Path) -> None:
    d = out / "distances"
    write(d, "basic.txt", "0 1 1\n1 2 1\n0 2 1.4142135623730951\n2 3 1\n1 3 1.4142135623730951\n0 3 1\n")
    write(d, "ids.txt", "# serial numbers\n1001 2002 3\n2002 3003 4\n1001 3003 5\n")
    write(d, "header.csv", "i,j,d\n0,1,2.5\n1,2,2.5\n2,0,2.5\n")
    write(d, "both_directions.txt", "0 1 1\n1 0 1\n1 2 2\n2 1 2\n0 2 2.5\n2 0 2.5\n")
    write(d, "contradiction.txt", "0 1 1\n1 0 2\n")
    write(d, "zero.txt", "0 1 0\n")
    write(d, "self.txt", "1 1 2\n")
    write(d, "negative_id.txt", "-1 2 3\n")
    write(d, "huge_id.txt", "0 99999999999999999999 1\n")
    write(d, "two_fields.txt", "0 1\n")
    write(d, "inf.txt", "0 1 inf\n")
    write(d, "empty.txt", "")


def obstacles(out: Path) -> None:
    d = out / "obstacles"
    readme = {"area": {"box": [0, 0, 100, 100]},
              "obstacles": [{"type": "polygon", "vertices": [[10, 10], [30, 10], [30, 20], [18, 20], [18, 40], [10, 40]]},
                            {"type": "circle", "center": [60, 60], "radius": 8},
                            {"type": "point", "position": [80, 20]},
                            {"type": "segment", "vertices": [[40, 80], [55, 90]]},
                            {"type": "union", "parts": [{"type": "circle", "center": [85, 85], "radius": 3},
                                                        {"type": "point", "position": [90, 70]}]}]}
    write(d, "readme.json", json.dumps(readme, indent=1))
    write(d, "polygon_area.json", json.dumps({"area": {"polygon": [[0, 0], [8, 0], [10, 6], [4, 10], [-2, 5]]},
                                              "obstacles": [{"type": "circle", "center": [4, 4], "radius": 1.5, "name": "pillar"}]}))
    write(d, "closed_ring.json", json.dumps({"area": {"box": [0, 0, 16, 16]},
                                             "obstacles": [{"type": "polygon", "vertices": [[2, 2], [6, 2], [6, 6], [2, 2]]}]}))
    write(d, "empty_obstacles.json", '{"area": {"box": [-1, -1, 1, 1]}, "obstacles": []}')
    write(d, "duplicate_key.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circle", "center": [5, 5], "radius": 1, "radius": 2}]}')
    write(d, "out_of_range.json", '{"area": {"box": [0, 0, 1e999, 10]}, "obstacles": []}')
    write(d, "unknown_field.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circle", "center": [5, 5], "raduis": 1}]}')
    write(d, "trailing_comma.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [],}')
    write(d, "escapes.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 2], "name": "caf\\u00e9 \\ud83d\\ude00\\n"}]}')
    write(d, "escaped_key.json", '{"area": {"box": [0, 0, 10, 10]}, "obst\\u0061cles": []}')
    write(d, "invalid_utf8.json", b'{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 2], "name": "\xff\xfe"}]}')
    write(d, "nested.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [[[[[[[[]]]]]]]]}')
    write(d, "bad_polygon.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "polygon", "vertices": [[1, 1], [2, 2], [3, 3]]}]}')
    write(d, "self_intersecting.json", '{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "polygon", "vertices": [[1, 1], [5, 5], [5, 1], [1, 5]]}]}')
    write(d, "huge_coordinates.json", '{"area": {"box": [-1e300, -1e300, 1e300, 1e300]}, "obstacles": [{"type": "point", "position": [1e-300, 0]}]}')
    write(d, "not_an_object.json", "[1, 2, 3]")
    write(d, "empty.json", "")


def pgm_p5(occ: np.ndarray, maxval: int = 255) -> bytes:
    h, w = occ.shape
    if maxval < 256:
        px = np.where(occ, 0, 254 if maxval == 255 else maxval).astype(np.uint8).tobytes()
    else:
        px = np.where(occ, 0, maxval).astype(">u2").tobytes()
    return f"P5\n{w} {h}\n{maxval}\n".encode() + px


def pgm_p2(occ: np.ndarray) -> bytes:
    h, w = occ.shape
    rows = "\n".join(" ".join("0" if o else "254" for o in r) for r in occ)
    return f"P2\n# a plain pgm\n{w} {h}\n255\n{rows}\n".encode()


def maps(out: Path) -> None:
    occ = room()
    h, w = occ.shape
    # PGM
    d = out / "pgm"
    write(d, "p5_8bit.pgm", pgm_p5(occ))
    write(d, "p5_16bit.pgm", pgm_p5(occ, 65535))
    write(d, "p2.pgm", pgm_p2(occ))
    write(d, "p5_comments.pgm", b"P5 # magic\n# size next\n" + f"{w} {h}\n255\n".encode() + pgm_p5(occ).split(b"255\n", 1)[1])
    unknown = np.where(occ, 0, 254).astype(np.uint8)
    unknown[2:4, 2:4] = 205
    write(d, "unknown.pgm", f"P5\n{w} {h}\n255\n".encode() + unknown.tobytes())
    write(d, "truncated.pgm", pgm_p5(occ)[:-7])
    write(d, "bad_magic.pgm", b"P6\n2 2\n255\n" + b"\0" * 12)
    write(d, "zero_width.pgm", b"P5\n0 4\n255\n")
    write(d, "maxval_big.pgm", b"P2\n1 1\n70000\n5\n")
    # PNG (hand-encoded: every colour type and several bit depths)
    d = out / "png"
    grey = np.where(occ, 0, 254).astype(np.uint8)
    write(d, "grey8.png", png_bytes([r.tobytes() for r in grey], w, h, 8, 0))
    bits = np.packbits(~occ, axis=1)
    write(d, "grey1.png", png_bytes([r.tobytes() for r in bits], w, h, 1, 0))
    g16 = np.where(occ, 0, 65000).astype(">u2")
    write(d, "grey16.png", png_bytes([r.tobytes() for r in g16], w, h, 16, 0))
    rgb = np.stack([grey, grey, np.where(occ, 0, 200).astype(np.uint8)], -1)
    write(d, "rgb.png", png_bytes([r.tobytes() for r in rgb], w, h, 8, 2))
    rgba = np.concatenate([rgb, np.full((h, w, 1), 128, np.uint8)], -1)
    write(d, "rgba.png", png_bytes([r.tobytes() for r in rgba], w, h, 8, 6, idat_split=20))
    ga = np.stack([grey, np.full((h, w), 255, np.uint8)], -1)
    write(d, "grey_alpha.png", png_bytes([r.tobytes() for r in ga], w, h, 8, 4))
    idx = occ.astype(np.uint8)
    write(d, "palette.png", png_bytes([r.tobytes() for r in idx], w, h, 8, 3, palette=b"\xfe\xfe\xfe\x00\x00\x00"))
    write(d, "truncated.png", png_bytes([r.tobytes() for r in grey], w, h, 8, 0)[:-20])
    write(d, "bad_crc.png", png_bytes([r.tobytes() for r in grey], w, h, 8, 0)[:-1] + b"\x00")
    # MovingAI
    d = out / "movingai"
    body = "\n".join("".join("@" if o else "." for o in r) for r in occ)
    write(d, "room.map", f"type octile\nheight {h}\nwidth {w}\nmap\n{body}\n")
    write(d, "all_chars.map", "type octile\nheight 2\nwidth 4\nmap\n.G@O\nTSW.\n")
    write(d, "crlf.map", f"type octile\r\nheight {h}\r\nwidth {w}\r\nmap\r\n" + body.replace("\n", "\r\n") + "\r\n")
    write(d, "bad_char.map", "type octile\nheight 2\nwidth 2\nmap\n.x\n..\n")
    write(d, "short_row.map", "type octile\nheight 2\nwidth 3\nmap\n...\n..\n")
    write(d, "missing_rows.map", "type octile\nheight 3\nwidth 2\nmap\n..\n")
    write(d, "no_map_line.map", "type octile\nheight 2\nwidth 2\n")
    write(d, "extra_text.map", "type octile\nheight 1\nwidth 1\nmap\n.\nmore\n")
    # ROS map_server YAML (the images beside it are fixed; the fuzzer mutates the YAML)
    d = out / "ros_yaml"
    write(d, "room.pgm", pgm_p5(occ))
    write(d, "room.png", png_bytes([r.tobytes() for r in grey], w, h, 8, 0))
    rest = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"  # keys map_server requires
    write(d, "map.yaml", "image: room.pgm\nresolution: 0.05\norigin: [-1.0, -2.5, 0.0]\n" + rest)
    write(d, "png.yaml", "image: \"room.png\"  # quoted\nresolution: 1\norigin: [0, 0, 0]\nmode: trinary\n" + rest)
    write(d, "negate.yml", "image: room.pgm\nresolution: 2\norigin: [0.5, 0.5, 0]\nnegate: 1\nextra_key: ignored\n"
                           "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    write(d, "rotated.yaml", "image: room.pgm\nresolution: 1\norigin: [0, 0, 0.5]\n" + rest)
    write(d, "missing_image.yaml", "resolution: 1\norigin: [0, 0, 0]\n" + rest)
    write(d, "missing_origin.yaml", "image: room.pgm\nresolution: 1\n" + rest)
    write(d, "scale_mode.yaml", "image: room.pgm\nresolution: 1\norigin: [0, 0, 0]\nmode: scale\n" + rest)
    write(d, "bad_threshold.yaml", "image: room.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 1.5\n"
                                   "free_thresh: 0.196\n")
    write(d, "thresholds_crossed.yaml", "image: room.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                                        "occupied_thresh: 0.1\nfree_thresh: 0.9\n")
    write(d, "no_such_image.yaml", "image: nowhere.pgm\nresolution: 1\norigin: [0, 0, 0]\n" + rest)


def regressions(out: Path) -> None:
    """Inputs that broke a reader (issue 20's fuzzing), kept so that they stay fixed: each made the
    reader allocate what its header claimed before checking that the file holds it."""
    # 19 bytes that allocated 2.1 GB of grey levels before "truncated PGM data" (P5 and P2)
    write(out / "pgm", "regress_huge_header_p5.pgm", b"P5\n16383 16383\n255\n")
    write(out / "pgm", "regress_huge_header_p2.pgm", b"P2\n16383 16383\n255\n0 0\n")
    # a 68-byte PNG whose IHDR claims 16383 x 16383: 1 GB of RGBA before "cannot decode"
    ihdr = struct.pack(">IIBBBBB", 16383, 16383, 8, 0, 0, 0, 0)
    write(out / "png", "regress_huge_ihdr.png", b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
          + png_chunk(b"IDAT", zlib.compress(bytes(10))) + png_chunk(b"IEND", b""))
    # a MovingAI header of 16383 x 16383 and no rows: 268 MB before "expected 16383 map rows, the file has 0"
    write(out / "movingai", "regress_huge_header.map", "type octile\nheight 16383\nwidth 16383\nmap\n")
    # a .npy shape whose byte count overflows (n * 16 wraps to 16): "out of memory" (exit 1), not
    # an error naming the file
    write(out / "points", "regress_overflowing_shape.npy",
          npy_with_header("{'descr': '<f8', 'fortran_order': False, 'shape': (1152921504606846977, 2), }", bytes(16)))
    # subnormal coordinates (5.3e-315): the CLI's "points[0]: out of the exact range" named no file
    write(out / "points", "regress_out_of_exact_range.npy",
          npy_bytes(np.array([[0.0, 0.0], [5.299808824e-315, 5.29462817e-315], [5.289447516e-315, 0.0]])))
    # a circle of radius 2^31 around a 16-cell area: its contacts were sampled all round (3.6e10
    # points, about an hour)
    write(out / "obstacles", "regress_huge_circle.json",
          '{"area": {"polygon": [[0, 0], [8, 0], [10, 6], [4, 10], [-2, 5]]}, '
          '"obstacles": [{"type": "circle", "center": [4, 4], "radius": 2147483647, "name": "pillar"}]}')
    # a NUL byte ended the JSON parser's input; the key check then parsed an escaped key after it:
    # nlohmann's parse_error escaped (RuntimeError in Python, status 1 from the CLI)
    write(out / "obstacles", "regress_nul_then_escaped_key.json",
          b'"type"\x00{"area": {"box": [0, 0, 10, 10]}, "\x00bst\\u0061cles": []}')
    # distances whose exact tests overflow: the CLI's message said "distances: robot 0", not the file
    write(out / "distances", "regress_out_of_exact_range.txt", "0 1 1\n1 2 1\n0 2 1e308\n2 3 1\n1 3 1.4142135623730951\n0 3 1\n")
    # an area vertex at 1e308: the exact tests overflow while tracing; the message named no file
    write(out / "obstacles", "regress_area_out_of_exact_range.json",
          '{"area": {"polygon": [[0, 0], [8, 0], [10, 6], [4, 1e308], [-2, 5]]}, '
          '"obstacles": [{"type": "circle", "center": [4, 4], "radius": 1.5}]}')
    # an area wider than DBL_MAX (finite corners 1.8e308 apart): the grid's cell size was infinite and
    # the obstacle index wrote out of bounds (signal 11); found by the byte-mutation pass
    write(out / "obstacles", "regress_area_wider_than_dbl_max.json",
          '{"area": {"box": [-1e300, -1e300, 1.7976931348623157e308, 1e300]}, '
          '"obstacles": [{"type": "point", "position": [1e-300, 0]}]}')
    # not UTF-8: UnicodeDecodeError from python -m dvoronoi.mpi's point reader
    write(out / "points", "regress_latin1.txt", b"1 2\n3 4\xe9\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "tests" / "data" / "fuzz_corpus")
    args = ap.parse_args()
    for make in (points, distances, obstacles, maps, regressions):
        make(args.out)
    print(f"corpus written to {args.out}")


if __name__ == "__main__":
    main()
