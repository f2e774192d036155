"""Exact triangle-triangle intersection on integer coordinates, in plain
Python: the oracle the cocotb test checks every verdict of the pipeline
against.

It is written independently of the pipeline's algorithm (Devillers-Guigue):
two closed convex sets are disjoint if and only if some axis separates
their projections strictly, and for two triangles (degenerate ones, that is
segments and points, included) the direction between their closest points
is always one of a finite set of candidates, each computed here from the
vertices with integer arithmetic only:

- a triangle's normal (closest point inside a face);
- the cross product of an edge of one with an edge of the other
  (closest points inside two edges that are not parallel);
- the difference of a vertex of one and a vertex of the other
  (closest points at two vertices);
- e x (e x d) for an edge e of either and such a difference d (closest
  point inside an edge, the other at a vertex or inside a parallel edge:
  the component of d perpendicular to e).

Python's integers have no overflow, so every comparison is exact.
"""

from itertools import product


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def edges(t):
    return [sub(t[(i + 1) % 3], t[i]) for i in range(3)]


def candidate_axes(t1, t2):
    e1, e2 = edges(t1), edges(t2)
    differences = [sub(q, p) for p, q in product(t1, t2)]
    yield cross(e1[0], e1[1])
    yield cross(e2[0], e2[1])
    for e, f in product(e1, e2):
        yield cross(e, f)
    yield from differences
    for e, d in product(e1 + e2, differences):
        yield cross(e, cross(e, d))


def separates(axis, t1, t2):
    p1 = [dot(axis, v) for v in t1]
    p2 = [dot(axis, v) for v in t2]
    return max(p1) < min(p2) or max(p2) < min(p1)


def intersects(t1, t2):
    """True when the closed triangles t1 and t2 (three integer 3-vectors
    each) share a point; touching, coplanar and degenerate triangles
    included."""
    return not any(axis != (0, 0, 0) and separates(axis, t1, t2) for axis in candidate_axes(t1, t2))


if __name__ == "__main__":
    # Hand-made cases (a crossing, coplanar contacts, degenerate triangles),
    # whose answers `tritri classify --arith exact` gives: a check of this oracle.
    a0 = ((0, 0, 0), (100, 0, 0), (0, 100, 0))
    assert intersects(a0, ((10, 10, -50), (10, 10, 50), (60, 20, 0)))        # crossing
    assert intersects(a0, ((50, 50, 0), (150, 50, 0), (50, 150, 0)))         # coplanar, one point
    assert not intersects(a0, ((51, 50, 0), (150, 50, 0), (51, 150, 0)))     # coplanar, apart
    assert intersects(a0, ((100, 0, 0),) * 3)                                # a point on a vertex
    assert not intersects(a0, ((-10, -10, -5), (-10, -10, 5), (-10, -10, 0)))  # a segment beside it
    print("exact.py: self-check passed")
