"""Voronoi neighbours from inter-robot distances only (Elwin, Freeman & Lynch, RA-L 2017).

>>> import dvoronoi as dv
>>> e = dv.distances.measure(points, radius=33.0, model="rssi", seed=1)   # simulated measurements
>>> res = dv.neighbors_from_distances(e)                                 # + consistency step
>>> res.neighbors(0), res.on_hull[0], res.region(0).vertices
>>> res.frame_transform(0, res.neighbors(0)[0]), res.localize(anchor=0, position=(1.0, 2.0), heading=0.3)
>>> dv.distances.delaunay_distortion(points, res), dv.distances.detection_distortion(points, e)
"""
from .. import _core
from ._neighbors import DistanceNeighbors, LocalRegion, as_distance_graph, neighbors_from_distances
from ._frames import FrameTransform, FrameTransforms, SecondRound
from .distortion import delaunay_distortion, detection_distortion, distortion, true_weights
from .noise import detection_pairs, distance_to_rssi, measure, rssi_to_distance

circumradius = _core.circumradius
signed_circumradius = _core.signed_circumradius
obtuse = _core.obtuse
opposite_sides = _core.opposite_sides

__all__ = [
    "neighbors_from_distances", "DistanceNeighbors", "LocalRegion", "as_distance_graph",
    "FrameTransform", "FrameTransforms", "SecondRound",
    "measure", "detection_pairs", "rssi_to_distance", "distance_to_rssi",
    "distortion", "detection_distortion", "delaunay_distortion", "true_weights",
    "circumradius", "signed_circumradius", "obtuse", "opposite_sides",
]
