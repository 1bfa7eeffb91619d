"""Simulated distance measurements for the distance-only algorithm, reproducible from a seed.

Each robot measures each detected robot independently (sigma_ij and sigma_ji), and the pair's edge
weight is e_ij = (sigma_ij + sigma_ji) / 2 (Elwin, Freeman & Lynch, Section II-A). Models:

* ``"exact"``: sigma = d.
* ``"additive"``: sigma = d + N(0, sigma^2) (``sigma`` in distance units).
* ``"multiplicative"``: sigma = d (1 + N(0, sigma^2)) (``sigma`` relative).
* ``"rssi"``: the paper's XBee model (Section V-A, Fig. 7) rebuilt from its published fit: the
  received signal strength (in -dBm) at distance d is the inverse of the fitted quadratic
  ``d(x) = -0.0141 x^2 + 1.9614 x - 35.365`` (cm) on its increasing branch, plus Gaussian noise of
  ``sigma`` dB, quantised to integer dBm (the radio reports whole dBm) and clipped to the fit's
  range; the measured distance is d(RSSI). Beyond 33 cm robots do not detect each other. The raw
  experimental data are not published, so the spread ``sigma`` (default 2 dB) is our assumption;
  the quantisation makes distances near the range limit very coarse (the fit flattens out at
  32.84 cm), as in the experiment. The experiment starts at 8.89 cm: robots closer than that measure
  like robots 8.89 cm apart (the closest data the paper's model can draw from).

Gaussian draws that come out negative are reflected (|sigma|): a measured distance of 0 or less would
claim coinciding robots; an exact 0 becomes the smallest positive double. Everything draws from
``numpy.random.default_rng(seed)``.
"""
from __future__ import annotations

from typing import Optional, Tuple

import numpy as np

__all__ = ["detection_pairs", "measure", "rssi_to_distance", "distance_to_rssi", "RSSI_FIT", "RSSI_RANGE_CM", "RSSI_MIN_CM"]

RSSI_FIT = (-0.0141, 1.9614, -35.365)  # d(x) = a x^2 + b x + c, x = RSSI in -dBm, d in cm (paper, Fig. 7)
RSSI_RANGE_CM = 33.0                   # robots farther apart cannot sense or communicate (paper, V-B)
RSSI_MIN_CM = 8.89                     # closest distance of the experiment (paper, V-A)
_X_PEAK = -RSSI_FIT[1] / (2.0 * RSSI_FIT[0])  # 69.55 dBm: the fit's maximum, 32.84 cm
# Smallest RSSI where the fit gives a positive distance (the root of d(x) = 0 below the peak).
_X_ZERO = (-RSSI_FIT[1] + np.sqrt(RSSI_FIT[1] ** 2 - 4.0 * RSSI_FIT[0] * RSSI_FIT[2])) / (2.0 * RSSI_FIT[0])


def rssi_to_distance(rssi) -> np.ndarray:
    """The paper's quadratic fit: distance (cm) from RSSI (-dBm)."""
    x = np.asarray(rssi, dtype=float)
    a, b, c = RSSI_FIT
    return a * x * x + b * x + c


def distance_to_rssi(d) -> np.ndarray:
    """Inverse of the fit on its increasing branch: the mean RSSI (-dBm) at distance d (cm);
    distances beyond the fit's maximum (32.84 cm) map to its peak."""
    a, b, c = RSSI_FIT
    d = np.minimum(np.asarray(d, dtype=float), rssi_to_distance(_X_PEAK))
    disc = np.maximum(b * b - 4.0 * a * (c - d), 0.0)
    return (-b + np.sqrt(disc)) / (2.0 * a)


def detection_pairs(points, radius: float) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """All pairs i < j closer than `radius` (strictly) and their true distances (KD-tree)."""
    from scipy.spatial import cKDTree

    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"points must be an (n, 2) array, got shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise ValueError("points has a non-finite coordinate (NaN or inf)")
    if not (np.isfinite(radius) and radius > 0):
        raise ValueError(f"radius must be a positive finite number, got {radius!r}")
    pairs = cKDTree(pts).query_pairs(radius, output_type="ndarray")
    if len(pairs) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    i, j = pairs[:, 0].astype(np.int64), pairs[:, 1].astype(np.int64)
    d = np.hypot(*(pts[i] - pts[j]).T)
    keep = d < radius
    return i[keep], j[keep], d[keep]


def _one_direction(d: np.ndarray, model: str, sigma: float, rng: np.random.Generator) -> np.ndarray:
    if model == "exact":
        return d.copy()
    if model == "additive":
        return d + rng.normal(0.0, sigma, size=d.shape)
    if model == "multiplicative":
        return d * (1.0 + rng.normal(0.0, sigma, size=d.shape))
    if model == "rssi":
        x = distance_to_rssi(np.maximum(d, RSSI_MIN_CM)) + rng.normal(0.0, sigma, size=d.shape)
        x = np.clip(np.rint(x), np.ceil(_X_ZERO), np.floor(_X_PEAK))
        return rssi_to_distance(x)
    raise ValueError(f"model must be 'exact', 'additive', 'multiplicative' or 'rssi', got {model!r}")


def measure(points, radius: Optional[float] = None, model: str = "exact", sigma: Optional[float] = None,
            seed=None):
    """Simulated measurements between robots at `points` closer than `radius`: a symmetric
    ``scipy.sparse.csr_matrix`` of e_ij = (sigma_ij + sigma_ji) / 2 (absent = not detected), ready for
    :func:`dvoronoi.neighbors_from_distances`.

    `radius` defaults to 33 (cm) for the ``"rssi"`` model and is required otherwise. `sigma`
    defaults to 0.05 (additive: distance units), 0.05 (multiplicative: relative), 2.0 (rssi: dB).
    """
    import scipy.sparse as sp

    if radius is None:
        if model != "rssi":
            raise ValueError("radius is required (the detection range)")
        radius = RSSI_RANGE_CM
    if sigma is None:
        sigma = {"additive": 0.05, "multiplicative": 0.05, "rssi": 2.0}.get(model, 0.0)
    if not (np.isfinite(sigma) and sigma >= 0):
        raise ValueError(f"sigma must be a finite number >= 0, got {sigma!r}")
    rng = np.random.default_rng(seed)
    i, j, d = detection_pairs(points, radius)
    s_ij = _one_direction(d, model, sigma, rng)
    s_ji = _one_direction(d, model, sigma, rng)
    e = 0.5 * (np.abs(s_ij) + np.abs(s_ji))
    e = np.maximum(e, np.finfo(float).tiny)
    n = len(np.asarray(points))
    m = sp.coo_matrix((np.concatenate([e, e]), (np.concatenate([i, j]), np.concatenate([j, i]))), shape=(n, n))
    return m.tocsr()
