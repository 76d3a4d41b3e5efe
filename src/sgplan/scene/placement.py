"""Greedy placement of text labels that must not cover markers or each other (display pixels).

A :class:`LabelPlacer` holds the boxes already taken (markers, placed labels) and, optionally, points
that labels should rather not cover (a drawn path). :meth:`LabelPlacer.place` tries the anchor itself,
then centres on square rings of growing size around it, and keeps the first free one with the
fewest soft points under it; with no free spot inside the bounds it takes the least-overlapping one.
Boxes are ``(x0, y0, x1, y1)`` with ``x0 <= x1`` and ``y0 <= y1``; units are whatever the caller uses
(matplotlib display pixels in :mod:`sgplan.scene.draw`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

Box = tuple[float, float, float, float]

_RING_SCALES = (1.0, 1.5, 2.2, 3.0, 4.0, 5.5)
"""Ring sizes, in units of the smallest ring (the box just clearing its anchor)."""
_ANGLES = np.deg2rad(np.arange(0, 360, 22.5))
_SOFT_WEIGHT = 0.15
"""Score of one covered soft point, against 1 per ring: covering ~7 path points costs one ring."""
_SOFT_CAP = 20


def _ring_offsets() -> np.ndarray:
    """``(k, 3)`` rows ``(unit_dx, unit_dy, ring)``: directions scaled onto a unit square, ring index."""
    cos, sin = np.cos(_ANGLES), np.sin(_ANGLES)
    m = np.maximum(np.abs(cos), np.abs(sin))
    rows = [np.zeros((1, 3))]
    for ring, scale in enumerate(_RING_SCALES, start=1):
        rows.append(np.column_stack([cos / m * scale, sin / m * scale, np.full(len(cos), ring)]))
    return np.concatenate(rows)


_OFFSETS = _ring_offsets()


@dataclass
class LabelPlacer:
    """Places labels one at a time inside ``bounds``, each avoiding every box placed or blocked before.

    Attributes
    ----------
    bounds:
        the box every label should lie inside (e.g. the axes in display pixels).
    gap:
        clearance kept between a moved label and its anchor, in the same units.
    soft_points:
        ``(n, 2)`` points a label should rather not cover (never a reason to refuse a spot).
    """

    bounds: Box
    gap: float = 3.0
    soft_points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    _boxes: list[Box] = field(default_factory=list)

    @property
    def boxes(self) -> list[Box]:
        """The boxes taken so far, in placement order."""
        return list(self._boxes)

    def block(self, box: Box) -> None:
        """Mark ``box`` as taken (a marker, a legend, a label placed by other means)."""
        self._boxes.append(tuple(float(v) for v in box))  # type: ignore[arg-type]

    def place(self, anchor: tuple[float, float], size: tuple[float, float], *, keep: bool = True) -> Box:
        """The box of a label of ``size = (width, height)`` placed near ``anchor = (x, y)``.

        The chosen box is added to the taken boxes unless ``keep`` is false.
        """
        w, h = size
        ax, ay = anchor
        cx = ax + _OFFSETS[:, 0] * (w / 2 + self.gap)
        cy = ay + _OFFSETS[:, 1] * (h / 2 + self.gap)
        x0, y0, x1, y1 = cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2
        bx0, by0, bx1, by1 = self.bounds
        # Area of each candidate lying outside the bounds, and overlapping the taken boxes.
        inside_w = np.clip(np.minimum(x1, bx1) - np.maximum(x0, bx0), 0, None)
        inside_h = np.clip(np.minimum(y1, by1) - np.maximum(y0, by0), 0, None)
        bad = w * h - inside_w * inside_h
        if self._boxes:
            taken = np.asarray(self._boxes)
            ow = np.clip(np.minimum(x1[:, None], taken[:, 2]) - np.maximum(x0[:, None], taken[:, 0]), 0, None)
            oh = np.clip(np.minimum(y1[:, None], taken[:, 3]) - np.maximum(y0[:, None], taken[:, 1]), 0, None)
            bad = bad + (ow * oh).sum(axis=1)
        score = _OFFSETS[:, 2].copy()
        if len(self.soft_points):
            px, py = self.soft_points[:, 0], self.soft_points[:, 1]
            covered = (px >= x0[:, None]) & (px <= x1[:, None]) & (py >= y0[:, None]) & (py <= y1[:, None])
            score += _SOFT_WEIGHT * np.minimum(covered.sum(axis=1), _SOFT_CAP)
        free = bad <= 1e-9
        # A free spot if there is one; otherwise the least-overlapping, nearest one.
        best = (
            int(np.argmin(np.where(free, score, np.inf))) if free.any() else int(np.lexsort((score, bad))[0])
        )
        box = (float(x0[best]), float(y0[best]), float(x1[best]), float(y1[best]))
        if keep:
            self._boxes.append(box)
        return box
