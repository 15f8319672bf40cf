"""Pictures of passive drops: a strip of snapshots per entry orientation (as the paper's
Figs. 10 and 11), the energy and overlap over time, and an animated GIF of the drops."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib import animation
from matplotlib import pyplot as plt

from experiments.drop.passive import DropResult
from experiments.pictures.scenes import ORIENTATION_COLOURS, draw_part, draw_scene, save_figure
from feeders.scene import Scene

SNAPSHOTS = 3  # as Figs. 10 and 11
FPS = 25


def _title(r: DropResult) -> str:
    verdict = "goal reached" if r.success else "goal missed"
    return f"{r.orientation.replace('_', ' ')}: {verdict} ({r.end}, T = {r.T:.2f} s)"


def _frame(ax: plt.Axes, scene: Scene, r: DropResult, upto: int) -> None:
    states = r.trajectory.states
    colour = ORIENTATION_COLOURS.get(r.orientation, "#1f77b4")
    ax.plot(states[: upto + 1, 0], states[: upto + 1, 1], color=colour, lw=1.4, zorder=6)
    draw_part(ax, scene.part, tuple(states[upto, :3]))


def drop_strip(scene: Scene, results: Sequence[DropResult], path: str | Path) -> Path:
    """One row per orientation: snapshots at the start, the middle and T, with the centre of
    mass trace so far, then the energy over time. Saved as PNG."""
    rows = len(results)
    fig, axes = plt.subplots(
        rows, SNAPSHOTS + 1, figsize=(3.3 * (SNAPSHOTS + 1), 4.2 * rows), squeeze=False
    )
    for row, r in zip(axes, results, strict=True):
        n = len(r.trajectory.states) - 1
        for k, ax in zip(
            np.linspace(0, n, SNAPSHOTS).round().astype(int), row[:SNAPSHOTS], strict=True
        ):
            draw_scene(ax, scene, starts=False)
            _frame(ax, scene, r, int(k))
            ax.set_title(f"t = {r.trajectory.times[k]:.2f} s", fontsize=9)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
        row[0].set_ylabel(_title(r), fontsize=8)
        energy = r.trajectory.energy()
        ax = row[SNAPSHOTS]
        ax.plot(r.trajectory.times, energy - energy[0], color="k", lw=1.0)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("E(t) - E(0)")
        ax.set_title(
            f"energy; rise {r.energy_rise:.1e}\noverlap <= {r.max_penetration:.1e}, "
            f"LCP failures {r.lcp_failures}",
            fontsize=8,
        )
    fig.suptitle(f"{scene.name}: passive drop (dynamic level, Eq. 7)", fontsize=11)
    return save_figure(fig, path)


def drop_animation(
    scene: Scene, results: Sequence[DropResult], path: str | Path, speed: float = 1.0
) -> Path:
    """An animated GIF, one panel per orientation, at ``speed`` x real time (FPS frames/s)."""
    fig, axes = plt.subplots(1, len(results), figsize=(4.0 * len(results), 4.8), squeeze=False)
    horizon = max(r.T for r in results)
    times = np.arange(0.0, horizon + 1e-12, speed / FPS)

    def draw(t: float) -> None:
        for ax, r in zip(axes[0], results, strict=True):
            ax.clear()
            draw_scene(ax, scene, starts=False)
            k = int(np.searchsorted(r.trajectory.times, min(t, r.T)))
            _frame(ax, scene, r, min(k, len(r.trajectory.states) - 1))
            ax.set_title(f"{r.orientation.replace('_', ' ')}  t = {min(t, r.T):.2f} s", fontsize=9)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])

    movie = animation.FuncAnimation(fig, draw, frames=times, interval=1000 / FPS)
    path = Path(path)
    movie.save(path, writer=animation.PillowWriter(fps=FPS), dpi=60)
    plt.close(fig)
    return path
