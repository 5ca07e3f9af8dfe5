"""librcsc's Delaunay-triangulation formation (``FormationDT``): a player's home position for a ball position.

agent2d's players take their positioning target from a formation trained on sample situations: for each sample, a
ball position and where every unum stands. librcsc triangulates the samples' ball positions (Delaunay) and, for a
focus point F inside the triangulation, interpolates the three samples of the triangle holding F; outside it, the
sample of the nearest ball position is used. HFO's base team reads ``normal-formation.conf``
(:mod:`hfo2d.agent2d.formation_data`).

Sources (facts, no code): librcsc d222758 ``rcsc/formation/formation_dt.cpp`` (train: the triangulation of the
sample ball points; getPosition / interpolate: the triangle search, the interpolation through the line from
vertex 0 and the nearest-vertex fallback), ``rcsc/geom/delaunay_triangulation.cpp`` (findTriangleContains: the
first triangle, by id, whose circumcircle's bounding square holds F and that holds F inside or on an edge;
findNearestVertex: the first nearest vertex in sample order), ``rcsc/geom/segment_2d.cpp`` (intersection with a
line, end points included), ``rcsc/formation/sample_data.cpp`` (coordinates rounded to 0.01 on reading).

The triangulation of these 115 points is unique (no four of them are co-circular where it matters), so the
triangles built here with Bowyer-Watson are librcsc's; only their order differs, which matters for a focus point
exactly on an edge, where both neighbouring triangles interpolate the same position.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence

from hfo2d.agent2d import formation_data

Point = tuple[float, float]

# librcsc Segment2D / Line2D tolerances
_EDGE_EPS = 1.0e-10  # DelaunayTriangulation::findTriangleContains: the cross products may be this far below 0
_LINE_EPS = 1.0e-10  # Line2D::EPSILON: parallel lines
_SEGMENT_CALC_ERROR = 1.0e-9  # Segment2D::CALC_ERROR: "on the segment" tolerance
_NEAR_VERTEX2 = 1.0e-5  # FormationDT::interpolate: F on vertex 0 when the intersection fails
GRID_CELL = (
    2.0  # m: the cell size of Formation's triangle index (an index only: any size gives the same results)
)
_CELL_MARGIN = (
    1.0e-6  # a triangle is listed in the cells its bounding box meets, widened by this (edge tolerance)
)


# Formation.position's memo: keyed by the focus point's bits (so that -0.0 and 0.0 stay apart), at most this big
_PACK_POINT = struct.Struct("<2d").pack
_MEMO_SIZE = 4096


def _round_sample(v: float) -> float:
    """librcsc SampleData reads each coordinate rounded to 0.01 (rint(v / 0.01) * 0.01)."""
    return round(v / 0.01) * 0.01


class _Triangle:
    """A triangle of ball points (vertex indices a, b, c, counter-clockwise) with its circumcircle."""

    __slots__ = ("a", "b", "c", "cx", "cy", "r2", "box")

    def __init__(self, pts: Sequence[Point], a: int, b: int, c: int) -> None:
        (ax, ay), (bx, by), (cx, cy) = pts[a], pts[b], pts[c]
        if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) < 0.0:
            b, c = c, b
            (bx, by), (cx, cy) = (cx, cy), (bx, by)
        self.a, self.b, self.c = a, b, c
        d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
        a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
        self.cx = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d
        self.cy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d
        self.r2 = (ax - self.cx) ** 2 + (ay - self.cy) ** 2
        r = math.sqrt(self.r2)
        self.box = (self.cx - r, self.cy - r, self.cx + r, self.cy + r)

    def in_circumcircle(self, x: float, y: float) -> bool:
        """Strictly inside (Lawson flips only for a point strictly inside the circumcircle)."""
        return (x - self.cx) ** 2 + (y - self.cy) ** 2 < self.r2 * (1.0 - 1.0e-12)


def delaunay(points: Sequence[Point]) -> list[tuple[int, int, int]]:
    """The Delaunay triangles of ``points`` (Bowyer-Watson insertion in the given order), as vertex indices,
    counter-clockwise. Points within 0.001 of an earlier one are dropped, as librcsc's addVertex does."""
    span = max(max(abs(x), abs(y)) for x, y in points) + 1.0
    big = 1.0e4 * span
    # a super-triangle far around every point; its three vertices get the indices n, n + 1, n + 2
    pts: list[Point] = list(points) + [(-big, -big), (big, -big), (0.0, big)]
    n = len(points)
    triangles = [_Triangle(pts, n, n + 1, n + 2)]
    kept: list[Point] = []
    for i in range(n):
        x, y = points[i]
        if any((x - kx) ** 2 + (y - ky) ** 2 < 1.0e-6 for kx, ky in kept):
            continue
        kept.append((x, y))
        edges: dict[tuple[int, int], int] = {}
        good: list[_Triangle] = []
        for t in triangles:
            if not t.in_circumcircle(x, y):
                good.append(t)
                continue
            for e in ((t.a, t.b), (t.b, t.c), (t.c, t.a)):
                key = (min(e), max(e))
                edges[key] = edges.get(key, 0) + 1
        triangles = good
        for (u, v), count in edges.items():
            if count == 1:  # an edge of the cavity's boundary
                triangles.append(_Triangle(pts, u, v, i))
    return [(t.a, t.b, t.c) for t in triangles if t.a < n and t.b < n and t.c < n]


class Formation:
    """A formation of samples (ball point, positions of unums 1..11) in the team's own frame (own goal at -52.5).

    :meth:`position` gives unum ``u``'s position for a focus point, as librcsc's FormationDT::getPosition.
    """

    def __init__(self, samples: Sequence[tuple[float, float, Sequence[Point]]]) -> None:
        if len(samples) < 3:
            raise ValueError(f"a Delaunay formation needs at least 3 samples, got {len(samples)}")
        self.ball_points: list[Point] = [(_round_sample(bx), _round_sample(by)) for bx, by, _ in samples]
        self.positions: list[tuple[Point, ...]] = [
            tuple((_round_sample(x), _round_sample(y)) for x, y in ps) for _, _, ps in samples
        ]
        self.unums = len(self.positions[0])
        self.triangles = delaunay(self.ball_points)
        self._memo: dict[tuple[int, bytes], Point] = {}
        pts = self.ball_points
        # A grid of GRID_CELL m cells over the samples' bounding box, each listing (in triangle order) the
        # triangles whose bounding box meets it: the search of librcsc's findTriangleContains (the first triangle,
        # in order, that holds F) then tests a few triangles instead of all of them.
        xs = [x for x, _ in pts]
        ys = [y for _, y in pts]
        self._grid_x0, self._grid_y0 = min(xs), min(ys)
        self._grid_nx = int((max(xs) - self._grid_x0) / GRID_CELL) + 1
        self._grid_ny = int((max(ys) - self._grid_y0) / GRID_CELL) + 1
        self._grid: list[list[tuple[int, int, int]]] = [[] for _ in range(self._grid_nx * self._grid_ny)]
        for a, b, c in self.triangles:
            tx = (pts[a][0], pts[b][0], pts[c][0])
            ty = (pts[a][1], pts[b][1], pts[c][1])
            i0, i1 = self._cell_x(min(tx) - _CELL_MARGIN), self._cell_x(max(tx) + _CELL_MARGIN)
            j0, j1 = self._cell_y(min(ty) - _CELL_MARGIN), self._cell_y(max(ty) + _CELL_MARGIN)
            for i in range(i0, i1 + 1):
                for j in range(j0, j1 + 1):
                    self._grid[i * self._grid_ny + j].append((a, b, c))

    def _cell_x(self, x: float) -> int:
        return min(max(int((x - self._grid_x0) // GRID_CELL), 0), self._grid_nx - 1)

    def _cell_y(self, y: float) -> int:
        return min(max(int((y - self._grid_y0) // GRID_CELL), 0), self._grid_ny - 1)

    def _find_triangle(self, fx: float, fy: float) -> tuple[int, int, int] | None:
        pts = self.ball_points
        if not (fx == fx and fy == fy):
            return None  # NaN: in no triangle
        for a, b, c in self._grid[self._cell_x(fx) * self._grid_ny + self._cell_y(fy)]:
            inside = True
            for u, v in ((a, b), (b, c), (c, a)):
                (ux, uy), (vx, vy) = pts[u], pts[v]
                if (vx - ux) * (fy - uy) - (vy - uy) * (fx - ux) < -_EDGE_EPS:
                    inside = False
                    break
            if inside:
                return a, b, c
        return None

    def _nearest_sample(self, fx: float, fy: float) -> int:
        best, best_d2 = 0, math.inf
        for i, (x, y) in enumerate(self.ball_points):
            d2 = (x - fx) ** 2 + (y - fy) ** 2
            if d2 < best_d2:
                best, best_d2 = i, d2
        return best

    def position(self, unum: int, fx: float, fy: float) -> Point:
        """Unum ``unum``'s formation position for the focus point (fx, fy).

        Memoised by unum and the focus point's bits (a resting ball, and with it the defenders' focus point,
        repeats from cycle to cycle); the position is a function of those alone."""
        if not 1 <= unum <= self.unums:
            raise ValueError(f"unum must be in 1..{self.unums}, got {unum!r}")
        key = (unum, _PACK_POINT(fx, fy))
        position = self._memo.get(key)
        if position is None:
            position = self._position(unum - 1, fx, fy)
            if len(self._memo) >= _MEMO_SIZE:
                self._memo.clear()
            self._memo[key] = position
        return position

    def _position(self, k: int, fx: float, fy: float) -> Point:
        """librcsc FormationDT::getPosition for the unum of index ``k`` (unum - 1)."""
        tri = self._find_triangle(fx, fy)
        if tri is None:
            return self.positions[self._nearest_sample(fx, fy)][k]
        a, b, c = tri
        (v0x, v0y), (v1x, v1y), (v2x, v2y) = self.ball_points[a], self.ball_points[b], self.ball_points[c]
        r0, r1, r2 = self.positions[a][k], self.positions[b][k], self.positions[c][k]
        hit = _segment_line_intersection(v1x, v1y, v2x, v2y, v0x, v0y, fx, fy)
        if hit is None:
            if (fx - v0x) ** 2 + (fy - v0y) ** 2 < _NEAR_VERTEX2:
                return r0
            return ((r0[0] + r1[0] + r2[0]) / 3.0, (r0[1] + r1[1] + r2[1]) / 3.0)
        ix, iy = hit
        d1i = math.hypot(v1x - ix, v1y - iy)
        d2i = math.hypot(v2x - ix, v2y - iy)
        w12 = d1i / (d1i + d2i)
        r12 = (r1[0] + (r2[0] - r1[0]) * w12, r1[1] + (r2[1] - r1[1]) * w12)
        d0b = math.hypot(v0x - fx, v0y - fy)
        dib = math.hypot(ix - fx, iy - fy)
        w = d0b / (d0b + dib)
        return (r0[0] + (r12[0] - r0[0]) * w, r0[1] + (r12[1] - r0[1]) * w)


def _segment_line_intersection(
    sx1: float, sy1: float, sx2: float, sy2: float, lx1: float, ly1: float, lx2: float, ly2: float
) -> Point | None:
    """librcsc Segment2D::intersection(Line2D): the point where the line through (lx1, ly1), (lx2, ly2) meets the
    segment (end points included, within CALC_ERROR), or None."""
    # Line2D(p1, p2): a x + b y + c = 0 with a = -(y2 - y1), b = x2 - x1, c = -a x1 - b y1
    a1, b1 = -(sy2 - sy1), sx2 - sx1
    c1 = -a1 * sx1 - b1 * sy1
    a2, b2 = -(ly2 - ly1), lx2 - lx1
    c2 = -a2 * lx1 - b2 * ly1
    tmp = a1 * b2 - a2 * b1
    if abs(tmp) < _LINE_EPS:
        return None
    x = (b1 * c2 - b2 * c1) / tmp
    y = (a2 * c1 - a1 * c2) / tmp
    # Segment2D::contains: within the segment's bounding box, with the tolerance
    if (
        min(sx1, sx2) - _SEGMENT_CALC_ERROR <= x <= max(sx1, sx2) + _SEGMENT_CALC_ERROR
        and min(sy1, sy2) - _SEGMENT_CALC_ERROR <= y <= max(sy1, sy2) + _SEGMENT_CALC_ERROR
    ):
        return (x, y)
    return None


_NORMAL: Formation | None = None


def normal_formation() -> Formation:
    """HFO's base team formation in PlayOn (``normal-formation.conf``), built once."""
    global _NORMAL
    if _NORMAL is None:
        _NORMAL = Formation(formation_data.SAMPLES)
    return _NORMAL
