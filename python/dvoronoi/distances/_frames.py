"""Elwin, Freeman & Lynch's second communication round: transformations between neighbouring robots'
local frames, and localisation of the team from one robot's pose (RA-L 2017, Sections I and IV-A:
"By transmitting these coordinates, in sequence, the robots can find the translation, rotation, and
flip between neighboring coordinate systems").

Every robot has local coordinates of its Voronoi neighbours (:meth:`DistanceNeighbors.region`: the
robot at the origin, its first path neighbour on +x, the path turning counter-clockwise). In the second
round robot i sends each Voronoi neighbour the list ``(robot, x, y)`` of its path in that order. Robot
i then fits, for each neighbour j, the rigid motion ``x_i = Q x_j + t`` (Q orthogonal: a rotation, or a
rotation after a reflection) over the robots both frames place — i, j and their common neighbours (the
apexes of the Delaunay triangles on edge ij): an orthogonal Procrustes fit with reflection allowed,
exact (up to rounding) when the distances are, least squares when they are noisy.

Everything is vectorised with numpy over all robots and directed Voronoi edges, O(sum over robots of
degree x path length); for 1e5 robots (about 6e5 directed edges) the fits take about 3 s and
`localize` 0.2 s on one core of the development machine.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence, Tuple

import numpy as np

__all__ = ["FrameTransform", "FrameTransforms", "SecondRound"]

#: A fit is defined when the robots both frames place are not all on one line: 1 - |sum z^2| / sum |z|^2
#: of their centred coordinates (0 on a line, 1 for an isotropic spread) must exceed this in both frames.
PLANARITY_TOL = 1e-12


@dataclass(frozen=True)
class FrameTransform:
    """The rigid motion taking robot ``neighbor``'s local frame to robot ``robot``'s:
    ``x_robot = rotation @ x_neighbor + translation``.

    ``rotation`` is orthogonal with determinant +1, or -1 when ``flip`` (the two local frames have
    opposite handedness). ``residual`` is the root-mean-square misfit (distance units) over the
    ``common`` robots the fit used (both frames place them): 0 up to rounding for exact distances.
    ``valid`` is False (and the arrays NaN) when fewer than three common robots, or only collinear
    ones, leave the flip undetermined, or when ``neighbor`` sent no coordinates to ``robot``.
    """

    robot: int
    neighbor: int
    rotation: np.ndarray
    translation: np.ndarray
    flip: bool
    residual: float
    common: np.ndarray
    valid: bool

    def apply(self, xy: Any) -> np.ndarray:
        """Map points given in the neighbour's frame (``(m, 2)`` or ``(2,)``) to the robot's frame."""
        xy = np.asarray(xy, dtype=np.float64)
        return xy @ self.rotation.T + self.translation


@dataclass(frozen=True)
class FrameTransforms:
    """All second-round transforms, one per directed Voronoi edge, aligned with the result's CSR
    arrays: entry ``k`` maps the frame of robot ``indices[k]`` into the frame of the robot whose row
    holds ``k``. Fields as in :class:`FrameTransform` (``rotation`` ``(E, 2, 2)``, ``translation``
    ``(E, 2)``, ``flip``, ``residual``, ``valid`` ``(E,)``, ``common`` the number of common robots)."""

    rotation: np.ndarray
    translation: np.ndarray
    flip: np.ndarray
    residual: np.ndarray
    common: np.ndarray
    valid: np.ndarray


@dataclass(frozen=True)
class SecondRound:
    """Messages of the second round. Robot i sends one message to each robot of its row (its Voronoi
    neighbours), carrying its path in order as ``payload[i]`` entries (a robot ID and two
    coordinates each).

    Counted as docs/spec.md counts transmissions: sent as unicasts, one transmission and one link
    delivery per directed Voronoi edge (``total_transmissions == total_deliveries == messages``).
    Robot i's message is the same for every neighbour, so a radio could broadcast it once instead:
    ``broadcasts`` transmissions (one per robot that has a neighbour).
    """

    sent: np.ndarray       #: (n,) messages robot i sends (its row length)
    received: np.ndarray   #: (n,) messages robot i receives
    payload: np.ndarray    #: (n,) entries (ID, x, y) in each message of robot i (its path length)

    @property
    def messages(self) -> int:
        """Messages: one per directed Voronoi edge."""
        return int(self.sent.sum())

    @property
    def total_transmissions(self) -> int:
        """Radio sends with unicasts (one per message)."""
        return self.messages

    @property
    def total_deliveries(self) -> int:
        """Link deliveries: one per message per link that receives it."""
        return int(self.received.sum())

    @property
    def broadcasts(self) -> int:
        """Transmissions if each robot broadcasts its one message once instead."""
        return int(np.count_nonzero(self.sent))

    @property
    def total_payload(self) -> int:
        """Coordinate entries delivered, summed over all messages."""
        return int(np.dot(self.sent, self.payload))

    def __repr__(self) -> str:
        return (f"SecondRound(robots={len(self.sent)}, messages={self.messages}, broadcasts={self.broadcasts}, "
                f"total_payload={self.total_payload})")


class Frames:
    """Local coordinates, second-round fits and edge lookups of one DistanceNeighbors result."""

    def __init__(self, n: int, indptr: np.ndarray, indices: np.ndarray, path_length: np.ndarray, graph: Any) -> None:
        self.n = n
        self.indptr = np.asarray(indptr, dtype=np.int64)
        self.indices = np.asarray(indices, dtype=np.int64)
        self.path_length = np.asarray(path_length, dtype=np.int64)
        deg = np.diff(self.indptr)
        self.erow = np.repeat(np.arange(n, dtype=np.int64), deg)
        ekeys = self.erow * n + self.indices
        self._eperm = np.argsort(ekeys, kind="stable")
        self._ekeys = ekeys[self._eperm]
        self._local_coordinates(graph)
        self._fit()

    # ---------------------------------------------------------------------------- lookups
    def edge(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """CSR positions of the directed edges (i, j), -1 where j is not in row i."""
        q = np.asarray(i, dtype=np.int64) * self.n + np.asarray(j, dtype=np.int64)
        pos = np.minimum(np.searchsorted(self._ekeys, q), max(len(self._ekeys) - 1, 0))
        hit = (self._ekeys[pos] == q) if len(self._ekeys) else np.zeros(np.shape(q), bool)
        return np.where(hit, self._eperm[pos] if len(self._eperm) else -1, -1)

    def measured_sq(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Measured squared distances of the pairs (a, b), NaN where not measured."""
        q = a * self.n + b
        if len(self._gkeys) == 0:
            return np.full(np.shape(q), np.nan)
        pos = np.minimum(np.searchsorted(self._gkeys, q), len(self._gkeys) - 1)
        return np.where(self._gkeys[pos] == q, self._gval[pos], np.nan)

    def _local_coordinates(self, graph: Any) -> None:
        """Every robot's path neighbours in its local frame, as LocalRegion.positions (local_region.hpp):
        the law of cosines on consecutive path triangles, angles summed along the path."""
        n = self.n
        gptr = np.asarray(graph.indptr, dtype=np.int64)
        gkeys = np.repeat(np.arange(n, dtype=np.int64), np.diff(gptr)) * n + np.asarray(graph.indices, dtype=np.int64)
        gval = np.asarray(graph.values, dtype=np.float64)
        if not graph.squared:
            gval = gval * gval

        self._gkeys, self._gval = gkeys, gval
        sq = self.measured_sq

        plen = self.path_length
        owner = np.repeat(np.arange(n, dtype=np.int64), plen)
        first = np.repeat(self.indptr[:-1], plen)
        t = np.arange(len(owner), dtype=np.int64) - np.repeat(np.cumsum(plen) - plen, plen)
        flat = first + t
        member = self.indices[flat]
        b = sq(owner, member)
        ang = np.zeros(len(owner))
        later = np.flatnonzero(t > 0)
        if len(later):
            prev = member[later - 1]
            a, c = sq(owner[later], prev), sq(prev, member[later])
            with np.errstate(invalid="ignore", divide="ignore"):
                ang[later] = np.arccos(np.clip((a + b[later] - c) / (2.0 * np.sqrt(a * b[later])), -1.0, 1.0))
        # theta along each path, summed left to right as local_region.hpp does (one step per position).
        theta = np.zeros(len(owner))
        order = np.argsort(t, kind="stable")
        bounds = np.searchsorted(t[order], np.arange(1, int(plen.max(initial=0)) + 1))
        for s in range(1, len(bounds)):
            sel = order[bounds[s - 1]: bounds[s]]
            theta[sel] = theta[sel - 1] + ang[sel]
        d = np.sqrt(b)
        z = d * np.cos(theta) + 1j * (d * np.sin(theta))
        # Table: every robot places itself (origin) and its path neighbours; sorted by (owner, member).
        tab_owner = np.concatenate([np.arange(n, dtype=np.int64), owner])
        tab_member = np.concatenate([np.arange(n, dtype=np.int64), member])
        tab_z = np.concatenate([np.zeros(n, complex), z])
        perm = np.argsort(tab_owner * n + tab_member, kind="stable")
        self.tab_keys = (tab_owner * n + tab_member)[perm]
        self.tab_member = tab_member[perm]
        self.tab_z = tab_z[perm]
        self.tab_ptr = np.concatenate([[0], np.cumsum(1 + plen)]).astype(np.int64)

    def _fit(self) -> None:
        """Orthogonal Procrustes (reflection allowed) per directed edge over the common robots."""
        n, E = self.n, len(self.indices)
        u, v = self.erow, self.indices            # edge k: robot u fits v's frame into its own
        L = self.tab_ptr[u + 1] - self.tab_ptr[u]  # u's table: itself + its path
        eid = np.repeat(np.arange(E, dtype=np.int64), L)
        within = np.arange(int(L.sum()), dtype=np.int64) - np.repeat(np.cumsum(L) - L, L)
        src = self.tab_ptr[u][eid] + within
        mem = self.tab_member[src]
        a = self.tab_z[src]                        # coordinates in u's frame
        q = v[eid] * n + mem
        pos = np.minimum(np.searchsorted(self.tab_keys, q), len(self.tab_keys) - 1) if len(q) else q
        keep = (self.tab_keys[pos] == q) if len(q) else np.zeros(0, bool)
        b = self.tab_z[pos]                        # the same robots in v's frame (v's message)
        keep &= np.isfinite(a) & np.isfinite(b)
        eid, a, b, mem = eid[keep], a[keep], b[keep], mem[keep]

        def gsum(w: np.ndarray) -> np.ndarray:
            if np.iscomplexobj(w):
                return np.bincount(eid, w.real, E) + 1j * np.bincount(eid, w.imag, E)
            return np.bincount(eid, w, E)

        cnt = np.bincount(eid, minlength=E)
        with np.errstate(invalid="ignore", divide="ignore"):
            abar, bbar = gsum(a) / cnt, gsum(b) / cnt
            ac, bc = a - abar[eid], b - bbar[eid]
            s_rot, s_flip = gsum(ac * np.conj(bc)), gsum(ac * bc)
            pa = 1.0 - np.abs(gsum(ac * ac)) / gsum(np.abs(ac) ** 2)
            pb = 1.0 - np.abs(gsum(bc * bc)) / gsum(np.abs(bc) ** 2)
            flip = np.abs(s_flip) > np.abs(s_rot)
            s = np.where(flip, s_flip, s_rot)
            c = s / np.abs(s)
            tr = abar - c * np.where(flip, np.conj(bbar), bbar)
            fit = c[eid] * np.where(flip[eid], np.conj(b), b) + tr[eid]
            resid = np.sqrt(gsum(np.abs(a - fit) ** 2) / cnt)
        sent_back = self.edge(v, u) >= 0           # v sends its coordinates to u only if u is in v's row
        planar = (cnt >= 3) & (np.minimum(pa, pb) > PLANARITY_TOL)
        valid = sent_back & planar & (np.abs(s) > 0)
        # Collinear common robots (i and j alone: four cocircular robots, whose diagonal is no Voronoi
        # edge, e.g. on lattices) fix the rotation up to the flip; a measured distance between a robot
        # only u places and one only v places decides it (beyond the paper).
        line = np.flatnonzero(sent_back & ~planar & (cnt >= 2) & (np.abs(s_rot) > 0))
        if len(line):
            f2, ok = self._flip_by_distance(line, u[line], v[line], s_rot[line], s_flip[line], abar[line], bbar[line])
            flip[line] = f2
            c[line] = np.where(f2, s_flip[line], s_rot[line]) / np.abs(s_rot[line])
            tr[line] = abar[line] - c[line] * np.where(f2, np.conj(bbar[line]), bbar[line])
            fit = c[eid] * np.where(flip[eid], np.conj(b), b) + tr[eid]
            with np.errstate(invalid="ignore", divide="ignore"):
                resid = np.sqrt(gsum(np.abs(a - fit) ** 2) / cnt)
            valid[line] = ok
        self.c = np.where(valid, c, np.nan)
        self.t = np.where(valid, tr, np.nan)
        self.flip = flip & valid
        self.residual = np.where(valid, resid, np.nan)
        self.count = cnt.astype(np.int64)
        self.valid = valid
        self._common = (eid, mem)

    def _flip_by_distance(self, e, u, v, s_rot, s_flip, abar, bbar):
        """For edges e (u fits v's frame) whose common robots are collinear: under each flip, map
        every robot of v's table into u's frame and compare its distance to every robot of u's table
        with the measurement; the pair that tells the two hypotheses apart best decides."""
        n = self.n
        lu = self.tab_ptr[u + 1] - self.tab_ptr[u]
        lv = self.tab_ptr[v + 1] - self.tab_ptr[v]
        m = lu * lv
        g = np.repeat(np.arange(len(e), dtype=np.int64), m)
        w = np.arange(int(m.sum()), dtype=np.int64) - np.repeat(np.cumsum(m) - m, m)
        iu = self.tab_ptr[u][g] + w // lv[g]
        iv = self.tab_ptr[v][g] + w % lv[g]
        ru, rv = self.tab_member[iu], self.tab_member[iv]
        # u and v lie on the line of the common robots: distances to them cannot tell a flip.
        off = (ru != rv) & (ru != u[g]) & (ru != v[g]) & (rv != u[g]) & (rv != v[g])
        g, iu, iv, ru, rv = g[off], iu[off], iv[off], ru[off], rv[off]
        meas = np.sqrt(self.measured_sq(ru, rv))
        za, zb = self.tab_z[iu], self.tab_z[iv]
        c_rot, c_flip = s_rot / np.abs(s_rot), s_flip / np.abs(s_flip)
        p_rot = np.abs(za - (c_rot[g] * (zb - bbar[g]) + abar[g]))
        p_flip = np.abs(za - (c_flip[g] * np.conj(zb - bbar[g]) + abar[g]))
        gap = np.abs(p_rot - p_flip)
        gap = np.where(np.isfinite(meas) & np.isfinite(gap), gap, -1.0)
        best = np.full(len(e), -1, np.int64)
        if len(g):                                    # g is grouped: the largest gap of each group
            starts = np.flatnonzero(np.r_[True, g[1:] != g[:-1]])
            top = np.maximum.reduceat(gap, starts)
            at = np.flatnonzero((gap == np.repeat(top, np.diff(np.r_[starts, len(g)]))) & (gap >= 0))
            first = at[np.r_[True, g[at][1:] != g[at][:-1]]]
            best[g[first]] = first
        has = best >= 0
        k = np.where(has, best, 0)
        scale = np.abs(za[k]) + np.abs(zb[k]) + np.abs(abar) + np.abs(bbar)
        ok = has & (gap[k] > 1e-12 * scale)
        flip = ok & (np.abs(p_flip[k] - meas[k]) < np.abs(p_rot[k] - meas[k]))
        return flip, ok

    # ---------------------------------------------------------------------------- results
    def rotation_matrices(self, k: np.ndarray) -> np.ndarray:
        c, f = self.c[k], self.flip[k]
        cr, ci = c.real, c.imag
        rot = np.empty(np.shape(k) + (2, 2))
        rot[..., 0, 0] = cr
        rot[..., 1, 0] = ci
        rot[..., 0, 1] = np.where(f, ci, -ci)
        rot[..., 1, 1] = np.where(f, -cr, cr)
        return rot

    def transform(self, i: int, j: int) -> FrameTransform:
        k = int(self.edge(np.array([i]), np.array([j]))[0])
        if k < 0:
            raise ValueError(f"robots {i} and {j} are not Voronoi neighbours (j is not in row i)")
        eid, mem = self._common
        lo, hi = np.searchsorted(eid, [k, k + 1])
        t = self.t[k]
        return FrameTransform(i, j, self.rotation_matrices(np.array(k)), np.array([t.real, t.imag]),
                              bool(self.flip[k]), float(self.residual[k]), np.sort(mem[lo:hi]), bool(self.valid[k]))

    def all_transforms(self) -> FrameTransforms:
        k = np.arange(len(self.indices))
        return FrameTransforms(self.rotation_matrices(k), np.column_stack([self.t.real, self.t.imag]),
                               self.flip.copy(), self.residual.copy(), self.count.copy(), self.valid.copy())

    def two_hop(self, i: int) -> Tuple[np.ndarray, np.ndarray]:
        """Robots i or its neighbours place, in i's frame (mean where several neighbours place one)."""
        lo, hi = self.tab_ptr[i], self.tab_ptr[i + 1]
        ids, zs = [self.tab_member[lo:hi]], [self.tab_z[lo:hi]]
        for k in range(int(self.indptr[i]), int(self.indptr[i + 1])):
            if not self.valid[k]:
                continue
            j = int(self.indices[k])
            a, b = self.tab_ptr[j], self.tab_ptr[j + 1]
            z = self.tab_z[a:b]
            ids.append(self.tab_member[a:b])
            zs.append(self.c[k] * (np.conj(z) if self.flip[k] else z) + self.t[k])
        idv, zv = np.concatenate(ids), np.concatenate(zs)
        own = np.zeros(len(idv), bool)
        own[: hi - lo] = True
        # i's own coordinates where it has them; the neighbours' mean for the others.
        known = np.isin(idv, idv[own])
        idv, zv = np.concatenate([idv[own], idv[~known]]), np.concatenate([zv[own], zv[~known]])
        uniq, inv = np.unique(idv, return_inverse=True)
        cnt = np.bincount(inv, minlength=len(uniq))
        mean = (np.bincount(inv, zv.real, len(uniq)) + 1j * np.bincount(inv, zv.imag, len(uniq))) / cnt
        return uniq.astype(np.int64), np.column_stack([mean.real, mean.imag])

    def second_round(self) -> SecondRound:
        sent = np.diff(self.indptr)
        received = np.bincount(self.indices, minlength=self.n).astype(np.int64)
        return SecondRound(sent.astype(np.int64), received, self.path_length.copy())

    def localize(self, anchor: int, position: Tuple[float, float], heading: float, flip: bool) -> np.ndarray:
        """Chain the transforms breadth-first from the anchor (fewest hops, through valid fits only)."""
        import scipy.sparse as sp
        from scipy.sparse.csgraph import shortest_path

        n = self.n
        k = np.flatnonzero(self.valid)
        g = sp.csr_matrix((np.ones(len(k)), (self.erow[k], self.indices[k])), shape=(n, n))
        hops, pred = shortest_path(g, method="D", directed=True, unweighted=True, indices=anchor,
                                   return_predecessors=True)
        gc = np.full(n, complex(np.nan, np.nan))
        gt = np.full(n, complex(np.nan, np.nan))
        gf = np.zeros(n, bool)
        gc[anchor], gt[anchor], gf[anchor] = np.exp(1j * heading), complex(*position), bool(flip)
        reached = np.flatnonzero(np.isfinite(hops) & (np.arange(n) != anchor))
        order = reached[np.argsort(hops[reached], kind="stable")]
        levels = np.searchsorted(hops[order], np.arange(1, int(hops[order].max(initial=0)) + 1), side="right")
        lo = 0
        for hi in levels:
            v = order[lo:hi]
            w = pred[v]
            e = self.edge(w, v)                    # w's fit of v's frame into w's
            ce, te, fe = self.c[e], self.t[e], self.flip[e]
            fw = gf[w]
            gc[v] = gc[w] * np.where(fw, np.conj(ce), ce)
            gt[v] = gc[w] * np.where(fw, np.conj(te), te) + gt[w]
            gf[v] = fw ^ fe
            lo = hi
        return np.column_stack([gt.real, gt.imag])


def check_pose(position: Sequence[float], heading: float) -> Tuple[Tuple[float, float], float]:
    p = np.asarray(position, dtype=np.float64)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"position must be two finite numbers (x, y), got {position!r}")
    h = float(heading)
    if not np.isfinite(h):
        raise ValueError(f"heading must be a finite angle in radians, got {heading!r}")
    return (float(p[0]), float(p[1])), h
