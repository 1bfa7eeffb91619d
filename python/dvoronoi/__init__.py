"""dvoronoi: exact range-limited Voronoi cells for multi-robot systems.

>>> import dvoronoi as dv
>>> part = dv.limited_cells(dv.datasets.intel_lab(), radius=3.0)
>>> part.neighbors(0), part.areas[0], part.cell(0).pieces

One agent's cell from the positions it knows (a robot's control step):

>>> cell = dv.limited_cell(center, others, radius)
>>> cell.neighbors, cell.area, cell.centroid

Every result answers in the same shape: ``neighbors(i)``, CSR ``indptr``/``indices``, ``areas``,
``centroids``, ``cell(i)``, ``to_json()``, ``to_geojson()``, ``plot()``, ``__geo_interface__``,
``to_shapely()``, ``to_geopandas()``; ``dv.load(path)`` reads a result JSON back.
"""
from ._core import CoincidentError, LimitedCell, Piece, __version__, limited_cell
from ._partition import LimitedPartition, limited_cells
from ._core import ClippedCell, VoronoiCell, VoronoiEdge
from ._voronoi import VoronoiPartition, voronoi_cell, voronoi_cells
from . import datasets
from .gvd import GridVoronoi, grid_voronoi, obstacles_from_occupancy_grid
from .occupancy import OccupancyGrid, OccupancyVoronoi
from . import distances
from .distances import DistanceNeighbors, neighbors_from_distances
from . import coverage
from . import network
from ._load import LoadedResult, load

__all__ = [
    "limited_cell",
    "limited_cells",
    "LimitedCell",
    "LimitedPartition",
    "voronoi_cell",
    "voronoi_cells",
    "VoronoiPartition",
    "VoronoiCell",
    "VoronoiEdge",
    "ClippedCell",
    "Piece",
    "CoincidentError",
    "datasets",
    "grid_voronoi",
    "GridVoronoi",
    "obstacles_from_occupancy_grid",
    "OccupancyGrid",
    "OccupancyVoronoi",
    "distances",
    "neighbors_from_distances",
    "DistanceNeighbors",
    "coverage",
    "network",
    "load",
    "LoadedResult",
    "__version__",
]
