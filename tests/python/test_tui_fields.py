"""The summary's fields (``movingpunch.tui.widgets.fields``): packed into
lines at any width without ever splitting a field, two spaces apart, or one
where that saves a line."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from movingpunch.tui.widgets.fields import Field, layout, plain_lines

SUMMARY = (
    Field("a/h", "0.372881"),
    Field("p0", "1.699"),
    Field("δ/h", "0.0023"),
    Field("σx⁺ top", "0.467"),
    Field("bot", "1.33"),
    Field("it", "9"),
    Field("err", "8e-15"),
    Field("", "1.2 ms"),
)


def test_the_papers_summary_fits_one_80_column_line() -> None:
    # 78 columns inside the summary's padding: one space between fields.
    assert plain_lines(SUMMARY, 78) == [
        "a/h 0.372881 p0 1.699 δ/h 0.0023 σx⁺ top 0.467 bot 1.33 it 9 err 8e-15 1.2 ms"
    ]
    # Wider: two spaces.
    (line,) = plain_lines(SUMMARY, 118)
    assert "err 8e-15  1.2 ms" in line


def test_narrow_lines_keep_fields_whole() -> None:
    lines = plain_lines(SUMMARY, 30)
    assert len(lines) > 2
    assert any(line.endswith("1.2 ms") for line in lines)  # never "ms" alone
    assert not any(line.startswith("ms") for line in lines)
    assert all(len(line) <= 30 for line in lines)


words = st.text(alphabet="abcdefghij/0123456789.", min_size=1, max_size=12)


@given(
    st.lists(st.tuples(words, words), min_size=1, max_size=12),
    st.integers(min_value=8, max_value=120),
)
def test_packing_never_splits_a_field(parts: list[tuple[str, str]], width: int) -> None:
    fields = [Field(label, value) for label, value in parts]
    lines, separator = layout(fields, width)
    assert [f for line in lines for f in line] == fields  # in order, all of them
    for line in lines:
        text = separator.join(f.text() for f in line)
        # Over-wide only when a single field is wider than the line.
        assert len(text) <= width or len(line) == 1
