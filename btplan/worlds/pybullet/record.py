"""A run as a movie (MP4 or GIF) from a camera following the robot, the action on each frame.

A user without a display can watch what the robot did. Pictures come from PyBullet's
software renderer (works headless); pillow writes the label and the GIF, and the ffmpeg
that ships inside the imageio-ffmpeg wheel encodes the MP4, so no system codec is needed.
Frames go to a temporary file next to the target and are renamed at the end: never half
a movie on disk.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import tempfile
from collections.abc import Generator
from pathlib import Path
from typing import Any, Protocol

from btplan.errors import WorldError
from btplan.io import output_mode, write_bytes_atomic  # a normal file's mode, renamed whole


class Camera(Protocol):
    """Whatever takes pictures of a scene: the simulation of either PyBullet world."""

    def snapshot(self, width: int, height: int) -> tuple[int, int, bytes]:
        """An RGBA picture as (width, height, pixels), four bytes a pixel."""
        ...


class Scene(Protocol):
    """What the recorder films: any scene state whose simulation can take a picture."""

    @property
    def sim(self) -> Camera:
        """The simulation that takes the pictures."""
        ...

FORMATS = (".gif", ".mp4")


class Recorder:
    """Keeps one frame every `every` action ticks; `save` finishes the file atomically."""

    def __init__(self, path: str, every: int = 2, width: int = 640, height: int = 400,
                 tick_seconds: float = 0.1) -> None:
        suffix = Path(path).suffix.lower()
        if suffix not in FORMATS:
            raise WorldError(f"cannot record to {path!r}: use a .mp4 or .gif file name")
        if not Path(path).resolve().parent.is_dir():
            raise WorldError(f"cannot record to {path!r}: its folder does not exist")
        self.path, self.every, self.size, self.suffix = path, every, (width, height), suffix
        self.fps = max(1, round(2 / (tick_seconds * every)))  # plays at twice real time
        self.frames: list[Any] = []      # GIF: palette images, small
        self._movie: Generator[None, bytes, None] | None = None
        self._temporary: str | None = None
        self._ticks = 0

    def __call__(self, world: Scene, label: str) -> None:
        self._ticks += 1
        if self._ticks % self.every != 1 and self.every != 1:
            return
        image = frame(world, label, *self.size)
        if self.suffix == ".gif":
            self.frames.append(image.convert("P", palette=_palette()))
            return
        if self._movie is None:
            self._movie = self._open_movie()
        self._movie.send(image.tobytes())

    def _open_movie(self) -> Generator[None, bytes, None]:
        imageio_ffmpeg: Any = importlib.import_module("imageio_ffmpeg")

        handle, self._temporary = tempfile.mkstemp(dir=Path(self.path).resolve().parent,
                                                   prefix=".btplan-", suffix=".mp4")
        os.close(handle)
        movie: Generator[None, bytes, None] = imageio_ffmpeg.write_frames(
            self._temporary, self.size, fps=self.fps, codec="libx264", quality=7,
            macro_block_size=8, ffmpeg_log_level="error")
        movie.send(None)  # type: ignore[arg-type]  # start the encoder
        return movie

    def save(self) -> None:
        """Finish the file: an MP4 is closed and renamed into place, a GIF written atomically.

        A run that kept no frame writes no file at all.
        """
        if self._movie is not None and self._temporary is not None:
            self._movie.close()
            target = Path(self.path)
            os.chmod(self._temporary, output_mode(target.stat() if target.exists() else None))
            os.replace(self._temporary, self.path)
            self._movie = self._temporary = None
            return
        if not self.frames:
            return
        import io

        buffer = io.BytesIO()
        first, *rest = self.frames
        first.save(buffer, format="GIF", save_all=True, append_images=rest,
                   duration=max(20, int(1000 / self.fps)), loop=0)
        write_bytes_atomic(self.path, buffer.getvalue())

    def discard(self) -> None:
        """Drop a movie being written (the run failed before `save`)."""
        if self._movie is not None:
            with contextlib.suppress(Exception):
                self._movie.close()
        if self._temporary is not None:
            Path(self._temporary).unlink(missing_ok=True)


def _palette() -> Any:
    from PIL import Image

    return Image.Palette.ADAPTIVE


def frame(world: Scene, label: str, width: int = 640, height: int = 400) -> Any:
    """One labelled RGB picture of the robot and what is around it, as a pillow image."""
    from PIL import Image, ImageDraw

    w, h, pixels = world.sim.snapshot(width, height)
    image = Image.frombytes("RGBA", (w, h), pixels).convert("RGB")
    draw = ImageDraw.Draw(image)
    draw.rectangle([0, 0, w, 20], fill=(0, 0, 0))
    draw.text((6, 4), label, fill=(255, 255, 255))
    return image
