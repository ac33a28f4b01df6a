"""The README and docs/tui.md agree with the app and the package: the tab
keys, the bundled scenes (issue 16: the README said keys 1-6 and docs/tui.md
1-5; the README's scene list lacked a scene); the help screen and
docs/tui.md say the same (its key table and facts) and what they say is the
app's (issue 25: the help said damped solves took 0.4-1.5 s and that three
tabs showed a message with damping)."""

from __future__ import annotations

import re
from pathlib import Path

from textual.binding import Binding

import movingpunch as mp
from movingpunch.tui import model
from movingpunch.tui.screens import help
from movingpunch.tui.screens.main import (
    DEBOUNCE_SECONDS,
    SHORT_TAB_TITLES,
    TAB_TITLES,
    MainScreen,
)
from movingpunch.tui.widgets.params import INPUT_MESSAGE_LINES, STATUS_LINES

ROOT = Path(__file__).resolve().parents[2]


def test_the_tab_keys_agree_with_the_app() -> None:
    tabs = len(model.TABS)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    tui = (ROOT / "docs" / "tui.md").read_text(encoding="utf-8")
    assert re.findall(r"`1`\u2013`(\d)`", readme) == [str(tabs)]  # an en dash
    assert re.findall(r"`1` … `(\d)`", tui) == [str(tabs)]


def test_every_bundled_scene_is_listed_in_the_readme() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    lists = [line for line in readme.splitlines() if "table1, fig2 ... fig6" in line]
    assert lists
    for line in lists:
        for name in mp.bundled_scenes():
            if re.fullmatch(r"fig[2-6]", name):
                continue  # "fig2 ... fig6"
            assert re.search(rf"\b{re.escape(name)}\b", line), (name, line)


# -- the help screen and docs/tui.md: one source (issue 25) -------------------


def _flat(text: str) -> str:
    """Whitespace folded, Markdown's backticks and emphasis dropped."""
    return " ".join(text.replace("`", "").replace("**", "").split())


def _docs_keys() -> list[tuple[str, str]]:
    """The rows of docs/tui.md's Keys table, as plain text."""
    tui = (ROOT / "docs" / "tui.md").read_text(encoding="utf-8")
    section = tui.split("\n## Keys\n", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("| ")]
    out = []
    for line in rows[1:]:  # after the header
        key, action = (cell.strip() for cell in line.strip("|").split(" | "))
        out.append((_flat(key).replace("…", "..."), _flat(action)))
    return out


def test_the_help_keys_are_the_docs_keys() -> None:
    """docs/tui.md's Keys table is the help's, row for row."""
    assert _docs_keys() == [(key, _flat(what)) for key, what in help.KEYS]


def test_every_fact_of_the_help_is_in_the_docs() -> None:
    tui = _flat((ROOT / "docs" / "tui.md").read_text(encoding="utf-8"))
    for name, fact in help.FACTS.items():
        assert _flat(fact) in _flat(help.HELP), name
        assert _flat(fact) in tui, name


def _binding_keys() -> set[str]:
    names = {
        "right_square_bracket": "]",
        "left_square_bracket": "[",
        "question_mark": "?",
    }
    out = set()
    for binding in MainScreen.BINDINGS:
        assert isinstance(binding, Binding)
        for key in binding.key.split(","):
            out.add(names.get(key, key).lower())
    return out


def _help_keys() -> set[str]:
    out = set()
    for key, _ in help.KEYS:
        for word in re.split(r", | / | and | or ", key):
            ends = re.fullmatch(r"(f?)(\d) \.\.\. f?(\d)", word.lower())
            if ends:  # "1 ... 6", "F2 ... F6"
                prefix, first, last = ends.groups()
                out |= {f"{prefix}{n}" for n in range(int(first), int(last) + 1)}
            else:
                out.add(word.lower())
    return out


def test_the_help_names_every_key_of_the_app() -> None:
    """Every key the main screen binds is in the help (and the docs), and
    the help names no key the app does not have (tab, shift+tab and enter
    are Textual's and the inputs')."""
    bound = _binding_keys()
    named = _help_keys()
    assert bound <= named, bound - named
    assert named - bound == {"tab", "shift+tab", "enter"}


def test_the_help_tabs_are_the_app_tabs() -> None:
    assert [name for name, _, _ in help.TABS] == [TAB_TITLES[t] for t in model.TABS]
    assert [short for _, short, _ in help.TABS] == [
        SHORT_TAB_TITLES[t] for t in model.TABS
    ]


def test_the_help_says_the_app_s_numbers() -> None:
    """The typing pause and the message areas' lines the help states are
    the app's."""
    assert round(DEBOUNCE_SECONDS * 1000) == help.DEBOUNCE_MS
    assert f"({help.DEBOUNCE_MS} ms)" in help.FACTS["typing"]
    for lines in (STATUS_LINES, INPUT_MESSAGE_LINES):
        for n in lines:
            word = ("no", "one", "two", "three", "four", "five")[n]
            assert re.search(rf"\b{word}\b", help.FACTS["messages"]), word


def test_every_tab_works_with_damping_as_the_help_says() -> None:
    """The help and docs say every tab works with damping (issue 25: they
    said three tabs showed a message instead): each tab of a damped set
    computes its data, no notice."""
    cache = model.Cache()
    params = model.Params(vstar=0.65, damping=0.1)
    assert "every tab works as without" in help.FACTS["damping"]
    for generation, tab in enumerate(model.TABS, start=1):
        request = model.Request(generation=generation, params=params, tab=tab)
        result = model.compute(cache, request)
        assert result is not None
        assert not isinstance(result.data, model.Notice), (tab, result.data)
        assert result.summary.damped
