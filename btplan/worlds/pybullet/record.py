"""Frames of a run from a fixed camera, with the current action written on each, saved as GIF.

A user without a display can watch what the robot did. Pictures come from PyBullet's
software renderer (works headless); pillow writes the label and the animated GIF.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

from btplan.errors import WorldError
from btplan.worlds.pybullet.state import SceneState


class Recorder:
    """Keeps one frame every `every` action ticks; `save` writes the GIF atomically."""

    def __init__(self, path: str, every: int = 3, width: int = 480, height: int = 300) -> None:
        if Path(path).suffix.lower() != ".gif":
            raise WorldError(f"cannot record to {path!r}: only .gif is supported")
        self.path, self.every, self.size = path, every, (width, height)
        self.frames: list[Any] = []
        self._ticks = 0

    def __call__(self, world: SceneState, label: str) -> None:
        self._ticks += 1
        if self._ticks % self.every == 1 or self.every == 1:
            self.frames.append(frame(world, label, *self.size))

    def save(self) -> None:
        if not self.frames:
            return
        import io

        buffer = io.BytesIO()
        first, *rest = self.frames
        first.save(buffer, format="GIF", save_all=True, append_images=rest,
                   duration=max(20, int(1000 * 0.1 * self.every)), loop=0)
        write_bytes_atomic(self.path, buffer.getvalue())


def write_bytes_atomic(path: str, data: bytes) -> None:
    """Temporary file in the same folder, then rename: never half a GIF on disk."""
    folder = Path(path).resolve().parent
    handle, temporary = tempfile.mkstemp(dir=folder, prefix=".btplan-", suffix=".gif")
    try:
        with os.fdopen(handle, "wb") as out:
            out.write(data)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def frame(world: SceneState, label: str, width: int = 480, height: int = 300) -> Any:
    """One labelled picture of the scene as a pillow image (palette mode, for GIF)."""
    from PIL import Image, ImageDraw

    w, h, pixels = world.sim.snapshot(width, height)
    image = Image.frombytes("RGBA", (w, h), pixels).convert("RGB")
    draw = ImageDraw.Draw(image)
    draw.rectangle([0, 0, w, 18], fill=(0, 0, 0))
    draw.text((6, 3), label, fill=(255, 255, 255))
    return image.convert("P", palette=Image.Palette.ADAPTIVE)
