"""The exceptions of ``cycloid``: the engine's errors, with their location in the spec."""

from __future__ import annotations

import re
from typing import Optional

__all__ = ["CycloidError", "SpecError", "ComputationError"]


class CycloidError(Exception):
    """An error of the engine. ``str(error)`` is the text the command line prints:
    ``file:line:column: kind: key.path: message``.

    Attributes: ``kind`` (``"syntax"``, ``"invalid_value"``, ``"impossible_design"``,
    ``"io"``, ``"usage"``, ``"computation"``), ``message`` (the explanation alone), ``key``
    (the dotted key path in the spec, or None), ``file``, ``line``, ``column`` (1-based, or
    None when not known).
    """

    def __init__(
        self,
        text: str,
        kind: str,
        message: str,
        key: Optional[str] = None,
        file: Optional[str] = None,
        line: Optional[int] = None,
        column: Optional[int] = None,
    ) -> None:
        super().__init__(text)
        self.text = text
        self.kind = kind
        self.message = message
        self.key = key
        self.file = file
        self.line = line
        self.column = column

    def __str__(self) -> str:
        return self.text

    def __reduce__(self):  # picklable, e.g. across a process pool
        return (
            type(self),
            (self.text, self.kind, self.message, self.key, self.file, self.line, self.column),
        )


class SpecError(CycloidError, ValueError):
    """A spec the engine refuses: YAML syntax, an unknown key, a bad value, a design rule
    broken, a file it names that cannot be read. ``line``/``column`` point into ``file``."""


_SCENE = re.compile(r"scene `([^`]*)`")
_CRANK = re.compile(r"crank (?:angle )?(-?[0-9]+(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?) ?°")


class ComputationError(CycloidError, RuntimeError):
    """A computation that could not give its result (a solve that did not converge). ``scene``
    is the scene's name and ``crank_deg`` the crank angle (degrees) where it failed, when the
    message names them, else None."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        scene = _SCENE.search(self.message)
        crank = _CRANK.search(self.message)
        self.scene: Optional[str] = scene.group(1) if scene else None
        self.crank_deg: Optional[float] = float(crank.group(1)) if crank else None
