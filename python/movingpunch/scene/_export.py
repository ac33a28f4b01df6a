"""Showing and saving a scene's result: summary table, ASCII plots (plotext),
CSV/JSON files with the scene and the package version as metadata, PNG
figures (matplotlib, optional). File names come from ``safe_name`` (never a
path outside the output folder); the files of one run are published together
(``movingpunch.outputs.publish``: all of them or none)."""

from __future__ import annotations

import importlib
import io
import json
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from movingpunch._display import drag_scale, shown, singular_note
from movingpunch._textplot import BLANK, MARKERS, Cell, compose, plain
from movingpunch._version import version
from movingpunch.errors import MissingExtraError
from movingpunch.outputs import publish, safe_name
from movingpunch.scene._model import SWEEP_QUANTITIES
from movingpunch.scene._result import Curve, FloatArray, OutputData
from movingpunch.scene._scene import Scene, SceneResult

__all__ = [
    "ascii_plots",
    "format_json",
    "format_summary",
    "read_csv",
    "read_json",
    "render_outputs",
    "render_pngs",
    "stream_outputs",
    "write_outputs",
    "write_pngs",
]


_PARAM_LABELS = {
    "vstar": "V*",
    "kw": "k_w h/μ",
    "radius": "R/h",
    "load": "P/(μh)",
    "nu": "ν",
    "damping": "damping",
    "kp": "k_p/(μh)",
    "friction": "friction f",
    "spacing": "spacing/h",
}
_QUANTITY_LABELS = {
    "a": "a/h",
    "p0": "p0/(P/h)",
    "indentation": "δ/h",
    "min_pressure": "min p/(P/h)",
    "critical_vstar": "V*_cr",
    "phi1": "φ1",
    "drag": "drag/P",
    "contact_start": "-b/h (trailing end)",
    "contact_end": "a/h (end)",
    "zones": "zones",
    "top_compressive": "top σx min",
    "top_tensile": "top σx max",
    "bottom_tensile": "bottom σx max",
    "centre_top": "σx(0,0)",
    "centre_bottom": "σx(0,-h)",
}


# ----------------------------------------------------------------------------
# Summary
# ----------------------------------------------------------------------------


def _fmt(x: float) -> str:
    if isinstance(x, float) and math.isnan(x):
        return "-"
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:.10g}"


def _indentation_text(value: object) -> str:
    """A punch's indentation; n/a where the medium does not give it (None:
    the asymmetric solver under a half-space)."""
    return "n/a" if value is None else _fmt(float(value))  # type: ignore[arg-type]


_ENDS = ("a", "contact_start", "contact_end")


def _drag_scale(
    scene: Scene,
    curve: int,
    override: Mapping[str, float] | None,
    ends: Sequence[float],
) -> float:
    """``drag_scale`` of the point of the ``curve``-th vary value (with the
    sweep's ``override``): the contact's reach over its R/h."""
    values = scene.curve_values()
    value = values[curve] if curve < len(values) else None
    radius = scene.point(value, **(override or {})).get("radius", math.inf)
    return drag_scale([float(x) for x in ends], float(radius))


def _punch_drag(d: Mapping[str, Any], scene: Scene, k: int) -> float:
    """The ``k``-th punch's drag/P as shown: round-off of its scale is 0."""
    at = float(d["at"])
    ends = [float(x) - at for zone in d["contact_zones"] for x in zone]
    radius = scene.point().get("radius", math.inf)
    if k < len(scene.punches):
        radius = scene.punches[k].profile.nominal_radius
    return shown(float(d["drag"]), scale=drag_scale(ends, radius))


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    widths = [len(h) for h in header]
    for row in rows:
        widths = [max(w, len(c)) for w, c in zip(widths, row, strict=True)]
    lines = ["  " + "  ".join(h.ljust(w) for h, w in zip(header, widths, strict=True))]
    lines += [
        "  " + "  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True))
        for row in rows
    ]
    return [line.rstrip() for line in lines]


def format_summary(result: SceneResult, hints: Sequence[str] = ()) -> str:
    """The run as text: the scene, its scalar results, the sweep table, the
    warnings, the plausibility ``hints`` (one line ``hint: ...``, if any)
    and the stages with their times."""
    scene = result.scene
    out: list[str] = []
    title = f"Scene {scene.name}" if scene.name else "Scene"
    out.append(f"{title}: {scene.description}" if scene.description else title)
    params = ", ".join(
        f"{_PARAM_LABELS[k]} = {_fmt(v)}" for k, v in scene.params.items()
    )
    out.append(f"  {params}, tol = {scene.tol:g}")
    if scene.medium is not None:
        out.append(f"  medium: {scene.medium.describe()}")
    if scene.contact != "auto":
        out.append(f"  contact = {scene.contact}")
    for k, punch in enumerate(scene.punches):
        out.append(
            f"  punch {k + 1}: {punch.profile.describe()}, "
            f"P/(μh) = {_fmt(punch.load)}, at x/h = {_fmt(punch.at)}"
        )
    if scene.vary is not None:
        vals = ", ".join(_fmt(v) for v in scene.vary.values)
        out.append(f"  curves: {_PARAM_LABELS[scene.vary.param]} = {vals}")

    cw = result.outputs.get("contact_width")
    if cw is not None:
        out += ["", "Contact"]
        hidden = ("error_estimate", "collocation_n", "contact_end")  # end: = a
        names = [n for n in cw.columns if n not in hidden]
        header = [_PARAM_LABELS.get(n, _QUANTITY_LABELS.get(n, n)) for n in names]
        rows = []
        for i in range(len(cw.columns["a"])):
            row = []
            for n in names:
                value = float(cw.columns[n][i])
                if n == "drag":  # round-off shown as 0 (movingpunch._display)
                    ends = (
                        cw.columns["contact_start"][i],
                        cw.columns["contact_end"][i],
                    )
                    value = shown(value, scale=_drag_scale(scene, i, None, ends))
                row.append(("yes" if value else "NO") if n == "valid" else _fmt(value))
            rows.append(row)
        out += _table(header, rows)
        out += _zone_lines(cw.details, len(rows), scene)

    cs = result.outputs.get("critical_speed")
    if cs is not None and not cs.curves:
        out += ["", "Critical speed"]
        rows = [
            [_fmt(float(cs.columns[n][i])) for n in cs.columns]
            for i in range(len(cs.columns["kw"]))
        ]
        header = ["k_w h/μ", "ν", "V*_cr", "αh at min", "V*_R"]
        if "kp" in cs.columns:  # a scene with a Pasternak shear layer
            header.append(_PARAM_LABELS["kp"])
        out += _table(header, rows)

    sw = result.sweep
    if sw is not None:
        out += ["", f"Sweep over {_PARAM_LABELS[sw.param]} ({len(sw.values)} points)"]
        header = [_PARAM_LABELS[sw.param]]
        for label in sw.labels:
            for q in sw.quantities:
                header.append(
                    f"{_QUANTITY_LABELS[q]} ({label})" if label else _QUANTITY_LABELS[q]
                )
        rows = []
        n_rows = len(sw.values)
        shown_rows = (
            list(range(n_rows))
            if n_rows <= _SUMMARY_ROWS
            else [*range(_SUMMARY_ENDS), *range(n_rows - _SUMMARY_ENDS, n_rows)]
        )
        for j in shown_rows:
            x = sw.values[j]
            row = [_fmt(float(x))]
            for i in range(len(sw.labels)):
                for q in sw.quantities:
                    value = float(sw.data[q][i, j])
                    if q == "drag":  # round-off shown as 0 (movingpunch._display)
                        reach = [float(sw.data[e][i, j]) for e in _ENDS if e in sw.data]
                        at = {sw.param: float(x)}
                        value = shown(value, scale=_drag_scale(scene, i, at, reach))
                    row.append(_fmt(value) + ("" if sw.valid[i, j] else " !"))
            rows.append(row)
        table = _table(header, rows)
        if n_rows > _SUMMARY_ROWS:  # the header line, then the first rows
            cut = 1 + _SUMMARY_ENDS
            left_out = n_rows - 2 * _SUMMARY_ENDS
            elided = f"  ... {left_out} rows not shown (--out DIR writes all)"
            table = [*table[:cut], elided, *table[cut:]]
        out += table
        if not sw.valid.all():
            out.append(
                "  ! not a valid single contact (p < 0, penetration or failed solve)"
            )
        for (_, j), message in list(sw.errors.items())[:3]:
            out.append(
                f"  error at {sw.param} = {_fmt(float(sw.values[j]))}: {message}"
            )

    files = [k for k in result.outputs if k not in ("contact_width",)]
    if files:
        out += ["", "Outputs: " + ", ".join(files)]

    if result.warnings:
        out += ["", f"Warnings ({len(result.warnings)})"]
        out += [f"  warning: {w}" for w in result.warnings]

    if hints:
        out += ["", "hint: " + "; ".join(hints)]

    out += [
        "",
        f"Stages (total {result.total_seconds:.3f} s, jobs {result.jobs or 'dask'})",
    ]
    out += _table(
        ["stage", "count", "seconds"],
        [[s.name, str(s.count), f"{s.seconds:.4f}"] for s in result.stages],
    )
    return "\n".join(out)


_SUMMARY_ROWS = 1000
"""Rows of a sweep's table the summary shows whole; a longer one shows its
first and last _SUMMARY_ENDS (the files hold every row)."""
_SUMMARY_ENDS = 20


def format_zones(zones: Sequence[Sequence[float]]) -> str:
    """Contact zones as text: "(-1.78, -0.72) (0.72, 1.78)"."""
    return " ".join(f"({lo:.6g}, {hi:.6g})" for lo, hi in zones)


def _zone_lines(details: Mapping[str, Any], n: int, scene: Scene) -> list[str]:
    """The contact zones of each curve that has several, and a line per
    punch of a train or a separated contact."""
    zones = details.get("contact_zones", [])
    punches = details.get("punches", [])
    values = scene.curve_values()
    param = scene.vary.param if scene.vary is not None else None
    lines: list[str] = []
    for i in range(min(n, len(zones))):
        mine = punches[i] if i < len(punches) else []
        if len(zones[i]) < 2 and len(mine) < 2:
            continue
        where = (
            f" ({_PARAM_LABELS[param]} = {_fmt(float(values[i] or 0.0))})"
            if param is not None and values[i] is not None
            else ""
        )
        lines.append(f"  contact zones{where}: {format_zones(zones[i])}")
        for k, d in enumerate(mine if len(mine) > 1 or len(zones[i]) > 1 else []):
            lines.append(
                f"    punch {k + 1} at x/h = {_fmt(float(d['at']))}: "
                f"P/(μh) = {_fmt(float(d['load']))}, "
                f"zones {format_zones(d['contact_zones'])}, "
                f"δ/h = {_indentation_text(d['indentation'])}, "
                f"drag/P = {_fmt(_punch_drag(d, scene, k))}"
            )
    return lines


# ----------------------------------------------------------------------------
# Plots
# ----------------------------------------------------------------------------


def _plot_items(
    result: SceneResult,
) -> list[tuple[str, str, str, str, tuple[Curve, ...], bool]]:
    """(key, title, x label, y label, curves, log x) for each plottable result
    (key: the output's name, or ``sweep-<quantity>``)."""
    items = []
    for data in result.outputs.values():
        if data.curves:
            log_x = data.name == "critical_speed"
            items.append(
                (data.name, data.title, data.x_label, data.y_label, data.curves, log_x)
            )
    sw = result.sweep
    if sw is not None:
        spacing_log = (
            result.scene.sweep is not None and result.scene.sweep.spacing == "log"
        )
        for q in sw.quantities:
            curves = tuple(c for c in sw.curves(q) if np.isfinite(c.x).all())
            items.append(
                (
                    f"sweep-{q}",
                    f"{SWEEP_QUANTITIES[q]} against {_PARAM_LABELS[sw.param]}",
                    _PARAM_LABELS[sw.param],
                    _QUANTITY_LABELS[q],
                    curves,
                    spacing_log,
                )
            )
    return items


_COLOURS = (33, 34, 32, 31, 35, 36, 91, 94, 92, 95)
"""ANSI colour of each series' marker with ``color``."""


def _wrap_items(prefix: str, items: Sequence[str], width: int) -> list[str]:
    """``prefix`` then ``items``, three spaces apart, on as many lines as
    ``width`` needs (the next lines indented like the first item; an item
    longer than a line is cut with "…"). Widths count visible characters
    (an item's ANSI colour codes take no room)."""
    indent = " " * len(prefix)
    room = max(width - len(prefix), 2)
    lines: list[str] = []
    line = ""
    used = 0
    for item in items:
        size = len(plain(item))
        if size > room:
            item, size = plain(item)[: room - 1] + "…", room
        if line and used + 3 + size <= room:
            line += "   " + item
            used += 3 + size
        else:
            if line:
                lines.append(line)
            line, used = item, size
    if line:
        lines.append(line)
    return [(prefix if i == 0 else indent) + text for i, text in enumerate(lines)]


def ascii_plots(
    result: SceneResult, *, width: int = 80, height: int = 20, color: bool = False
) -> str:
    """ASCII plots (plotext) of every curve output and every sweep quantity.

    Each plot is its title, the frame with the curves, and under the frame
    (never over the curves) a line naming both axes with their units and,
    when the plot has several series, a legend: each series its own marker
    (and, with ``color``, its own colour). No line is wider than ``width``."""
    plt: Any = importlib.import_module("plotext")

    blocks = []
    for _, title, xl, yl, curves, log_x in _plot_items(result):
        shown = []
        for c in curves:
            mask = np.isfinite(c.x) & np.isfinite(c.y)
            if mask.sum() >= 1:
                shown.append((c, mask))
        if not shown:
            continue
        several = len(shown) > 1

        def draw(
            only: int | None,
            shown: list[tuple[Curve, Any]] = shown,
            title: str = title,
            log_x: bool = log_x,
            several: bool = several,
        ) -> str:
            """The plot with series ``only`` in its marker, the others blank."""
            plt.clear_figure()
            plt.plotsize(width, height)
            plt.theme("clear")
            order = [k for k in range(len(shown)) if k != only]
            order += [] if only is None else [only]
            for k in order:
                c, mask = shown[k]
                marker = BLANK
                if k == only:
                    marker = MARKERS[k % len(MARKERS)] if several else "braille"
                plt.plot(c.x[mask].tolist(), c.y[mask].tolist(), marker=marker)
            if log_x:
                plt.xscale("log")
            plt.title(title[:width])
            return str(plt.build())

        if several:
            frame, cells = compose(draw, len(shown))
            lines = _overlay(plain(frame).splitlines(), cells, color)
        else:
            lines = plain(draw(0)).splitlines()
        lines = [line.rstrip() for line in lines]
        x_axis = f"x axis: {xl or '-'}{' (log scale)' if log_x else ''}"
        lines += _wrap_items("  ", [x_axis, f"y axis: {yl or '-'}"], width)
        if several:
            legend = [
                f"{_paint(MARKERS[k % len(MARKERS)], k, color)} "
                f"{c.label or f'series {k + 1}'}"
                for k, (c, _) in enumerate(shown)
            ]
            lines += _wrap_items("  legend: ", legend, width)
        blocks.append("\n".join(lines))
    plt.clear_figure()
    return "\n\n".join(blocks)


def _paint(marker: str, k: int, color: bool) -> str:
    """``marker`` in series ``k``'s ANSI colour when ``color``."""
    if not color:
        return marker
    return f"\x1b[{_COLOURS[k % len(_COLOURS)]}m{marker}\x1b[0m"


def _overlay(lines: list[str], cells: Mapping[Cell, int], color: bool) -> list[str]:
    """The frame's ``lines`` with each cell's series marker written in."""
    rows: list[list[str]] = [list(line) for line in lines]
    for (i, j), k in cells.items():
        rows[i][j] = _paint(MARKERS[k % len(MARKERS)], k, color)
    return ["".join(row) for row in rows]


_LINE_STYLES = ("-", "--", "-.", ":")
_PNG_MARKERS = ("o", "s", "^", "x", "D", "v", "+", "*")


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend, or MissingExtraError."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MissingExtraError(
            "--png needs matplotlib: pip install 'movingpunch[png]'"
        ) from None
    return plt


def render_pngs(result: SceneResult) -> list[tuple[str, bytes]]:
    """(file name, PNG bytes) of one figure per curve output and sweep
    quantity (and per stress field); needs matplotlib (the ``png`` extra)."""
    plt = pyplot()
    stem = _stem(result.scene)
    rendered: list[tuple[str, bytes]] = []
    figures: list[tuple[str, Any]] = []
    try:
        for key, title, xl, yl, curves, log_x in _plot_items(result):
            fig, ax = plt.subplots(figsize=(6.4, 4.4))
            for k, c in enumerate(curves):
                # Line style and marker per curve: coinciding curves stay apart.
                ax.plot(
                    c.x,
                    c.y,
                    label=c.label or None,
                    linestyle=_LINE_STYLES[k % len(_LINE_STYLES)],
                    marker=_PNG_MARKERS[k % len(_PNG_MARKERS)],
                    markevery=max(len(c.x) // 12, 1),
                    markersize=4,
                )
            if log_x:
                ax.set_xscale("log")
            ax.set(title=title, xlabel=xl, ylabel=yl)
            ax.grid(True, alpha=0.3)
            if any(c.label for c in curves):
                ax.legend()
            figures.append((key, fig))
        fd = result.outputs.get("stress_field")
        if fd is not None:
            comp = result.scene.outputs["stress_field"].resolved_component()
            figures.append((f"stress_field-{comp}", field_figure(plt, fd, comp)))
        for name, fig in figures:
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=120)
            rendered.append((f"{stem}-{name}.png", buf.getvalue()))
    finally:
        for _, fig in figures:
            plt.close(fig)
    return rendered


def field_figure(plt: Any, fd: OutputData, comp: str) -> Any:
    """The figure of a ``stress_field`` output: one map of ``comp`` per
    curve. A point where the stress is infinite (a flat punch's sharp edges
    x = ±b on the surface) is masked out of the colours, marked with a
    magenta x and named by the legend ("masked: singular at x/h = ±0.5")."""
    n = len(fd.fields)
    fig, axes = plt.subplots(n, 1, figsize=(6.4, 2.6 * n), squeeze=False)
    for ax, (label, f) in zip(axes[:, 0], fd.fields, strict=True):
        values = np.ma.masked_invalid(getattr(f, comp))
        mesh = ax.pcolormesh(f.x, f.y, values, shading="auto", cmap="RdBu_r")
        fig.colorbar(mesh, ax=ax, label=f"{comp}/(P/h)")
        rows, cols = np.nonzero(np.ma.getmaskarray(values))
        if rows.size:
            ax.plot(
                f.x[cols],
                f.y[rows],
                "x",
                color="magenta",
                clip_on=False,
                label=singular_note(f.x[np.unique(cols)].tolist()),
            )
            ax.legend(loc="lower right", fontsize="small")
        ax.set(title=f"{comp} {label}".strip(), xlabel="x/h", ylabel="y/h")
    fig.tight_layout()
    return fig


def write_pngs(result: SceneResult, out_dir: Path) -> list[Path]:
    """Writes ``render_pngs(result)`` into ``out_dir`` (all or none);
    returns the paths written."""
    return publish(out_dir, render_pngs(result))


def _stem(scene: Scene) -> str:
    return safe_name(scene.name)


# ----------------------------------------------------------------------------
# CSV and JSON
# ----------------------------------------------------------------------------


_Table = tuple[str, str, Mapping[str, FloatArray], Mapping[str, Any]]


def _tables(result: SceneResult) -> list[_Table]:
    """(output, title, columns, details) of each output and of the sweep."""
    tables: list[_Table] = [
        (name, data.title, data.columns, data.details)
        for name, data in result.outputs.items()
    ]
    if result.sweep is not None:
        tables.append(
            ("sweep", f"sweep over {result.sweep.param}", result.sweep.columns(), {})
        )
    return tables


def format_tables(result: SceneResult) -> str:
    """Every output's numbers (and the sweep's) as plain-text tables: what
    the files hold, without their metadata, one block per output, columns
    aligned, values to 10 significant digits. ``movingpunch run`` prints it
    when its stdout is not a terminal (``| cat``, a file), where the ASCII
    plots would not serve."""
    blocks: list[str] = []
    for output, title, columns, _ in _tables(result):
        names = list(columns)
        if not names:
            continue
        cells = [[_fmt(float(v)) for v in np.ravel(columns[n])] for n in names]
        rows = max(len(c) for c in cells)
        widths = [
            max(len(n), *(len(x) for x in c)) for n, c in zip(names, cells, strict=True)
        ]
        lines = [f"Output {output}: {title}"]
        lines.append(
            "  " + "  ".join(n.ljust(w) for n, w in zip(names, widths, strict=True))
        )
        for i in range(rows):
            row = (c[i] if i < len(c) else "" for c in cells)
            lines.append(
                "  "
                + "  ".join(
                    v.ljust(w) for v, w in zip(row, widths, strict=True)
                ).rstrip()
            )
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def _metadata(result: SceneResult, output: str, title: str) -> dict[str, str]:
    return {
        "movingpunch_version": version(),
        "scene_name": result.scene.name,
        "output": output,
        "title": title,
        **(
            {"medium": result.scene.medium.describe()}
            if result.scene.medium is not None
            else {}
        ),
        # Every point's unmet accuracy, " | "-separated ("none": all met).
        "warnings": " | ".join(result.warnings) if result.warnings else "none",
    }


def stream_outputs(
    result: SceneResult, fmt: str = "csv"
) -> list[tuple[str, Iterable[bytes]]]:
    """(file name, content in pieces) of one ``<scene>-<output>.csv`` (or
    ``.json``) per output and one for the sweep, each with the scene (as
    TOML) and the package version as metadata. The pieces are made as they
    are written (``publish``): a long sweep's file never sits whole in
    memory."""
    if fmt not in ("csv", "json"):
        raise ValueError(f"format must be 'csv' or 'json', got {fmt!r}")
    stem = _stem(result.scene)
    scene_toml = result.scene.to_toml()
    pieces = _csv_pieces if fmt == "csv" else _json_pieces
    return [
        (
            f"{stem}-{output}.{fmt}",
            _encoded(
                pieces(_metadata(result, output, title), scene_toml, columns, details)
            ),
        )
        for output, title, columns, details in _tables(result)
    ]


def _encoded(pieces: Iterable[str]) -> Iterator[bytes]:
    for piece in pieces:
        yield piece.encode("utf-8")


def render_outputs(result: SceneResult, fmt: str = "csv") -> list[tuple[str, bytes]]:
    """``stream_outputs`` with each file's content whole."""
    return [(name, b"".join(body)) for name, body in stream_outputs(result, fmt)]


def write_outputs(result: SceneResult, out_dir: Path, fmt: str = "csv") -> list[Path]:
    """Writes ``stream_outputs(result, fmt)`` into ``out_dir`` (created if
    missing): every file or, on a failure, none (``publish``). Returns the
    paths written."""
    return publish(out_dir, stream_outputs(result, fmt))


_ROWS = 4096
"""Rows of a table formatted at a time."""


def _csv_pieces(
    meta: Mapping[str, str],
    scene_toml: str,
    columns: Mapping[str, FloatArray],
    details: Mapping[str, Any] | None = None,
) -> Iterator[str]:
    lines = [f"# {k}: {v}" for k, v in meta.items()]
    # Details (contact zones, per-punch results): one JSON text a line.
    lines += [
        f"# {k}: {json.dumps(_json_safe(v), allow_nan=False)}"
        for k, v in (details or {}).items()
    ]
    lines.append("# columns: " + ",".join(columns))
    lines.append("# scene:")
    lines += [f"#   {line}" if line else "#" for line in scene_toml.splitlines()]
    yield "\n".join(lines) + "\n"
    arrays = [np.asarray(v, dtype=np.float64) for v in columns.values()]
    n = len(arrays[0]) if arrays else 0
    for start in range(0, n, _ROWS):
        rows = zip(*(a[start : start + _ROWS].tolist() for a in arrays), strict=True)
        yield "".join(",".join(map(repr, row)) + "\n" for row in rows)


def _csv(
    meta: Mapping[str, str],
    scene_toml: str,
    columns: Mapping[str, FloatArray],
    details: Mapping[str, Any] | None = None,
) -> str:
    return "".join(_csv_pieces(meta, scene_toml, columns, details))


def _json_float(x: float) -> float | str:
    return (
        x
        if math.isfinite(x)
        else ("nan" if math.isnan(x) else ("inf" if x > 0 else "-inf"))
    )


def _json_safe(value: Any) -> Any:
    """``value`` (details: nested lists and dicts of numbers and strings)
    with non-finite floats as the strings "nan", "inf", "-inf"."""
    if isinstance(value, Mapping):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return _json_float(float(value))
    return value


_DETAILS = ("contact_zones", "punches")
"""The details an output may carry (``OutputData.details``)."""


def _json_data(
    columns: Mapping[str, FloatArray], details: Mapping[str, Any] | None = None
) -> dict[str, Any]:
    """An output's details and columns as JSON values (non-finite floats as
    "nan", "inf", "-inf"): the data of a JSON file and of ``format_json``."""
    return {
        **{k: _json_safe(v) for k, v in (details or {}).items()},
        "columns": {
            k: [_json_float(float(x)) for x in np.asarray(v, dtype=np.float64)]
            for k, v in columns.items()
        },
    }


def _json_pieces(
    meta: Mapping[str, str],
    scene_toml: str,
    columns: Mapping[str, FloatArray],
    details: Mapping[str, Any] | None = None,
) -> Iterator[str]:
    """The text of ``json.dumps(doc, indent=1)`` of the file's document
    (its metadata, details, scene and columns), the columns formatted
    ``_ROWS`` values at a time."""
    data = {k: _json_safe(v) for k, v in (details or {}).items()}
    doc = {**meta, **data, "scene": scene_toml, "columns": {}}
    head = json.dumps(doc, indent=1, allow_nan=False)
    tail = "{}\n}"
    assert head.endswith(tail)
    if not columns:
        yield head + "\n"
        return
    yield head[: -len(tail)] + "{\n"
    for i, (name, values) in enumerate(columns.items()):
        key = ("" if i == 0 else ",\n") + "  " + json.dumps(name) + ": "
        arr = np.asarray(values, dtype=np.float64)
        if len(arr) == 0:
            yield key + "[]"
            continue
        yield key + "[\n"
        for start in range(0, len(arr), _ROWS):
            block = arr[start : start + _ROWS].tolist()
            text = ",\n".join("   " + json.dumps(_json_float(x)) for x in block)
            yield text + (",\n" if start + _ROWS < len(arr) else "\n")
        yield "  ]"
    yield "\n }\n}\n"


def _json(
    meta: Mapping[str, str],
    scene_toml: str,
    columns: Mapping[str, FloatArray],
    details: Mapping[str, Any] | None = None,
) -> str:
    return "".join(_json_pieces(meta, scene_toml, columns, details))


def format_json(result: SceneResult, hints: Sequence[str] = ()) -> str:
    """The whole run as one JSON document (``movingpunch run --format json``
    without ``--out`` prints it): the package version, the scene (TOML) and
    its parameters, the warnings and plausibility ``hints``, every output's
    (and the sweep's) title, details and columns as the JSON files hold
    them (non-finite numbers as "nan", "inf", "-inf"), and the stages."""
    doc: dict[str, Any] = {
        "movingpunch_version": version(),
        "scene_name": result.scene.name,
        "scene": result.scene.to_toml(),
        "params": _json_safe(dict(result.scene.params)),
        **(
            {"medium": _json_safe(result.scene.medium.to_dict())}
            if result.scene.medium is not None
            else {}
        ),
        "warnings": list(result.warnings),
        "hints": list(hints),
        "outputs": {
            output: {"title": title, **_json_data(columns, details)}
            for output, title, columns, details in _tables(result)
        },
        "stages": [
            {"name": s.name, "count": s.count, "seconds": s.seconds}
            for s in result.stages
        ],
        "total_seconds": result.total_seconds,
        "jobs": result.jobs,
    }
    return json.dumps(doc, indent=1, allow_nan=False) + "\n"


def read_csv(path: str | Path) -> tuple[dict[str, Any], dict[str, FloatArray]]:
    """Reads a CSV written by ``write_outputs``: (metadata, columns).

    The metadata holds the ``#`` header fields and ``scene``, the ``Scene``
    the file came from. The numbers alone load with
    ``np.loadtxt(path, delimiter=",")`` (every header line is a comment).
    """
    text = Path(path).read_text(encoding="utf-8")
    meta: dict[str, Any] = {}
    names: list[str] = []
    toml_lines: list[str] = []
    in_scene = False
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        body = line[1:]
        if in_scene:
            toml_lines.append(body[3:] if body.startswith("   ") else body.strip())
            continue
        key, _, value = body.strip().partition(": ")
        if body.strip() == "scene:":
            in_scene = True
        elif key == "columns":
            names = value.split(",")
        elif key in _DETAILS:
            meta[key] = json.loads(value)
        else:
            meta[key] = value
    meta["scene"] = Scene.from_toml("\n".join(toml_lines) + "\n", f"{path} (metadata)")
    data = np.loadtxt(path, delimiter=",", ndmin=2)
    columns = {name: data[:, i] for i, name in enumerate(names)}
    return meta, columns


def read_json(path: str | Path) -> tuple[dict[str, Any], dict[str, FloatArray]]:
    """Reads a JSON file written by ``write_outputs``: (metadata, columns)."""
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    raw_columns = doc.pop("columns")
    doc["scene"] = Scene.from_toml(doc["scene"], f"{path} (metadata)")
    columns = {
        k: np.asarray([float(x) for x in v], dtype=np.float64)
        for k, v in raw_columns.items()
    }
    return doc, columns
