"""The report's chart of path cost against search time, one point per AMRA* iteration, as inline SVG."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sgplan.report.outcome import Iteration


def chart_svg(iterations: Sequence[Iteration]) -> str:
    """Cost (m) against search time (s) of the iterations, as an inline SVG step chart."""
    its = [it for it in iterations if math.isfinite(it.cost_m)]
    if not its:
        return '<p class="empty">No iteration finished with a path.</p>'
    w, h, left, bottom, top, right = 560, 260, 64, 40, 14, 16
    t = np.array([it.time_s for it in its])
    c = np.array([it.cost_m for it in its])
    t_max = float(t.max()) * 1.08 or 1e-3
    c_lo, c_hi = float(c.min()), float(c.max())
    pad = (c_hi - c_lo) * 0.15 or max(c_hi * 0.05, 0.5)
    c_lo, c_hi = max(0.0, c_lo - pad), c_hi + pad

    def x(v: float) -> float:
        return left + (w - left - right) * v / t_max

    def y(v: float) -> float:
        return h - bottom - (h - bottom - top) * (v - c_lo) / (c_hi - c_lo)

    steps = [f"{x(t[0]):.1f},{y(c[0]):.1f}"]
    for k in range(1, len(its)):
        steps += [f"{x(t[k]):.1f},{y(c[k - 1]):.1f}", f"{x(t[k]):.1f},{y(c[k]):.1f}"]
    steps.append(f"{x(t_max):.1f},{y(c[-1]):.1f}")
    parts = [
        (
            f'<svg id="cost-chart" viewBox="0 0 {w} {h}" width="{w}" height="{h}" '
            'xmlns="http://www.w3.org/2000/svg" role="img" aria-label="cost against time">'
        ),
        f'<line class="axis" x1="{left}" y1="{h - bottom}" x2="{w - right}" y2="{h - bottom}"/>',
        f'<line class="axis" x1="{left}" y1="{top}" x2="{left}" y2="{h - bottom}"/>',
    ]
    for v in np.linspace(c_lo, c_hi, 5):
        parts.append(f'<text class="tick" x="{left - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:.2f}</text>')
    for v in np.linspace(0, t_max, 5):
        parts.append(
            f'<text class="tick" x="{x(v):.1f}" y="{h - bottom + 16}" text-anchor="middle">{v:.3g}</text>'
        )
    parts.append(
        f'<text class="label" x="{(left + w) / 2}" y="{h - 6}" text-anchor="middle">search time (s)</text>'
    )
    parts.append(
        f'<text class="label" transform="translate(14,{(h - bottom + top) / 2}) rotate(-90)" '
        'text-anchor="middle">path cost (m)</text>'
    )
    parts.append(f'<polyline class="series" points="{" ".join(steps)}"/>')
    for it in its:
        parts.append(
            f'<circle class="point" cx="{x(it.time_s):.1f}" cy="{y(it.cost_m):.1f}" r="4">'
            f"<title>(w1, w2) = ({it.w1:g}, {it.w2:g}): cost {it.cost_m:.3f} m after {it.time_s:.4f} s, "
            f"bound x{it.bound:g}</title></circle>"
        )
    parts.append("</svg>")
    return "".join(parts)
