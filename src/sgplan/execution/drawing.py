"""Pictures of a simulated run: per floor, the path driven, the plans it abandoned and the cells the scene
changes touched, over the building as the changes left it; and an HTML page of them with the timeline."""

from __future__ import annotations

import base64
import html
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from sgplan.errors import SceneError
from sgplan.files import write_text_atomically

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sgplan.execution.simulate import Simulation

ABANDONED = "#606060"
CHANGED = "#ff8c00"


def draw_simulation(sim: Simulation, out_dir: str | Path) -> list[Path]:
    """Write ``<out_dir>/run_<floor>.png`` per floor; returns the paths. Costs a drawing per floor."""
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise SceneError(f"cannot create the drawing folder {out}: {error.strerror}") from None
    written = []
    for floor in range(sim.run.building.num_floors):
        target = out / f"run_{floor}.png"
        try:
            simulation_figure(sim, floor).savefig(target, format="png")
        except OSError as error:
            raise SceneError(f"cannot write {target}: {error.strerror}") from None
        written.append(target)
    return written


def simulation_figure(sim: Simulation, floor: int) -> Figure:
    """One floor of the run: the path driven (with its direction), the plans abandoned (dashed) and the
    cells the changes touched, over the building as the changes left it. Drawn in the map frame of
    :func:`sgplan.scene.draw.draw_floor`, where a cell's data coordinates are ``(row, col)``."""
    from matplotlib.lines import Line2D

    from sgplan.scene.draw import draw_floor

    run = sim.run
    abandoned = sim.plans[:-1] if run.status != "done" or len(sim.plans) > 1 else []
    fig = draw_floor(run.building, floor, grid=run.grid, path=sim.driven_cells,
                     title=f"{run.building.name}, floor {floor}: the run ({run.status}), driven path")
    ax = fig.axes[0]
    for path in abandoned:
        here = path[path[:, 2] == floor]
        if len(here):
            ax.plot(here[:, 0], here[:, 1], color=ABANDONED, lw=1.2, ls="--", alpha=0.8, zorder=3)
    cells = np.concatenate(sim.changed.get(floor, [np.zeros(0, np.int64)]))
    if cells.size:
        rows, cols = np.divmod(cells, run.building.grid_shape[1])
        ax.scatter(rows, cols, s=9, marker="s", color=CHANGED, alpha=0.9, linewidths=0, zorder=4)
    ax.legend(handles=[Line2D([], [], color=ABANDONED, ls="--", label="abandoned plans"),
                       Line2D([], [], color=CHANGED, marker="s", ls="", label="changed cells")],
              loc="lower right", fontsize=7)
    return fig


def simulation_html(sim: Simulation, pictures: list[Path], path: str | Path) -> Path:
    """A self-contained HTML page: the timeline and the pictures (embedded)."""
    rows = "".join(f"<tr><td>{m.driven_m:.2f}</td><td>{html.escape(m.what)}</td>"
                   f"<td>{'' if m.replan_s is None else f'{m.replan_s * 1e3:.0f}'}</td>"
                   f"<td>{'' if m.cost_m is None else f'{m.cost_m:.2f}'}</td>"
                   f"<td>{html.escape(m.left)}</td></tr>"
                   for m in sim.timeline)
    images = "".join(f"<figure><img alt='{p.name}' src='data:image/png;base64,"
                     f"{base64.b64encode(p.read_bytes()).decode()}'><figcaption>{p.name}</figcaption></figure>"
                     for p in pictures)
    name = html.escape(sim.run.building.name)
    page = (f"<!doctype html><meta charset='utf-8'><title>sgplan simulate: {name}</title>"
            f"<style>body{{font-family:sans-serif}}td,th{{padding:2px 8px;text-align:left}}"
            f"img{{max-width:100%}}</style><h1>Run on {html.escape(sim.run.building.name)}: "
            f"{sim.run.status}</h1><table><tr><th>driven m</th><th>what</th><th>replan ms</th>"
            f"<th>to go m</th><th>left</th></tr>{rows}</table>{images}")
    write_text_atomically(Path(path), page)
    return Path(path)
