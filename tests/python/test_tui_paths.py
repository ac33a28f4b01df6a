"""Open, Save and Export stay inside the working folder, ask before
overwriting, and name the user's path (never a temporary file) in errors.

Each test makes a working folder ``root`` inside a scratch directory, so a
path that escaped would land next to it, where the test looks for it.
"""

from __future__ import annotations

import asyncio
import os
import subprocess
from collections.abc import Callable
from pathlib import Path

import pytest
from textual.pilot import Pilot
from textual.widgets import Input, Label, Static

from movingpunch.scene import Scene
from movingpunch.tui import MovingPunchApp, create_app
from movingpunch.tui.model import Params
from movingpunch.tui.paths import (
    DEFAULT_FOLDER,
    OutsideFolderError,
    OverwriteNeeded,
    WorkingFolder,
    source_checkout,
)
from movingpunch.tui.screens import MainScreen, PathPrompt
from tui_pilot import screen_of, settle, sync

SIZE = (100, 32)


@pytest.fixture
def root(tmp_path: Path) -> Path:
    folder = tmp_path / "root"
    folder.mkdir()
    return folder


def prompt_message(app: MovingPunchApp) -> str:
    return str(app.screen.query_one("#prompt-msg", Static).render())


async def submit(app: MovingPunchApp, pilot: Pilot[None], path: str) -> None:
    """Types ``path`` into the open prompt and presses enter."""
    assert isinstance(app.screen, PathPrompt)
    app.screen.query_one("#path", Input).value = path
    await pilot.pause()
    await pilot.press("enter")
    await pilot.pause()


async def confirm(pilot: Pilot[None]) -> None:
    """The second enter that confirms overwriting (after the prompt's
    guard against a repeated keypress)."""
    await asyncio.sleep(PathPrompt.CONFIRM_AFTER + 0.05)
    await pilot.press("enter")
    await pilot.pause()


def escapes(root: Path) -> list[Path]:
    """Paths that would escape the folder, each with where it would land."""
    outside = root.parent / "elsewhere"
    outside.mkdir(exist_ok=True)
    (root / "out").symlink_to(outside, target_is_directory=True)
    return [
        root.parent / "x",  # typed as ../x
        outside / "x",  # typed as an absolute path elsewhere
        outside / "y",  # typed as out/y: a link inside leading out
    ]


TYPED = ["../x", "{elsewhere}/x", "out/y"]


# -- the folder alone ---------------------------------------------------------


def test_paths_resolve_inside_the_folder_only(root: Path) -> None:
    folder = WorkingFolder.at(root)
    (root / "sub").mkdir()
    assert folder.resolve("a.toml") == root.resolve() / "a.toml"
    assert folder.resolve("sub/../b.csv") == root.resolve() / "b.csv"
    assert folder.resolve(str(root / "sub" / "c.csv")) == root.resolve() / "sub/c.csv"
    # A link inside that stays inside is followed.
    (root / "here").symlink_to(root / "sub", target_is_directory=True)
    assert folder.resolve("here/d.csv") == root.resolve() / "sub" / "d.csv"
    landing = escapes(root)
    typed = [t.format(elsewhere=landing[1].parent) for t in TYPED]
    # A dangling link pointing out, the folder itself, a sibling that shares
    # the folder's name as a prefix, and the home directory are out too.
    (root / "dangling").symlink_to(root.parent / "nowhere.toml")
    (root.parent / "root2").mkdir()
    for text in [*typed, "dangling", ".", "", "../root2/x", "~/x", "/"]:
        with pytest.raises(OutsideFolderError, match="outside the working folder"):
            folder.resolve(text)


def test_target_refuses_folders_and_asks_before_overwriting(root: Path) -> None:
    folder = WorkingFolder.at(root)
    (root / "sub").mkdir()
    (root / "old.csv").write_text("old", encoding="utf-8")
    with pytest.raises(OutsideFolderError, match="sub: is a folder"):
        folder.target("sub", overwrite=True)
    with pytest.raises(OverwriteNeeded, match=r"old\.csv exists"):
        folder.target("old.csv", overwrite=False)
    assert folder.target("old.csv", overwrite=True) == root.resolve() / "old.csv"
    assert folder.target("new.csv", overwrite=False) == root.resolve() / "new.csv"


def test_the_folder_must_exist(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    with pytest.raises(ValueError, match=r"root: .* is not an existing directory"):
        WorkingFolder.at(tmp_path / "missing")
    with pytest.raises(ValueError, match="not an existing directory"):
        WorkingFolder.at(Path(__file__))
    monkeypatch.chdir(tmp_path)  # not a source checkout: the folder is here
    assert WorkingFolder.at().root == Path(os.path.realpath(tmp_path))
    assert WorkingFolder.at().checkout is None


# -- started in the source checkout (issue 25) --------------------------------

CHECKOUT = Path(__file__).resolve().parents[2]
"""This source checkout (the one the tests run from)."""


def fake_checkout(where: Path, name: str = "movingpunch") -> Path:
    (where / "python" / "movingpunch").mkdir(parents=True)
    (where / "pyproject.toml").write_text(
        f'[project]\nname = "{name}"\nversion = "0"\n', encoding="utf-8"
    )
    return where


@pytest.fixture
def home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A scratch home folder (``~``)."""
    folder = tmp_path / "home"
    folder.mkdir()
    monkeypatch.setenv("HOME", str(folder))
    return folder


def test_the_source_checkout_is_found(tmp_path: Path) -> None:
    assert source_checkout(CHECKOUT) == CHECKOUT
    assert source_checkout(CHECKOUT / "docs") == CHECKOUT
    assert source_checkout(tmp_path) is None
    other = fake_checkout(tmp_path / "other", name="movingpunch-fork")
    assert source_checkout(other) is None  # another project
    mine = fake_checkout(tmp_path / "mine")
    (mine / "results").mkdir()
    assert source_checkout(mine / "results") == mine


@pytest.mark.parametrize("start", ["", "docs"], ids=["root", "docs"])
def test_started_in_the_checkout_the_folder_is_elsewhere(
    start: str, home: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Inside the checkout without --root the folder is ~/movingpunch,
    made only when a file is written; --root . keeps the checkout."""
    monkeypatch.chdir(CHECKOUT / start)
    folder = WorkingFolder.at()
    assert folder.root == home.resolve() / "movingpunch"
    assert folder.checkout == CHECKOUT
    assert folder.label == "~/movingpunch"
    assert DEFAULT_FOLDER == "~/movingpunch"
    assert not folder.root.exists()  # nothing made by starting
    assert folder.target("scene.toml", overwrite=False) == folder.root / "scene.toml"
    assert folder.root.is_dir()
    # `serve` passes the folder on as --root before it exists.
    folder.root.rmdir()
    assert WorkingFolder.at(str(folder.root)).root == folder.root
    kept = WorkingFolder.at(".")
    assert kept.root == (CHECKOUT / start).resolve()
    assert kept.checkout is None


@sync
async def test_exports_from_the_checkout_never_land_in_it(
    home: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The app started in the checkout (as ``bash scripts/run.sh`` does):
    its prompts name ~/movingpunch, and Export and Save write there, not
    into the source tree (issue 25: an untracked movingpunch-pressure.csv
    and scene.toml in the checkout)."""
    monkeypatch.chdir(CHECKOUT)
    before = set(os.listdir(CHECKOUT))
    app = create_app(show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for key, name in (("e", "movingpunch-pressure.csv"), ("s", "scene.toml")):
            await pilot.press(key)
            await pilot.pause()
            assert isinstance(app.screen, PathPrompt)
            title = str(app.screen.query_one("#prompt-title", Label).render())
            assert title.endswith("in ~/movingpunch"), title
            assert app.screen.query_one("#path", Input).value == name
            await pilot.press("enter")
            await pilot.pause()
            assert isinstance(app.screen, MainScreen)
            assert (home / "movingpunch" / name).stat().st_size > 0
    assert set(os.listdir(CHECKOUT)) == before


def test_tui_with_a_bad_root_is_one_line_and_exit_2(
    tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli("tui", "--root", str(tmp_path / "no"), timeout=60)
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("movingpunch: error: root: ")


@pytest.mark.parametrize("command", ["tui", "serve"])
def test_an_empty_root_is_refused_naming_root(
    tmp_path: Path,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
    command: str,
) -> None:
    # `--root ''` silently meant the current directory (even in the source
    # checkout, where no --root means ~/movingpunch), as `run --out ''` did.
    proc = run_cli(command, "--root", "", cwd=tmp_path, timeout=60)
    assert_one_line_error(
        proc, "argument --root", "must name a folder, got ''", "use '.'"
    )
    assert list(tmp_path.iterdir()) == []


def test_an_empty_root_is_refused_by_the_api(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=r"root: '' names no folder .*'\.'"):
        WorkingFolder.at("")
    with pytest.raises(ValueError, match=r"root: '' names no folder"):
        create_app(root="")
    assert WorkingFolder.at(".").root == Path(os.path.realpath(tmp_path))


# -- the app ------------------------------------------------------------------


@sync
async def test_save_and_export_stay_inside_the_folder(root: Path) -> None:
    landing = escapes(root)
    typed = [t.format(elsewhere=landing[1].parent) for t in TYPED]
    app = create_app(root=root)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for key in ("s", "e"):
            await pilot.press(key)
            await pilot.pause()
            prompt = app.screen
            assert isinstance(prompt, PathPrompt)
            for text in typed:
                await submit(app, pilot, text)
                assert app.screen is prompt  # refused: the prompt stays
                message = prompt_message(app)
                assert f"{text}: outside the working folder" in message
            assert not any(p.exists() for p in landing)
            # Inside the folder (also through a sub-folder) it writes.
            (root / "sub").mkdir(exist_ok=True)
            await submit(app, pilot, f"sub/{key}.out")
            assert isinstance(app.screen, MainScreen)
            assert (root / "sub" / f"{key}.out").stat().st_size > 0
    assert Scene.load(root / "sub" / "s.out").params["vstar"] == 0.2
    header = (root / "sub" / "e.out").read_text(encoding="utf-8").splitlines()[0]
    assert header.startswith("#")


@sync
async def test_overwriting_asks_first(root: Path) -> None:
    old = root / "old.toml"
    other = root / "other.csv"
    old.write_text("keep me\n", encoding="utf-8")
    other.write_text("keep me too\n", encoding="utf-8")
    app = create_app(root=root)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("s")
        await pilot.pause()
        prompt = app.screen
        await submit(app, pilot, "old.toml")
        assert app.screen is prompt
        assert prompt_message(app) == (
            "old.toml exists: enter again to overwrite, escape to cancel"
        )
        assert old.read_text(encoding="utf-8") == "keep me\n"
        # Another existing path asks again (its own confirmation).
        await submit(app, pilot, "other.csv")
        assert app.screen is prompt
        assert "other.csv exists" in prompt_message(app)
        assert other.read_text(encoding="utf-8") == "keep me too\n"
        # Back to the first one: asked anew, not overwritten by one enter.
        await submit(app, pilot, "old.toml")
        assert app.screen is prompt
        assert old.read_text(encoding="utf-8") == "keep me\n"
        # The second enter on the same path writes.
        await confirm(pilot)
        assert isinstance(app.screen, MainScreen)
        assert Scene.load(old).params["load"] == 0.002
        assert other.read_text(encoding="utf-8") == "keep me too\n"
        # Export asks the same way; escape leaves the file as it was.
        await pilot.press("e")
        await pilot.pause()
        await submit(app, pilot, "other.csv")
        assert "other.csv exists" in prompt_message(app)
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)
        assert other.read_text(encoding="utf-8") == "keep me too\n"
        await pilot.press("e")
        await pilot.pause()
        await submit(app, pilot, "other.csv")
        await confirm(pilot)
        assert isinstance(app.screen, MainScreen)
        assert other.read_text(encoding="utf-8").startswith("#")


@sync
async def test_write_errors_name_the_typed_path(root: Path) -> None:
    (root / "afile").write_text("", encoding="utf-8")
    app = create_app(root=root)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for key in ("s", "e"):
            await pilot.press(key)
            await pilot.pause()
            prompt = app.screen
            await submit(app, pilot, "no/such/dir/x.toml")
            assert app.screen is prompt
            message = prompt_message(app)
            assert message == (
                "cannot write no/such/dir/x.toml: No such file or directory"
            )
            await submit(app, pilot, "afile/x.toml")
            assert prompt_message(app) == "cannot write afile/x.toml: Not a directory"
            assert ".tmp" not in message
            await pilot.press("escape")
            await pilot.pause()
        assert sorted(p.name for p in root.iterdir()) == ["afile"]


@sync
async def test_open_stays_inside_the_folder(root: Path) -> None:
    landing = escapes(root)
    typed = [t.format(elsewhere=landing[1].parent) for t in TYPED]
    faster = Scene.bundled("fig4").with_params(vstar=0.3)
    for path in landing:
        faster.save(path.with_suffix(".toml"))
    inside = root / "mine.toml"
    faster.with_params(vstar=0.1).save(inside)
    app = create_app(root=root)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("o")
        await pilot.pause()
        prompt = app.screen
        for text in typed:
            await submit(app, pilot, text + ".toml")
            assert app.screen is prompt
            assert f"{text}.toml: outside the working folder" in prompt_message(app)
        assert screen.params.vstar == 0.2
        # A missing file is named as typed, not by its real path.
        await submit(app, pilot, "missing.toml")
        assert prompt_message(app).startswith("missing.toml: (file): cannot read")
        await submit(app, pilot, "mine.toml")
        await settle(pilot)
        assert isinstance(app.screen, MainScreen)
        assert screen.params == Params(vstar=0.1)
        # A bundled scene's name still opens it.
        await pilot.press("o")
        await pilot.pause()
        await submit(app, pilot, "fig5")
        await settle(pilot)
        assert isinstance(app.screen, MainScreen)
        assert screen.overlay is not None
        assert screen.overlay.param == "kw"
