"""The GIS bridge of results with cells: __geo_interface__, to_shapely(tolerance), to_geopandas().

Polygons are checked against the exact cells: area within the stated densification bound (below the
exact area by at most tolerance x arc length), every vertex on or inside the exact cell's circle.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import dvoronoi as dv

shapely = pytest.importorskip("shapely", reason="shapely is not installed (pip install .[test])")
from shapely.geometry import shape  # noqa: E402

RNG = np.random.default_rng(5)
P = RNG.random((80, 2))


def _arc_length(part, i):
    lo, hi = part.piece_ptr[i], part.piece_ptr[i + 1]
    arcs = part.piece_neighbor[lo:hi] == -1
    return float(part.radius * np.sum(part.piece_span[lo:hi][arcs]))


def cell_results():
    return {
        "limited": dv.limited_cells(P, 0.12),
        "coverage": dv.coverage.lloyd(P, 0.12, steps=2, bounds=(0, 0, 1, 1)),
        "network_cc": dv.network.simulate("cc", P * 100, 30.0, seed=2, bounds=(0, 0, 100, 100)),
        "network_bd07": dv.network.simulate("bd07", P * 100, 30.0, bounds=(0, 0, 100, 100)),
    }


@pytest.mark.parametrize("name", ["limited", "coverage", "network_cc", "network_bd07"])
def test_geo_interface_is_the_geojson_export(name):
    r = cell_results()[name]
    fc = r.__geo_interface__
    assert fc["type"] == "FeatureCollection" and len(fc["features"]) == len(r)
    assert fc == json.loads(r.to_geojson())  # the default tolerance, as the export
    polys = [None if f["geometry"] is None else shape(f["geometry"]) for f in fc["features"]]
    assert all(p is None or p.is_valid for p in polys)
    # shapely reads the protocol of the whole result too
    assert len(shapely.geometry.shape(fc["features"][0]["geometry"]).exterior.coords) >= 4


@pytest.mark.parametrize("tolerance", [1e-3, 1e-5])
def test_to_shapely_areas_within_the_stated_bound(tolerance):
    part = dv.limited_cells(P, 0.12)
    polys = part.to_shapely(tolerance=tolerance)
    assert len(polys) == len(part)
    for i, poly in enumerate(polys):
        exact = float(part.areas[i])
        assert poly.is_valid
        assert poly.area <= exact + 1e-12
        assert exact - poly.area <= tolerance * _arc_length(part, i) + 1e-12
        # every vertex lies in the cell's disk (chords are inscribed)
        d = np.hypot(*(np.asarray(poly.exterior.coords) - P[i]).T)
        assert np.all(d <= part.radius * (1 + 1e-12))
    # a finer tolerance gives areas closer to the exact ones (the arcs are really densified)
    coarse = sum(p.area for p in part.to_shapely(tolerance=1e-2))
    fine = sum(p.area for p in polys)
    assert abs(fine - part.areas.sum()) < abs(coarse - part.areas.sum())
    with pytest.raises(ValueError, match="tolerance"):
        part.to_shapely(tolerance=-1.0)


def test_voronoi_partition_polygons():
    vor = dv.voronoi_cells(P, bounds=(0, 0, 1, 1))
    polys = vor.to_shapely()
    assert sum(p.area for p in polys) == pytest.approx(1.0, rel=1e-12)
    assert np.allclose([p.area for p in polys], vor.areas, rtol=1e-12)
    unbounded = dv.voronoi_cells(P).to_shapely()
    hull = dv.voronoi_cells(P).on_hull
    assert [p is None for p in unbounded] == hull.tolist()  # unbounded cells have no polygon
    with pytest.raises(ValueError, match="tolerance"):
        vor.to_shapely(tolerance=0.0)


def test_to_geopandas():
    gpd = pytest.importorskip("geopandas", reason="geopandas is not installed")
    part = dv.limited_cells(P, 0.12)
    frame = part.to_geopandas(tolerance=1e-4)
    assert isinstance(frame, gpd.GeoDataFrame) and len(frame) == len(part)
    assert frame.index.tolist() == list(range(len(part)))
    assert np.array_equal(frame["area"].to_numpy(), part.areas)  # the exact areas
    assert frame["neighbors"].iloc[3] == part.neighbors(3).tolist()
    assert np.allclose(frame.geometry.area, part.areas, rtol=0, atol=1e-4 * 2 * math.pi * 0.12)


def test_missing_optional_package_says_what_to_install(monkeypatch):
    import sys

    # None in sys.modules makes `import name` raise ImportError, as if the package were not installed.
    for name in ("shapely", "shapely.geometry", "geopandas"):
        monkeypatch.setitem(sys.modules, name, None)
    part = dv.limited_cells(P[:5], 0.12)
    with pytest.raises(ImportError, match=r"to_shapely\(\) needs shapely.*pip install shapely"):
        part.to_shapely()
    with pytest.raises(ImportError, match=r"to_geopandas\(\) needs geopandas.*pip install geopandas"):
        part.to_geopandas()
    assert part.__geo_interface__["type"] == "FeatureCollection"  # needs nothing


def test_single_cells_have_the_gis_bridge():
    # dv.limited_cell and dv.voronoi_cell results are compiled classes; they get __geo_interface__ and
    # to_shapely() like every result with cells. Arcs are densified, so the polygon's area is the
    # exact area minus at most tolerance x arc length (tolerance radius / 1000).
    shapely = pytest.importorskip("shapely.geometry")
    rng = np.random.default_rng(3)
    others = rng.uniform(-1, 1, (12, 2))
    cell = dv.limited_cell([0.0, 0.0], others, 0.6)
    geo = cell.__geo_interface__
    assert geo["type"] == "Feature" and geo["geometry"]["type"] == "Polygon"
    poly = shapely.shape(geo["geometry"])
    arcs = float(np.sum(cell.piece_span[cell.piece_neighbor < 0])) * 0.6
    assert cell.area - 0.6e-3 * arcs - 1e-12 <= poly.area <= cell.area + 1e-12
    assert cell.to_shapely().equals(poly)
    # An exact cell: a polygon when bounded (or clipped to bounds), None when unbounded.
    ring = dv.voronoi_cell([0.0, 0.0], np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]))
    assert ring.to_shapely().area == pytest.approx(ring.area, rel=1e-12)
    open_cell = dv.voronoi_cell([0.0, 0.0], np.array([[1.0, 0.0], [0.0, 1.0]]))
    assert open_cell.__geo_interface__["geometry"] is None and open_cell.to_shapely() is None
    boxed = dv.voronoi_cell([0.0, 0.0], np.array([[1.0, 0.0], [0.0, 1.0]]), bounds=(-2, -2, 2, 2))
    assert boxed.to_shapely().area == pytest.approx(boxed.area, rel=1e-12)
    assert boxed.to_shapely().exterior.is_ccw


def _refuse_constants(name):
    raise ValueError(f"GeoJSON must be strict JSON, found {name}")


def test_network_cc_cells_and_unbounded_hull_cells():
    # Written in C++ (io/network_geojson.hpp): strict JSON, a closed counter-clockwise polygon per
    # interior cell with its exact area, null geometry and area for an unbounded hull cell.
    cc = dv.network.simulate("cc", P * 100, 30.0, seed=2)
    doc = json.loads(cc.to_geojson(), parse_constant=_refuse_constants)
    assert doc == cc.__geo_interface__ and len(doc["features"]) == len(cc)
    for i, f in enumerate(doc["features"]):
        props = f["properties"]
        assert props["agent"] == i and props["neighbors"] == cc.neighbors(i).tolist()
        if cc.on_hull[i]:
            assert f["geometry"] is None and props["area"] is None
            continue
        ring = f["geometry"]["coordinates"][0]
        assert ring[0] == ring[-1]
        poly = shape(f["geometry"])
        assert poly.is_valid and poly.exterior.is_ccw
        assert poly.area == pytest.approx(cc.areas[i], rel=1e-9) and props["area"] == cc.areas[i]
    polys = cc.to_shapely()
    assert [p is None for p in polys] == cc.on_hull.tolist()


@pytest.mark.parametrize("tolerance", [None, 0.5, 0.01])
def test_network_bs_arcs_around_the_positions_used(tolerance):
    # DV-Hop moves the cells to the estimated positions: the arcs are densified around those.
    bs = dv.network.simulate("bs", P * 100, 30.0, anchor_fraction=0.3, seed=3)
    assert bs.estimates is not None and not np.allclose(bs.positions[bs.localized], bs.points[bs.localized])
    tol = bs.radius / 1000 if tolerance is None else tolerance
    polys = bs.to_shapely(tolerance=tolerance)
    assert [p is None for p in polys] == (~bs.localized).tolist()
    for i, poly in enumerate(polys):
        if poly is None:
            continue
        exact = float(bs.areas[i])
        assert poly.is_valid and poly.exterior.is_ccw and poly.area <= exact + 1e-9
        assert exact - poly.area <= tol * _arc_length(bs, i) + 1e-9
        d = np.hypot(*(np.asarray(poly.exterior.coords) - bs.positions[i]).T)
        assert np.all(d <= bs.radius * (1 + 1e-12))
    with pytest.raises(ValueError, match="tolerance"):
        bs.to_geojson(tolerance=-1.0)
