"""The registry of the bundled scenes: the TOML files shipped in the folder
``movingpunch/bundled_scenes/`` (the paper's Table 1 and Figs. 2-6, and more),
their names (the files' stems, the paper's first) and their text.
"""

from __future__ import annotations

from importlib import resources
from typing import Any

from movingpunch.errors import SceneError

__all__ = ["BUNDLED_FOLDER", "bundled_names", "bundled_scene_text", "bundled_text"]

BUNDLED_FOLDER = "bundled_scenes"
"""The package folder that holds the bundled scene files."""


def _bundled_dir() -> Any:
    """The folder of the bundled files (a ``Traversable``: it may sit in a
    zip)."""
    return resources.files("movingpunch").joinpath(BUNDLED_FOLDER)


def bundled_names() -> list[str]:
    """The names of the bundled scenes: Table 1 and Figs. 2-6 first, then the
    others in alphabetical order."""
    names = [
        entry.name[: -len(".toml")]
        for entry in _bundled_dir().iterdir()
        if entry.name.endswith(".toml")
    ]
    order = ["table1", "fig2", "fig3", "fig4", "fig5", "fig6"]
    return sorted(
        names, key=lambda n: (order.index(n) if n in order else len(order), n)
    )


def bundled_text(name: str) -> str:
    """The TOML text of the bundled scene ``name``; SceneError naming the
    bundled scenes if there is none of that name."""
    names = bundled_names()
    if name not in names:
        raise SceneError(
            f"<bundled scene {name}>",
            "name",
            f"no bundled scene {name!r} and no such file",
            ", ".join(names),
        )
    text: str = _bundled_dir().joinpath(f"{name}.toml").read_text(encoding="utf-8")
    return text


def bundled_scene_text(name: str) -> str | None:
    """The TOML text (with its comments) of a bundled scene, None if there is
    no bundled scene of that name."""
    if name not in bundled_names():
        return None
    return bundled_text(name)
