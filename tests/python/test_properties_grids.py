"""Property-based tests (hypothesis) of the grid diagrams: obstacle documents (dv.grid_voronoi on
documents, diagram "labels" and "medial") and occupancy grids (dv.grid_voronoi on arrays, "medial"
and "labels"; updates; workers).

Ties and what stays invariant. Both diagrams break ties by an order that the symmetries of the grid
do not keep: a corner of the labelled diagram takes the lower obstacle label among equally near
obstacles, and a pixel's nearest point F(p) of the medial diagram is the one with the smallest x,
then the smallest y. A rotation or a mirror (or a relabelling of the obstacles) can therefore change
the diagram exactly where a tie decides, and nowhere else:

* labelled diagram: a cell's membership (its corners carry two or more labels) is fixed by the
  corners' nearest obstacles. The tests compute, by brute force here, which corners are *ambiguous*
  (the two nearest labels' squared distances equal, or within 1e-9 relative for circles, whose
  distances carry a square root) and compare the transformed diagrams on the cells with four
  unambiguous corners -- where they must agree, and agree with the brute-force labels;
* medial diagram: a pixel's membership depends only on F of the pixel and of its 4-neighbours (and
  on the occupancy near them). Tie-free pixels (those five nearest points unique; computed here
  exactly, in quarter-integers) must map onto each other. The clearance map has no tie at all: it
  is compared exactly, everywhere. F itself is compared where it is unique and checked against the
  documented tie rule everywhere.

Transformations that keep the tie order keep the whole diagram: scaling by 2**k and dyadic
translations of documents, the map's resolution and origin, a one-pixel occupied frame around a map
(the outside of a map is occupied anyway), worker counts, slice approaches, incremental updates, and
the different spellings of one polygon (closed ring, repeated vertex, box or polygon area).
"""
from __future__ import annotations

import copy
import warnings

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import event, given, note, strategies as st  # noqa: E402

import dvoronoi as dv  # noqa: E402
from property_support import (  # noqa: E402
    ARRAY_SYMMETRIES, DIHEDRAL, NON_IDENTITY, corner_ambiguity, determined_cells, map_doc,
    obstacle_scenes, occupancy_maps, pixel_nearest_candidates, tie_free_pixels)

scipy_ndimage = pytest.importorskip("scipy.ndimage")

#: A symmetry of the plane applied to a document and the matching symmetry of its raster image.
DOC_TO_ARRAY = {"rot90": "rot90", "rot180": "rot180", "rot270": "rot270", "mirror_x": "fliplr",
                "mirror_y": "flipud", "transpose": "antitranspose", "antitranspose": "transpose"}


def medial(source, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # "no diagram pixel" on maps without passages
        return dv.grid_voronoi(source, workers=kw.pop("workers", 1), **kw)


def pixel_offsets(gv) -> np.ndarray:
    """F(p) - centre(p) per pixel, in pixel units (x right, y up)."""
    H, W = gv.shape
    rr, cc = np.mgrid[0:H, 0:W]
    centre = np.stack([cc + 0.5, H - 1 - rr + 0.5], axis=-1)
    ox, oy = gv.origin
    f = (gv.nearest_points - np.array([ox, oy])) / gv.resolution
    return f - centre


# ============================================================================ occupancy: medial
@given(data=st.data())
def test_medial_diagram_under_grid_symmetries(data):
    occ = data.draw(occupancy_maps())
    name = data.draw(st.sampled_from(sorted(ARRAY_SYMMETRIES)))
    T, L = ARRAY_SYMMETRIES[name]
    a = medial(occ)
    b = medial(np.ascontiguousarray(T(occ)))
    d2, ties, nearest = pixel_nearest_candidates(occ)
    # clearance has no tie: exactly equivariant, and exactly the brute-force distance
    assert np.array_equal(b.clearance_map, T(a.clearance_map))
    assert np.array_equal(a.clearance_map, np.sqrt(d2))
    # the nearest point: the documented tie rule everywhere, equivariant where it is unique
    H, W = occ.shape
    rr, cc = np.mgrid[0:H, 0:W]
    assert np.array_equal(a.nearest_points, nearest), "F(p) is not the smallest-x-then-y nearest point"
    oa, ob = pixel_offsets(a), pixel_offsets(b)
    unique = T((ties == 1) | occ)
    assert np.array_equal(ob[unique], L(T(oa))[unique])
    # the diagram on tie-free pixels
    free = T(tie_free_pixels(occ, ties))
    event(f"tie-free pixels: {'all' if free.sum() == (~occ).sum() else 'some' if free.any() else 'none'}")
    note(f"{name}: {int(free.sum())} tie-free of {int((~occ).sum())} free pixels")
    diff = (b.diagram_mask != T(a.diagram_mask)) & free
    assert not diff.any(), f"{name}: diagrams differ at tie-free pixels {np.argwhere(diff)[:5].tolist()}"
    assert not (b.diagram_mask & T(occ)).any()


@given(data=st.data())
def test_medial_diagram_frame_resolution_and_origin(data):
    occ = data.draw(occupancy_maps())
    k = data.draw(st.integers(-6, 6))
    origin = (data.draw(st.integers(-512, 512)) / 8.0, data.draw(st.integers(-512, 512)) / 8.0)
    a = medial(occ)
    # the outside of a map is occupied: a one-pixel occupied frame changes nothing inside
    framed = np.pad(occ, 1, constant_values=True)
    b = medial(framed)
    assert np.array_equal(b.diagram_mask[1:-1, 1:-1], a.diagram_mask) and not b.diagram_mask[[0, -1]].any()
    assert np.array_equal(b.clearance_map[1:-1, 1:-1], a.clearance_map)
    assert np.array_equal(pixel_offsets(b)[1:-1, 1:-1], pixel_offsets(a))
    # map units: resolution 2**k and a dyadic origin move nothing in pixel units
    c = medial(occ, resolution=2.0 ** k, origin=origin)
    assert np.array_equal(c.diagram_mask, a.diagram_mask)
    assert np.array_equal(c.clearance_map, a.clearance_map * 2.0 ** k)
    assert np.array_equal(c.nearest_points, a.nearest_points * 2.0 ** k + np.array(origin))


@given(data=st.data())
def test_medial_diagram_workers_and_updates_equal_a_full_build(data):
    occ = data.draw(occupancy_maps())
    H, W = occ.shape
    ref_workers = medial(occ, workers=data.draw(st.integers(2, 4)))
    a = medial(occ)
    assert np.array_equal(ref_workers.diagram_mask, a.diagram_mask)
    assert np.array_equal(ref_workers.nearest_points, a.nearest_points)
    current = occ.copy()
    for _ in range(data.draw(st.integers(1, 4))):
        pix = data.draw(st.lists(st.tuples(st.integers(0, H - 1), st.integers(0, W - 1)), min_size=1, max_size=6))
        how = data.draw(st.sampled_from(["set_occupied", "set_free", "update"]))
        if how == "update":
            for r, c in pix:
                current[r, c] = ~current[r, c]
            a.update(current.copy())
        else:
            getattr(a, how)(pix)
            for r, c in pix:
                current[r, c] = how == "set_occupied"
    full = medial(current)
    assert np.array_equal(a.grid.occupied, current)
    assert np.array_equal(a.diagram_mask, full.diagram_mask)
    assert np.array_equal(a.clearance_map, full.clearance_map)
    assert np.array_equal(a.nearest_points, full.nearest_points)


# ============================================================================ occupancy: labels
def _labels_ambiguity(occ: np.ndarray):
    """Corner labels of the map's labelled diagram (8-connected occupied regions, then the area's
    edges bottom, right, top, left) and exact ties, on the pixel corners (x, y) = (i, j), as
    (H+1, W+1) arrays indexed [j, i] (y up). Integer arithmetic: exact."""
    H, W = occ.shape
    regions, n = scipy_ndimage.label(occ, structure=np.ones((3, 3), bool))
    yy, xx = np.mgrid[0:H + 1, 0:W + 1].astype(float)
    d = []
    for k in range(1, n + 1):
        rr, cc = np.nonzero(regions == k)
        x0, x1 = cc.astype(float), cc + 1.0
        y0, y1 = (H - 1 - rr).astype(float), (H - rr).astype(float)
        dx = np.maximum(0, np.maximum(x0[:, None, None] - xx, xx - x1[:, None, None]))
        dy = np.maximum(0, np.maximum(y0[:, None, None] - yy, yy - y1[:, None, None]))
        d.append(np.min(dx * dx + dy * dy, axis=0))
    d += [yy * yy, (W - xx) ** 2, (H - yy) ** 2, xx * xx]
    D = np.stack(d)
    srt = np.sort(D, axis=0)
    return np.argmin(D, axis=0), srt[0] == srt[1]


@given(data=st.data())
def test_labels_diagram_of_maps_under_grid_symmetries(data):
    occ = data.draw(occupancy_maps(max_side=14))
    name = data.draw(st.sampled_from(sorted(ARRAY_SYMMETRIES)))
    T, _ = ARRAY_SYMMETRIES[name]
    a = medial(occ, diagram="labels")
    b = medial(np.ascontiguousarray(T(occ)), diagram="labels")
    H, W = occ.shape
    assert a.shape == (H, W)
    img_a, img_b = a.diagram_mask[::-1], b.diagram_mask[::-1]   # cells are pixels; rows bottom-up
    label, amb = _labels_ambiguity(occ)
    sure, mixed = determined_cells(label, amb)
    sure_img, mixed_img = sure[::-1], mixed[::-1]
    event(f"determined cells: {'all' if sure.all() else 'some' if sure.any() else 'none'}")
    assert np.array_equal(img_a[sure_img], mixed_img[sure_img]), "labelled diagram differs from its definition"
    diff = (img_b != T(img_a)) & T(sure_img)
    assert not diff.any(), f"{name}: labelled diagrams differ at determined cells {np.argwhere(diff)[:5].tolist()}"


# ============================================================================ obstacle documents
def _cell_map(gv_from, gv_to, f):
    """Index arrays mapping every cell (j, i) of gv_from's grid to gv_to's cell under the point map f."""
    ny, nx = gv_from.shape
    jj, ii = np.mgrid[0:ny, 0:nx]
    h = gv_from.cell_size
    centres = np.stack([gv_from.origin[0] + (ii + 0.5) * h, gv_from.origin[1] + (jj + 0.5) * h], -1).reshape(-1, 2)
    t = f(centres)
    i2 = np.floor((t[:, 0] - gv_to.origin[0]) / gv_to.cell_size).astype(int)
    j2 = np.floor((t[:, 1] - gv_to.origin[1]) / gv_to.cell_size).astype(int)
    return jj.ravel(), ii.ravel(), j2, i2


def _labels_of(gv):
    out = {}
    for (c, r), lab in zip(gv.cells.tolist(), gv.labels.tolist()):
        out[(c, r)] = lab
    return out


@given(data=st.data())
def test_document_labels_diagram_under_symmetries_and_relabelling(data):
    doc, cells = data.draw(obstacle_scenes())
    name = data.draw(st.sampled_from(NON_IDENTITY))
    perm = data.draw(st.permutations(list(range(len(doc["obstacles"])))))
    moved = map_doc(doc, DIHEDRAL[name])
    moved["obstacles"] = [moved["obstacles"][k] for k in perm]
    a = dv.grid_voronoi(doc, cells=cells, workers=1)
    b = dv.grid_voronoi(moved, cells=cells, workers=1)
    label, amb = corner_ambiguity(doc, cells)
    sure, mixed = determined_cells(label, amb)
    event(f"determined cells: {'all' if sure.all() else 'some' if sure.any() else 'none'}")
    ma = a.diagram_mask
    assert np.array_equal(ma[sure], mixed[sure]), \
        f"diagram differs from the brute-force labels at {np.argwhere((ma != mixed) & sure)[:5].tolist()}"
    # traced labels are the nearest obstacles wherever a corner is unambiguous
    for (c, r), lab in _labels_of(a).items():
        for (dc, dr), got in zip(((0, 0), (1, 0), (1, 1), (0, 1)), lab):
            if not amb[r + dr, c + dc]:
                want = int(label[r + dr, c + dc])
                assert got == want, ((c, r), (dc, dr), got, want)
    j, i, j2, i2 = _cell_map(a, b, DIHEDRAL[name])
    mb = b.diagram_mask
    keep = sure[j, i]
    bad = np.flatnonzero(keep & (ma[j, i] != mb[j2, i2]))
    assert not len(bad), f"{name}: diagrams differ at determined cells {[(int(i[k]), int(j[k])) for k in bad[:5]]}"


@given(data=st.data())
def test_document_scaling_and_translation_are_exact(data):
    doc, cells = data.draw(obstacle_scenes())
    k = data.draw(st.integers(-8, 8))
    f = 2.0 ** k
    shift = np.array([data.draw(st.integers(-256, 256)) / 4.0, data.draw(st.integers(-256, 256)) / 4.0])
    a = dv.grid_voronoi(doc, cells=cells, workers=1)
    b = dv.grid_voronoi(map_doc(doc, lambda p: p * f), cells=cells, workers=1)
    c = dv.grid_voronoi(map_doc(doc, lambda p: p + shift), cells=cells, workers=1)
    for other in (b, c):
        assert np.array_equal(other.cells, a.cells)
        assert np.array_equal(other.labels, a.labels)
        assert np.array_equal(other.vertices, a.vertices)
    assert np.array_equal(b.clearance, a.clearance * f)
    assert np.array_equal(c.clearance, a.clearance)


@given(data=st.data())
def test_document_workers_modes_and_visibility_give_one_diagram(data):
    doc, cells = data.draw(obstacle_scenes())
    a = dv.grid_voronoi(doc, cells=cells, workers=1)
    b = dv.grid_voronoi(doc, cells=cells, workers=data.draw(st.integers(2, 5)),
                        mode=data.draw(st.sampled_from(["cooperative", "independent"])),
                        visibility=data.draw(st.booleans()))
    assert np.array_equal(a.cells, b.cells) and np.array_equal(a.labels, b.labels)
    assert np.array_equal(a.clearance, b.clearance) and np.array_equal(a.blocked, b.blocked)
    brute = dv._core._gvd_brute_force(dv.gvd.load_obstacles(doc), cells, True)[2]
    assert np.array_equal(a.diagram_mask, brute)


@given(data=st.data())
def test_document_polygon_spellings_are_one_polygon(data):
    doc, cells = data.draw(obstacle_scenes())
    a = dv.grid_voronoi(doc, cells=cells, workers=1)
    spelled = copy.deepcopy(doc)
    polys = [s for s in spelled["obstacles"] if s["type"] == "polygon"]
    polys += [p for s in spelled["obstacles"] if s["type"] == "union" for p in s["parts"] if p["type"] == "polygon"]
    for s in polys:
        v = s["vertices"]
        how = data.draw(st.sampled_from(["closed", "repeat", "rotate", "reverse"]))
        if how == "closed":
            s["vertices"] = v + [v[0]]
        elif how == "repeat":
            k = data.draw(st.integers(0, len(v) - 1))
            s["vertices"] = v[:k + 1] + v[k:]
        elif how == "rotate":
            k = data.draw(st.integers(0, len(v) - 1))
            s["vertices"] = v[k:] + v[:k]
        else:
            s["vertices"] = v[::-1]
    x0, y0, x1, y1 = doc["area"]["box"]
    area = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]   # the box as a polygon: the same edge labels
    area_form = data.draw(st.sampled_from(["box", "polygon", "closed", "repeat"]))
    if area_form == "polygon":
        spelled["area"] = {"polygon": area}
    elif area_form == "closed":
        spelled["area"] = {"polygon": area + [area[0]]}
    elif area_form == "repeat":
        k = data.draw(st.integers(0, 3))
        spelled["area"] = {"polygon": area[:k + 1] + area[k:]}
    b = dv.grid_voronoi(spelled, cells=cells, workers=1)
    assert np.array_equal(a.diagram_mask, b.diagram_mask)
    assert np.array_equal(a.labels, b.labels)
    assert np.array_equal(a.clearance, b.clearance)


@given(data=st.data())
def test_document_medial_diagram_under_symmetries(data):
    doc, cells = data.draw(obstacle_scenes())
    name = data.draw(st.sampled_from(NON_IDENTITY))
    T, _ = ARRAY_SYMMETRIES[DOC_TO_ARRAY[name]]
    a = medial(doc, cells=cells, diagram="medial")
    b = medial(map_doc(doc, DIHEDRAL[name]), cells=cells, diagram="medial")
    occ = a.grid.occupied
    # the raster: a pixel is occupied when its closed square meets an obstacle -- equivariant
    assert np.array_equal(b.grid.occupied, T(occ))
    _, ties, _ = pixel_nearest_candidates(occ)
    free = T(tie_free_pixels(occ, ties))
    assert np.array_equal(b.clearance_map, T(a.clearance_map))
    diff = (b.diagram_mask != T(a.diagram_mask)) & free
    assert not diff.any(), f"{name}: medial diagrams differ at tie-free pixels {np.argwhere(diff)[:5].tolist()}"
