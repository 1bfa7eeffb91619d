"""``dv.load(path)``: read back a result JSON that dvoronoi (Python or the ``dvoronoi`` CLI) wrote.

Every result JSON names its type in ``"kind"``. Where the file records all of a result's inputs
(``limited_partition``: points, radius, method; ``voronoi_partition``: points, inner, bounds;
``network_cc``, ``network_bd07``, ``network_bs``: points, range, loss, seed, obstacles, bounds,
radius, anchors and the other ``options``) the full result object is rebuilt by running the same
exact, deterministic computation, and the rebuilt result's JSON is checked against the file, so what
comes back is what the file says. Every other kind (its inputs, e.g. obstacles or distances, are not
in the file) loads as a read-only :class:`LoadedResult` holding the file's fields; so does a network
file written before its ``options`` were recorded.
"""
from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Union

import numpy as np

from ._io import PathLike
from ._result import Result

#: Network kinds: rebuilt by running the simulation again when the file records its ``options``.
NETWORK_KINDS = ("network_cc", "network_bd07", "network_bs")
#: Kinds rebuilt as full result objects; the others load as :class:`LoadedResult`.
REBUILT_KINDS = ("limited_partition", "voronoi_partition") + NETWORK_KINDS
#: Kinds that load as :class:`LoadedResult`.
READ_ONLY_KINDS = ("limited_cell", "grid_voronoi", "distance_neighbors", "coverage_cells", "lloyd")


def _readonly(value: Any) -> Any:
    """A JSON list of numbers (or of equal-length number rows) as a read-only numpy array; anything
    else (strings, objects, ragged lists, lists with nulls) as it is."""
    if not isinstance(value, list) or not value:
        return value
    try:
        a = np.asarray(value)
    except ValueError:  # ragged rows
        return value
    if a.dtype.kind not in "biuf":
        return value
    if a.dtype.kind == "i":
        a = a.astype(np.int64)
    a.flags.writeable = False
    return a


class LoadedResult(Result):
    """A result read back from JSON whose inputs the file does not record (see :func:`load`).

    Each top-level JSON field is ``result[name]`` and, unless a method has its name (a single cell's
    ``neighbors``), ``result.name``: numeric lists as read-only numpy arrays (``int64`` or
    ``float64``), everything else as parsed. ``kind`` is the file's kind and ``path`` the file. Where
    the file holds the neighbour relation (``indptr``/``indices``, or a coverage result's cells),
    ``neighbors(i)``, ``to_csr()`` and ``len()`` work as on every result. Attributes cannot be set,
    and ``to_json()`` writes the document as it was read, whatever is done to the parsed fields.
    """

    kind: str
    path: str

    def __init__(self, doc: Dict[str, Any], path: str) -> None:
        self.__dict__["_text"] = json.dumps(doc)  # what to_json() writes, apart from the fields handed out
        self.__dict__["_names"] = list(doc)
        self.__dict__["kind"] = doc["kind"]
        self.__dict__["path"] = path
        fields = {k: _readonly(v) for k, v in doc.items()}
        cells = doc.get("cells")
        if "indptr" not in fields and isinstance(cells, list) and all(
                isinstance(c, dict) and isinstance(c.get("neighbors"), list) for c in cells):
            # Coverage results list each cell's neighbours: the same relation as CSR arrays.
            counts = [len(c["neighbors"]) for c in cells]
            indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
            indices = np.array([j for c in cells for j in c["neighbors"]], dtype=np.int64)
            indptr.flags.writeable = indices.flags.writeable = False
            fields.setdefault("indptr", indptr)
            fields.setdefault("indices", indices)
        self.__dict__["_fields"] = fields

    @property
    def fields(self) -> List[str]:
        """The top-level field names of the file, in its order (``indptr``/``indices`` are also
        attributes of a coverage result, built from its cells' ``neighbors``)."""
        return list(self._names)

    def __getitem__(self, name: str) -> Any:
        try:
            return self._fields[name]
        except KeyError:
            raise KeyError(f"a loaded {self.kind!r} result has no field {name!r}; it has {self.fields}") from None

    def __getattr__(self, name: str) -> Any:
        fields = self.__dict__.get("_fields", {})
        if name in fields:
            return fields[name]
        raise AttributeError(f"a loaded {self.__dict__.get('kind', '?')!r} result has no field {name!r}")

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"a loaded result is read-only (setting {name!r})")

    def __len__(self) -> int:
        if "indptr" in self._fields:
            return int(len(self._fields["indptr"]) - 1)
        if "points" in self._fields:
            return len(self._fields["points"])
        raise TypeError(f"a loaded {self.kind!r} result has no agents (no indptr or points field)")

    def neighbors(self, i: int) -> np.ndarray:
        if "indptr" not in self._fields:
            raise AttributeError(f"a loaded {self.kind!r} result has no neighbour relation (indptr/indices)")
        return super().neighbors(i)

    def _json_text(self, indent: Optional[int]) -> str:
        text: str = self._text
        return text if indent is None else json.dumps(json.loads(text), indent=indent)

    def __getstate__(self) -> Dict[str, Any]:
        return {"text": self._text, "path": self.path}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        LoadedResult.__init__(self, json.loads(state["text"]), state["path"])

    def __repr__(self) -> str:
        return f"LoadedResult(kind={self.kind!r}, path={self.path!r}, fields={self.fields})"


def _first_difference(a: Any, b: Any, where: str = "") -> Optional[str]:
    """The path of the first place where two parsed JSON documents differ, or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in list(a) + [k for k in b if k not in a]:
            if k not in a or k not in b:
                return f"{where}.{k}"
            d = _first_difference(a[k], b[k], f"{where}.{k}")
            if d is not None:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where} (length {len(a)} vs {len(b)})"
        for k, (x, y) in enumerate(zip(a, b)):
            d = _first_difference(x, y, f"{where}[{k}]")
            if d is not None:
                return d
        return None
    return None if a == b else (where or "the document")


def _simulate_again(doc: Dict[str, Any], points: np.ndarray) -> Result:
    """The network run a file records, run again with the inputs and options it holds."""
    from . import network

    options = dict(doc["options"])
    budget = options.pop("budget")
    if doc["algorithm"] == "bs":
        options.update(radius=doc["radius"], anchors=doc["anchors"])
    else:
        options.update(bounds=doc["bounds"])
    result: Result = network.simulate(doc["algorithm"], points, doc["comm_range"], loss=doc["loss"],
                                      obstacles=np.asarray(doc["obstacles"], dtype=np.float64).reshape(-1, 4),
                                      seed=doc["seed"], budget=budget or None, **options)
    return result


def _rebuild(doc: Dict[str, Any], path: str) -> Result:
    from . import limited_cells, voronoi_cells

    kind = doc["kind"]
    try:
        points = np.asarray(doc["points"], dtype=np.float64).reshape(-1, 2)
        if kind in NETWORK_KINDS:
            result = _simulate_again(doc, points)
        elif kind == "limited_partition":
            result = limited_cells(points, doc["radius"], method=doc["method"], progress=False)
        else:
            bounds = doc["bounds"]
            result = voronoi_cells(points, inner=doc["inner"],
                                   bounds=None if bounds is None else np.asarray(bounds, dtype=np.float64),
                                   progress=False)
    except KeyError as e:
        raise ValueError(f"{path}: a {kind} result without the field {e.args[0]!r}") from None
    except (TypeError, ValueError) as e:
        raise ValueError(f"{path}: the {kind} result's inputs are not valid: {e}") from e
    diff = _first_difference(doc, json.loads(result._json_text(None)))
    if diff is not None:
        raise ValueError(f"{path}: the {kind} result differs at {diff.lstrip('.')} from what dvoronoi computes "
                         "from the points and options it records (edited, or written by another version?)")
    return result


def load(path: PathLike) -> Union[Result, LoadedResult]:
    """Read back a result that dvoronoi wrote as JSON (``to_json(path)`` or the ``dvoronoi`` CLI's ``-o``).

    - ``"limited_partition"`` and ``"voronoi_partition"`` come back as :class:`LimitedPartition` and
      :class:`VoronoiPartition`, ``"network_cc"``, ``"network_bd07"`` and ``"network_bs"`` as
      :class:`~dvoronoi.network.CcResult`, :class:`~dvoronoi.network.Bd07Result` and
      :class:`~dvoronoi.network.BoundaryScanResult`: rebuilt from the points and options the file
      records (the computation, a simulation included, is deterministic) and checked against the
      file: a file whose results differ from what its inputs give raises ValueError naming the first
      differing field.
    - Every other kind (``limited_cell``, ``grid_voronoi``, ``distance_neighbors``,
      ``coverage_cells``, ``lloyd``) records results but not all of its inputs, so it loads as a
      read-only :class:`LoadedResult`; so does a network file without ``"options"`` (written by an
      earlier version).

    Raises
    ------
    FileNotFoundError, OSError
        The file cannot be read.
    ValueError
        The file is not JSON, not a dvoronoi result (no known ``"kind"``; a GeoJSON export is not a
        result), or inconsistent with its inputs. Every message names the file.
    """
    name = os.fspath(path)
    with open(name, "rb") as f:
        data = f.read()
    try:
        doc = json.loads(data)
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ValueError(f"{name}: not a JSON file ({e})") from None
    kind = doc.get("kind") if isinstance(doc, dict) else None
    if kind in NETWORK_KINDS and "options" not in doc:
        return LoadedResult(doc, name)
    if kind in REBUILT_KINDS:
        return _rebuild(doc, name)
    if kind in READ_ONLY_KINDS:
        return LoadedResult(doc, name)
    if isinstance(doc, dict) and doc.get("type") == "FeatureCollection":
        raise ValueError(f"{name}: a GeoJSON export, not a dvoronoi result JSON (write the result with "
                         "to_json() or the CLI's -o FILE.json to load it back)")
    known = ", ".join(REBUILT_KINDS + READ_ONLY_KINDS)
    raise ValueError(f"{name}: not a dvoronoi result JSON: its \"kind\" is {kind!r}; known kinds: {known}")
