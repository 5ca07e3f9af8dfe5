"""librcsc's Delaunay-triangulation formation over HFO's normal-formation.conf (hfo2d.agent2d.formation)."""

from __future__ import annotations

import numpy as np
import pytest

from hfo2d.agent2d import formation_data
from hfo2d.agent2d.formation import Formation, delaunay, normal_formation

# Positions of unums 2..5 (DF) for focus points F, printed to 3 decimals by librcsc's own FormationDT
# (rcsc/formation, rcsc/geom at d222758, compiled unchanged) reading HFO b8b2a1d's normal-formation.conf.
LIBRCSC_REFERENCE = {
    (0.0, 0.0): [(-15.530, -5.420), (-15.530, 5.420), (-11.560, -15.780), (-11.560, 15.780)],
    (-10.0, 0.0): [(-18.833, -4.384), (-18.833, 4.384), (-18.839, -15.104), (-18.839, 15.104)],
    (-20.0, 10.0): [(-27.494, 0.468), (-26.747, 9.630), (-27.581, -8.659), (-27.761, 17.888)],
    (-30.0, -15.0): [(-37.145, -9.895), (-37.337, -2.622), (-36.465, -16.944), (-36.677, 4.518)],
    (-36.0, 0.0): [(-42.360, -1.960), (-42.360, 1.960), (-41.376, -7.222), (-41.376, 7.222)],
    (-40.0, 20.0): [(-43.556, 3.287), (-44.022, 9.162), (-43.393, -2.899), (-43.027, 15.899)],
    (-45.0, -15.0): [(-45.679, -7.017), (-45.365, -1.568), (-45.883, -12.455), (-46.040, 3.546)],
    (-50.0, 5.0): [(-46.901, -1.288), (-46.976, 4.016), (-48.384, -5.353), (-48.365, 8.066)],
    (-5.0, 30.0): [(-16.594, 5.269), (-15.736, 19.510), (-11.637, -9.344), (-14.776, 28.100)],
    (-25.0, -33.0): [(-32.113, -16.667), (-30.537, -4.313), (-30.910, -26.976), (-29.750, 7.986)],
    # outside the hull [-54.5, 54.5] x [-36, 36]: the nearest sample's positions
    (-55.0, 3.0): [(-47.530, -3.170), (-47.530, 3.170), (-49.990, -6.880), (-49.990, 6.880)],
    (-53.0, -37.0): [(-46.240, -10.290), (-44.480, -1.690), (-48.450, -21.850), (-48.060, 2.310)],
}


def test_the_triangulation_is_delaunay_with_librcscs_220_triangles() -> None:
    f = normal_formation()
    assert len(f.ball_points) == 115
    assert len(f.triangles) == 220  # as librcsc's DelaunayTriangulation (and Qhull) build it
    pts = f.ball_points
    for a, b, c in f.triangles:
        (ax, ay), (bx, by), (cx, cy) = pts[a], pts[b], pts[c]
        assert (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) > 0.0  # counter-clockwise, not degenerate
        # the empty-circumcircle property: no sample strictly inside
        d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
        ux = (
            (ax * ax + ay * ay) * (by - cy)
            + (bx * bx + by * by) * (cy - ay)
            + (cx * cx + cy * cy) * (ay - by)
        ) / d
        uy = (
            (ax * ax + ay * ay) * (cx - bx)
            + (bx * bx + by * by) * (ax - cx)
            + (cx * cx + cy * cy) * (bx - ax)
        ) / d
        r2 = (ax - ux) ** 2 + (ay - uy) ** 2
        for i, (px, py) in enumerate(pts):
            if i not in (a, b, c):
                assert (px - ux) ** 2 + (py - uy) ** 2 >= r2 * (1.0 - 1e-9)


@pytest.mark.parametrize("focus", list(LIBRCSC_REFERENCE))
def test_positions_match_librcscs_formation(focus: tuple[float, float]) -> None:
    f = normal_formation()
    for unum, expected in zip(range(2, 6), LIBRCSC_REFERENCE[focus], strict=True):
        assert f.position(unum, *focus) == pytest.approx(expected, abs=6e-4)


def test_a_sample_ball_point_gives_that_samples_positions() -> None:
    f = normal_formation()
    for bx, by, positions in formation_data.SAMPLES[:40]:
        for unum in (2, 4, 6, 11):
            assert f.position(unum, bx, by) == pytest.approx(positions[unum - 1], abs=1e-9)


def test_the_formation_is_mirror_symmetric_for_the_mirrored_roles() -> None:
    # unum 3 mirrors 2 and 5 mirrors 4 (the file's symmetry column): a mirrored ball mirrors their positions
    f = normal_formation()
    for fx, fy in [(-12.3, 7.7), (-41.0, -3.2), (-28.0, 21.0)]:
        x2, y2 = f.position(2, fx, fy)
        x3, y3 = f.position(3, fx, -fy)
        assert (x3, y3) == pytest.approx((x2, -y2), abs=1e-6)


def test_bad_inputs_raise() -> None:
    f = normal_formation()
    with pytest.raises(ValueError, match="unum"):
        f.position(12, 0.0, 0.0)
    with pytest.raises(ValueError, match="unum"):
        f.position(0, 0.0, 0.0)
    with pytest.raises(ValueError, match="at least 3 samples"):
        Formation(formation_data.SAMPLES[:2])


def test_delaunay_of_a_square_with_its_centre() -> None:
    tris = delaunay([(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0), (1.0, 1.0)])
    assert len(tris) == 4 and all(4 in t for t in tris)


def test_the_triangle_index_finds_what_a_search_of_every_triangle_finds() -> None:
    # librcsc's findTriangleContains: the first triangle, in order, holding F (on an edge within 1e-10)
    f = normal_formation()
    pts = f.ball_points

    def first_holding(fx: float, fy: float) -> tuple[int, int, int] | None:
        for a, b, c in f.triangles:
            if all(
                (pts[v][0] - pts[u][0]) * (fy - pts[u][1]) - (pts[v][1] - pts[u][1]) * (fx - pts[u][0])
                >= -1e-10
                for u, v in ((a, b), (b, c), (c, a))
            ):
                return a, b, c
        return None

    rng = np.random.default_rng(0)
    focus = list(zip(rng.uniform(-58.0, 58.0, 2000), rng.uniform(-40.0, 40.0, 2000), strict=True)) + pts
    assert all(f._find_triangle(fx, fy) == first_holding(fx, fy) for fx, fy in focus)
