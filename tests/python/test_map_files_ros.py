"""Map files read as ROS map_server reads them: PNG grey levels as stored (no gamma), alpha averaged in
with the colour (trinary mode), 16-bit samples at full precision; the checks of the thresholds,
resolution and origin for bare images; the YAML forms map_server files are written in; plain-PGM
errors that name the line and column. The expected occupancy is map_server's rule written out here,
independently of the reader; the PNG files are built here with zlib and struct."""
from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import _core

needs_png = pytest.mark.skipif(not _core._has_png, reason="dvoronoi built without libpng")


# -- PNG files, written by hand ---------------------------------------------------------------------

def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_png(path, samples, colour, depth=8, palette=None, trns=None, extra=()):
    """samples: (H, W) or (H, W, channels) unsigned integers as stored; colour: PNG colour type
    (0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA); extra: (kind, data) chunks before IDAT."""
    a = np.asarray(samples)
    if a.ndim == 2:
        a = a[:, :, None]
    h, w, _ = a.shape
    rows = []
    for row in a:
        flat = row.reshape(-1)
        if depth == 16:
            raw = flat.astype(">u2").tobytes()
        elif depth == 8:
            raw = flat.astype(np.uint8).tobytes()
        else:  # 1, 2, 4 bits: packed from the high bits of each byte
            per = 8 // depth
            padded = np.concatenate([flat, np.zeros((-len(flat)) % per, flat.dtype)]).astype(np.uint16)
            packed = np.zeros(len(padded) // per, np.uint16)
            for k in range(per):
                packed |= padded[k::per] << (8 - depth * (k + 1))
            raw = packed.astype(np.uint8).tobytes()
        rows.append(b"\0" + raw)
    data = b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, 0))
    for kind, payload in extra:
        data += _chunk(kind, payload)
    if palette is not None:
        data += _chunk(b"PLTE", np.asarray(palette, np.uint8).reshape(-1).tobytes())
    if trns is not None:
        data += _chunk(b"tRNS", trns)
    data += _chunk(b"IDAT", zlib.compress(b"".join(rows))) + _chunk(b"IEND", b"")
    Path(path).write_bytes(data)
    return data


def gama(gamma):
    return (b"gAMA", struct.pack(">I", int(round(gamma * 100000))))


SRGB = (b"sRGB", b"\0")
ICCP = (b"iCCP", b"fake\0\0" + zlib.compress(b"not an ICC profile"))
CHRM = (b"cHRM", struct.pack(">8I", 31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000))


def map_server(channels, top=255, negate=False, occupied_thresh=0.65, free_thresh=0.196):
    """map_server's trinary rule (ROS1 image_loader.cpp, nav2 map_io.cpp): the mean of all the
    channels, alpha included, as stored; 1 occupied, 0 free, -1 unknown."""
    avg = np.asarray(channels, dtype=float).mean(axis=-1) * (255.0 / top)
    occ = avg / 255.0 if negate else (255.0 - avg) / 255.0
    return np.where(occ > occupied_thresh, 1, np.where(occ < free_thresh, 0, -1))


def check_load(path, want):
    """The loader against the rule: occupancy with unknown="free", and the unknown count."""
    g = dv.OccupancyGrid.load(path, unknown="free")
    assert g.occupied.shape == want.shape
    np.testing.assert_array_equal(g.occupied.astype(int), (want == 1).astype(int))
    assert g.unknown_pixels == int((want == -1).sum())
    assert np.array_equal(dv.OccupancyGrid.load(path).occupied, want != 0)


# -- PNG grey levels ------------------------------------------------------------------------------------

@needs_png
@pytest.mark.parametrize("extra", [(), (gama(1.0),), (gama(0.45455),), (gama(2.2), CHRM), (SRGB,), (ICCP,)],
                         ids=["plain", "gAMA 1.0", "gAMA 0.45455", "gAMA 2.2 + cHRM", "sRGB", "iCCP"])
def test_8_bit_grey_is_read_as_stored_whatever_the_colour_chunks_say(tmp_path, extra):
    levels = np.arange(256).reshape(16, 16)
    write_png(tmp_path / "g.png", levels, colour=0, extra=extra)
    want = map_server(levels[..., None])
    assert (want == 1).sum() > 0 and (want == 0).sum() > 0 and (want == -1).sum() > 0
    check_load(tmp_path / "g.png", want)
    # the same as the PGM of the same levels
    (tmp_path / "g.pgm").write_bytes(b"P5\n16 16\n255\n" + levels.astype(np.uint8).tobytes())
    assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "g.pgm").occupied, dv.OccupancyGrid.load(tmp_path / "g.png").occupied)


@needs_png
@pytest.mark.parametrize("extra", [(), (gama(1.0),), (SRGB,)], ids=["plain", "gAMA 1.0", "sRGB"])
def test_16_bit_grey_keeps_its_precision(tmp_path, extra):
    # map_server's unknown grey 205 (205 * 257 in 16 bits) must stay unknown; the simplified libpng API
    # took 16-bit samples for linear light and changed them. Samples near the thresholds: v = s / 65535
    # (22938 and 52691 would fall the other way if only their high byte were kept).
    s = np.array([[0, 60 * 257, 205 * 257, 254 * 257, 65535, 22937, 22938, 52690, 52691, 100 * 257 + 99]])
    write_png(tmp_path / "w.png", s, colour=0, depth=16, extra=extra)
    want = map_server(s[..., None], top=65535)
    np.testing.assert_array_equal(want, [[1, 1, -1, 0, 0, 1, -1, -1, 0, -1]])
    check_load(tmp_path / "w.png", want)
    # and the 16-bit PGM of the same samples reads the same
    (tmp_path / "w.pgm").write_bytes(b"P5\n10 1\n65535\n" + s.astype(">u2").tobytes())
    assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "w.pgm").occupied, dv.OccupancyGrid.load(tmp_path / "w.png").occupied)


@needs_png
@pytest.mark.parametrize("depth", [1, 2, 4])
def test_grey_below_8_bits_is_scaled_to_the_full_range(tmp_path, depth):
    top = 2 ** depth - 1
    s = np.arange(top + 1).reshape(1, -1).repeat(3, axis=0)
    write_png(tmp_path / "b.png", s, colour=0, depth=depth)
    check_load(tmp_path / "b.png", map_server(s[..., None], top=top))


@needs_png
def test_rgb_is_the_mean_of_the_channels(tmp_path):
    rng = np.random.default_rng(3)
    rgb = rng.integers(0, 256, size=(20, 30, 3))
    write_png(tmp_path / "c.png", rgb, colour=2, extra=(gama(0.45455),))
    check_load(tmp_path / "c.png", map_server(rgb))
    rgb16 = rng.integers(0, 65536, size=(7, 9, 3))
    write_png(tmp_path / "c16.png", rgb16, colour=2, depth=16)
    check_load(tmp_path / "c16.png", map_server(rgb16, top=65535))


# -- alpha ------------------------------------------------------------------------------------------

@needs_png
def test_rgba_averages_alpha_in_with_the_colour_as_map_server_does_in_trinary_mode(tmp_path):
    # the adversarial review's case: opaque black, unknown grey and free white; then the same greys
    # half and fully transparent
    grey = np.array([0, 205, 254])
    rows = [np.dstack([grey, grey, grey, np.full(3, a)])[0] for a in (255, 128, 0)]
    rgba = np.stack(rows)
    want = map_server(rgba)
    assert want[0].tolist() == [1, 0, 0]            # (3 * 205 + 255) / 4 = 217.5: free, not unknown
    assert want[2].tolist() == [1, -1, -1]          # transparent pixels read darker: white is unknown
    write_png(tmp_path / "a.png", rgba, colour=6)
    check_load(tmp_path / "a.png", want)
    rng = np.random.default_rng(4)
    rgba = rng.integers(0, 256, size=(25, 17, 4))
    write_png(tmp_path / "r.png", rgba, colour=6, extra=(gama(1.0),))
    check_load(tmp_path / "r.png", map_server(rgba))
    rgba16 = rng.integers(0, 65536, size=(6, 5, 4))
    write_png(tmp_path / "r16.png", rgba16, colour=6, depth=16)
    check_load(tmp_path / "r16.png", map_server(rgba16, top=65535))


@needs_png
def test_grey_alpha_counts_as_rgb_grey_plus_alpha(tmp_path):
    # map_server sees a grey+alpha PNG as RGBA with R = G = B = grey: v = (3 grey + alpha) / 4
    rng = np.random.default_rng(5)
    ga = rng.integers(0, 256, size=(30, 20, 2))
    ga[0, :4] = [[205, 255], [0, 255], [254, 0], [254, 255]]
    as_map_server = np.concatenate([ga[..., :1], ga[..., :1], ga[..., :1], ga[..., 1:]], axis=-1)
    want = map_server(as_map_server)
    assert want[0, :4].tolist() == [0, 1, -1, 0]     # black: (0 + 255) / 4, occupied
    assert map_server(ga)[0, 1] == -1                # where the plain mean of two channels differs
    write_png(tmp_path / "ga.png", ga, colour=4)
    check_load(tmp_path / "ga.png", want)
    write_png(tmp_path / "ga16.png", ga * 257, colour=4, depth=16)
    check_load(tmp_path / "ga16.png", want)


@needs_png
def test_palette_colours_and_their_trns_alpha(tmp_path):
    palette = np.array([[0, 0, 0], [205, 205, 205], [254, 254, 254], [255, 0, 0], [254, 254, 254]])
    alpha = np.array([255, 255, 255, 255, 0])      # the last entry: transparent white
    idx = np.array([[0, 1, 2, 3, 4], [4, 3, 2, 1, 0]])
    write_png(tmp_path / "p.png", idx, colour=3, palette=palette)
    check_load(tmp_path / "p.png", map_server(palette[idx]))
    write_png(tmp_path / "pt.png", idx, colour=3, palette=palette, trns=alpha.astype(np.uint8).tobytes())
    rgba = np.concatenate([palette, alpha[:, None]], axis=1)[idx]
    want = map_server(rgba)
    assert want[0].tolist() == [1, 0, 0, -1, -1]    # red (255 + 0 + 0 + 255) / 4 and (3 * 254 + 0) / 4
    check_load(tmp_path / "pt.png", want)


@needs_png
def test_a_grey_colour_key_is_not_a_channel(tmp_path):
    # tRNS on a grey image is one transparent grey: ROS1's loader (SDL_image) makes it a colour key,
    # not an alpha channel, so the pixels read as their grey
    levels = np.arange(0, 256, 5).reshape(1, -1)
    write_png(tmp_path / "k.png", levels, colour=0, trns=struct.pack(">H", 205))
    check_load(tmp_path / "k.png", map_server(levels[..., None]))


# -- broken PNG files -------------------------------------------------------------------------------

@needs_png
def test_truncated_or_corrupt_png_is_a_valueerror_naming_the_file(tmp_path):
    rng = np.random.default_rng(6)
    good = write_png(tmp_path / "good.png", rng.integers(0, 256, size=(40, 40, 4)), colour=6)
    bad = tmp_path / "bad.png"
    idat = good.index(b"IDAT")
    cases = [good[:n] for n in (0, 7, 8, 20, 33, 40, idat, idat + 30, len(good) // 2, len(good) - 20)]
    for k in range(40):  # flipped bytes in the compressed data, CRC fixed so that zlib sees them
        data = bytearray(good)
        pos = int(rng.integers(idat + 6, idat + 4 + struct.unpack(">I", good[idat - 4:idat])[0]))
        data[pos] ^= int(rng.integers(1, 256))
        n = struct.unpack(">I", data[idat - 4:idat])[0]
        data[idat + 4 + n:idat + 8 + n] = struct.pack(">I", zlib.crc32(bytes(data[idat:idat + 4 + n])) & 0xFFFFFFFF)
        cases.append(bytes(data))
    cases.append(good[:idat + 8] + b"\xff" * 10 + good[idat + 18:])   # CRC now wrong
    refused = 0
    for data in cases:
        bad.write_bytes(data)
        try:
            dv.OccupancyGrid.load(bad)
        except ValueError as e:
            assert str(e).startswith(str(bad) + ": "), str(e)
            refused += 1
    assert refused >= 11   # every truncation and the bad CRC at least
    # through a YAML the message names both files
    (tmp_path / "m.yaml").write_text("image: bad.png\nresolution: 1\norigin: [0, 0, 0]\n" + REST)
    bad.write_bytes(good[:len(good) // 2])
    with pytest.raises(ValueError, match=r"m\.yaml: image: .*bad\.png: cannot decode PNG image"):
        dv.OccupancyGrid.load(tmp_path / "m.yaml")


# -- the options' checks ----------------------------------------------------------------------------

@pytest.mark.parametrize("kw, message", [
    (dict(occupied_thresh=2.0), r"occupied_thresh: expected a number in \[0, 1\], got 2"),
    (dict(occupied_thresh=float("nan")), r"occupied_thresh: expected a number in \[0, 1\], got nan"),
    (dict(free_thresh=float("nan")), r"free_thresh: expected a number in \[0, 1\], got nan"),
    (dict(free_thresh=-1.0), r"free_thresh: expected a number in \[0, 1\], got -1"),
    (dict(occupied_thresh=0.1, free_thresh=0.9), r"free_thresh is larger than occupied_thresh \(0\.9 > 0\.1\)"),
])
def test_bad_thresholds_for_bare_images_are_refused_naming_the_parameter(tmp_path, kw, message):
    img = np.full((6, 6), 254, np.uint8)
    img[:, 2] = 0
    (tmp_path / "m.pgm").write_bytes(b"P5\n6 6\n255\n" + img.tobytes())
    with pytest.raises(ValueError, match=r"m\.pgm: " + message):
        dv.OccupancyGrid.load(tmp_path / "m.pgm", unknown="free", **kw)
    if list(kw) == ["occupied_thresh"]:  # the one threshold grid_voronoi passes on
        with pytest.raises(ValueError, match=message):
            dv.grid_voronoi(tmp_path / "m.pgm", **kw)
    (tmp_path / "m.map").write_text("type octile\nheight 1\nwidth 2\nmap\n.@\n")
    with pytest.raises(ValueError, match=r"m\.map: a MovingAI map has no grey levels"):  # thresholds do nothing there
        dv.OccupancyGrid.load(tmp_path / "m.map", **kw)


def test_thresholds_at_the_ends_of_the_range_are_allowed(tmp_path):
    img = np.array([[0, 128, 255]], np.uint8)
    (tmp_path / "m.pgm").write_bytes(b"P5\n3 1\n255\n" + img.tobytes())
    g = dv.OccupancyGrid.load(tmp_path / "m.pgm", occupied_thresh=1.0, free_thresh=0.0, unknown="free")
    assert not g.occupied.any() and g.unknown_pixels == 3   # p = 1 is not above 1, p = 0 not below 0


def test_yaml_thresholds_name_the_line(tmp_path):
    (tmp_path / "m.pgm").write_bytes(b"P5\n2 1\n255\n\x00\xfe")
    (tmp_path / "a.yaml").write_text("image: m.pgm\nresolution: 1\nfree_thresh: .nan\n")
    with pytest.raises(ValueError, match=r"a\.yaml:3: free_thresh: expected a finite decimal number, got '\.nan'"):
        dv.OccupancyGrid.load(tmp_path / "a.yaml")
    (tmp_path / "b.yaml").write_text("image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n\noccupied_thresh: -0.5\n"
                                     "free_thresh: 0\n")
    with pytest.raises(ValueError, match=r"b\.yaml:6: occupied_thresh: expected a number in \[0, 1\], got -0\.5"):
        dv.OccupancyGrid.load(tmp_path / "b.yaml")


# -- YAML forms -------------------------------------------------------------------------------------

BASE = "image: m.pgm\nresolution: 0.05\norigin: [1.5, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
REST = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"  # keys map_server requires besides image, resolution, origin


@pytest.mark.parametrize("text", [
    BASE.replace("negate: 0", "negate: false"),
    BASE.replace("negate: 0", "negate: False"),
    BASE.replace("negate: 0", "negate: no"),
    BASE.replace("origin: [1.5, -2.0, 0.0]", "origin:\n  - 1.5\n  - -2.0\n  - 0.0"),
    BASE.replace("origin: [1.5, -2.0, 0.0]", "origin:\n- 1.5   # x\n- -2.0\n- 0"),
    "---\n" + BASE,
    "---\n" + BASE + "...\n",
    "\ufeff" + BASE,
    "{image: m.pgm, resolution: 0.05, origin: [1.5, -2.0, 0], negate: 0, occupied_thresh: 0.65, free_thresh: 0.196}\n",
    "{image: 'm.pgm', resolution: 0.05,  # a comment\n origin: [1.5, -2.0, 0], negate: 0,\n occupied_thresh: 0.65, free_thresh: 0.196}\n",
    "image: \"m.pgm\"   # quoted\nresolution: '0.05'\norigin: [1.5, -2.0, 0.0]\nmode: trinary\n" + REST,
    BASE.replace("resolution: 0.05", "resolution: 5E-2"),
    BASE + "extra:\n  nested: {a: 1}\n  list:\n    - x\n",
], ids=["negate false", "negate False", "negate no", "block origin", "block origin, same indent", "---", "--- ...",
        "BOM", "flow mapping", "flow mapping over lines", "quotes and comments", "exponent", "nested ignored key"])
def test_map_server_yaml_forms_are_read(tmp_path, text):
    img = np.array([[0, 205, 254, 254]], np.uint8)
    (tmp_path / "m.pgm").write_bytes(b"P5\n4 1\n255\n" + img.tobytes())
    (tmp_path / "m.yaml").write_bytes(text.encode("utf-8"))
    g = dv.OccupancyGrid.load(tmp_path / "m.yaml", unknown="free")
    assert g.resolution == 0.05 and g.origin == (1.5, -2.0)
    assert g.occupied.tolist() == [[True, False, False, False]] and g.unknown_pixels == 1


@pytest.mark.parametrize("value", ["true", "True", "TRUE", "yes", "Yes", "on", "1", "2", "-1"])  # nav2: an int, nonzero true
def test_negate_as_a_boolean(tmp_path, value):
    img = np.array([[0, 205, 254]], np.uint8)
    (tmp_path / "m.pgm").write_bytes(b"P5\n3 1\n255\n" + img.tobytes())
    (tmp_path / "m.yaml").write_text(BASE.replace("negate: 0", "negate: " + value))
    g = dv.OccupancyGrid.load(tmp_path / "m.yaml", unknown="free")
    want = map_server(img[..., None], negate=True)
    assert g.occupied.tolist() == (want == 1).tolist() and want.tolist() == [[0, 1, 1]]


@pytest.mark.parametrize("text, message", [
    ("image: m.pgm\nresolution: &r 0.05\n", r"m\.yaml:2: resolution: YAML anchors, aliases, tags"),
    ("{image: m.pgm, resolution: 0.05\n", r"m\.yaml:1: the flow mapping '\{' is not closed"),
    ("image: m.pgm\nresolution: 0.05\nnegate: maybe\n", r"m\.yaml:3: negate: expected an integer \(0: false, others: true\), true or false, got 'maybe'"),
    ("image: m.pgm\nresolution: 0.05\norigin:\n  - 0\n  - oops\n", r"m\.yaml:5: origin: expected a finite decimal number, got 'oops'"),
    ("image: m.pgm\nresolution: 0x1p-4\n", r"m\.yaml:2: resolution: expected a finite decimal number, got '0x1p-4'"),
    ("image: m.pgm\nresolution: 0.05\norigin: [0x10, 0, 0]\n", r"m\.yaml:3: origin: expected a finite decimal number, got '0x10'"),
    ("image: m.pgm\nresolution: 0.05\norigin: [-1, 2]\n", r"m\.yaml:3: origin: expected \[x, y, yaw\], got 2 numbers"),
    ("image: m.pgm\nresolution: 0.05\n  deeper: 1\n", r"m\.yaml:3: resolution: unexpected indented line under its value"),
    ("- image: m.pgm\n- resolution: 0.05\n", r"m\.yaml:1: expected 'key: value', got '- image: m\.pgm'"),
])
def test_unsupported_yaml_names_the_line_not_a_missing_key(tmp_path, text, message):
    (tmp_path / "m.pgm").write_bytes(b"P5\n1 1\n255\n\x00")
    (tmp_path / "m.yaml").write_text(text)
    with pytest.raises(ValueError, match=message) as info:
        dv.OccupancyGrid.load(tmp_path / "m.yaml")
    assert "missing" not in str(info.value)


@pytest.mark.parametrize("key", ["origin", "negate", "occupied_thresh", "free_thresh"])
def test_a_yaml_without_a_key_map_server_requires_is_refused(tmp_path, key):
    # map_server and nav2 refuse such a file (only mode is optional): read with defaults, a map whose
    # origin was forgotten would sit at (0, 0) without a word
    (tmp_path / "m.pgm").write_bytes(b"P5\n1 1\n255\n\x00")
    (tmp_path / "m.yaml").write_text("".join(line + "\n" for line in BASE.splitlines() if not line.startswith(key + ":")))
    with pytest.raises(ValueError, match=rf"m\.yaml: missing '{key}'"):
        dv.OccupancyGrid.load(tmp_path / "m.yaml")
    cli = _cli()
    if cli is not None:
        proc = subprocess.run([cli, "gvd", str(tmp_path / "m.yaml"), "-q", "-o", str(tmp_path / "o.json")],
                              capture_output=True, text=True, timeout=120)
        assert proc.returncode == 2 and f"m.yaml: missing '{key}'" in proc.stderr, proc.stderr
        assert not (tmp_path / "o.json").exists()


# -- plain PGM ----------------------------------------------------------------------------------------

def test_plain_pgm_errors_name_line_and_column(tmp_path):
    (tmp_path / "p.pgm").write_text("P2\n# a map\n3 2\n255\n0 254 0\n254 25x 0\n")
    with pytest.raises(ValueError, match=r"p\.pgm:6:5: bad PGM pixel value '25x' \(pixel 5 of 6\)"):
        dv.OccupancyGrid.load(tmp_path / "p.pgm")
    (tmp_path / "q.pgm").write_text("P2\n3 2\n255\n0 254 0\n254\n# only four values, and then a comment\n")
    with pytest.raises(ValueError, match=r"q\.pgm:7:1: truncated PGM data \(4 of 6 pixels\)"):
        dv.OccupancyGrid.load(tmp_path / "q.pgm")


# -- the CLI reads the same files ---------------------------------------------------------------------

def _cli():
    env = os.environ.get("DVORONOI_CLI")
    if env:
        return env if Path(env).is_file() else None
    return shutil.which("dvoronoi")


def test_cli_reads_a_flow_mapping_yaml_and_names_the_line_of_a_bad_one(tmp_path):
    cli = _cli()
    if cli is None:
        pytest.skip("no dvoronoi executable (set DVORONOI_CLI)")
    img = np.full((30, 40), 254, np.uint8)
    img[:2], img[-2:], img[:, :2], img[:, -2:] = 0, 0, 0, 0
    img[12:18, 15:25] = 0
    (tmp_path / "m.pgm").write_bytes(b"P5\n40 30\n255\n" + img.tobytes())
    (tmp_path / "m.yaml").write_text("---\n{image: m.pgm, resolution: 0.5, origin: [-1, 2, 0], negate: false,\n"
                                     " occupied_thresh: 0.65, free_thresh: 0.196}\n")
    out = tmp_path / "out.json"
    proc = subprocess.run([cli, "gvd", str(tmp_path / "m.yaml"), "-q", "-o", str(out)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(out.read_text())
    assert doc["map"]["resolution"] == 0.5 and doc["map"]["origin"] == [-1, 2]
    (tmp_path / "bad.yaml").write_text("image: m.pgm\nresolution: 0.5\nnegate: sometimes\n")
    proc = subprocess.run([cli, "gvd", str(tmp_path / "bad.yaml"), "-q", "-o", str(tmp_path / "bad.json")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and "bad.yaml:3: negate:" in proc.stderr
    assert not (tmp_path / "bad.json").exists()


def test_a_yaml_keeps_its_own_thresholds_and_negate_and_negate_is_a_bool(tmp_path):
    (tmp_path / "m.pgm").write_bytes(b"P5\n3 2\n255\n" + bytes([0, 254, 205, 254, 0, 254]))
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    for kw in ({"occupied_thresh": 0.1}, {"free_thresh": 0.05}, {"negate": True}):
        with pytest.raises(ValueError, match=r"m\.yaml: a map_server YAML brings its own occupied_thresh, free_thresh and negate"):
            dv.OccupancyGrid.load(tmp_path / "m.yaml", **kw)
    with pytest.raises(ValueError, match="brings its own occupied_thresh"):
        dv.grid_voronoi(tmp_path / "m.yaml", occupied_thresh=0.99)
    assert dv.OccupancyGrid.load(tmp_path / "m.yaml").occupied.sum() == 3  # 2 walls + 1 unknown
    with pytest.raises(TypeError, match="negate must be True or False, got str"):
        dv.OccupancyGrid.load(tmp_path / "m.pgm", negate="false")
    assert dv.OccupancyGrid.load(tmp_path / "m.pgm", negate=np.bool_(False)).occupied.sum() == 3
