"""Example data shipped with dvoronoi."""
from __future__ import annotations

import io
from importlib import resources

import numpy as np

__all__ = ["intel_lab"]


def _read(name: str) -> str:
    return resources.files("dvoronoi").joinpath("data").joinpath(name).read_text(encoding="utf-8")


def intel_lab() -> np.ndarray:
    """Positions of the 54 Mica2Dot motes of the Intel Berkeley Research Lab deployment (2004).

    Returns
    -------
    numpy.ndarray
        Shape ``(54, 2)``, float64, metres in the lab's floor plan; row ``k`` is mote ``k + 1``.

    Notes
    -----
    The file ``dvoronoi/data/intel_lab_motes.txt`` (columns ``mote_id x y``) keeps the data set's
    provenance in its comment lines.
    """
    table = np.loadtxt(io.StringIO(_read("intel_lab_motes.txt")), comments="#", ndmin=2)
    table = table[np.argsort(table[:, 0], kind="stable")]
    return np.ascontiguousarray(table[:, 1:3], dtype=np.float64)
