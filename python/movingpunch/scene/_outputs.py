"""The outputs of a scene: each ``_out_*`` evaluates one kind of output
(``OUTPUT_KINDS``) on the solutions of the scene's curves, one per vary value,
timing its work as a stage of the run.

Every output reads the solutions through the contract (``ContactSolution``):
damped points (docs/damped.md) differ only in their values (an asymmetric
contact, a drag).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from movingpunch.contract import ContactSolution
from movingpunch.fields import StressField
from movingpunch.media import Medium, Winkler
from movingpunch.regime import given_indentation
from movingpunch.scene._model import STRESS_COMPONENTS, point_medium
from movingpunch.scene._result import (
    Curve,
    FloatArray,
    OutputData,
    column_name,
)
from movingpunch.scene._solve import RunState, curve_label, radius_ratio
from movingpunch.scene._validate import critical_speed
from movingpunch.solver import critical_vstar, critical_wavenumber, rayleigh_vstar

__all__ = ["OUTPUTS"]


_Solutions = Mapping[float | None, ContactSolution]


def _curves(
    run: RunState,
    stage: str,
    solutions: _Solutions,
    x: FloatArray,
    evaluate: Callable[[ContactSolution, Mapping[str, float]], FloatArray],
) -> tuple[Curve, ...]:
    scene = run.scene
    param = scene.vary.param if scene.vary is not None else None
    out = []
    for v, s in solutions.items():
        p = scene.point(v)
        with run.timed(stage):
            y = evaluate(s, p)
        out.append(Curve(curve_label(param, v), v, x, np.asarray(y, dtype=np.float64)))
    return tuple(out)


def _curve_columns(
    xname: str, yname: str, curves: Sequence[Curve]
) -> dict[str, FloatArray]:
    cols: dict[str, FloatArray] = {xname: curves[0].x}
    for c in curves:
        cols[column_name(yname, c.label)] = c.y
    return cols


def _x_grid(
    spec_x: tuple[float, float] | None, default: tuple[float, float], n: int
) -> FloatArray:
    lo, hi = spec_x if spec_x is not None else default
    return np.linspace(lo, hi, n)


def _out_contact_width(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    """The contact of every curve: its ends (x_back, x_front) = (-a, a) when
    symmetric, the drag (0 without damping), p(0), the indentation."""
    scene = run.scene
    cols: dict[str, list[float]] = {}
    if scene.vary is not None:
        cols[scene.vary.param] = []
    names = ["a", "contact_start", "contact_end", "drag", "p0", "indentation"]
    for name in [*names, "zones", "valid", "error_estimate", "collocation_n"]:
        cols[name] = []
    zones: list[list[list[float]]] = []
    punches: list[list[dict[str, object]]] = []
    for v, s in solutions.items():
        p = scene.point(v)
        if scene.vary is not None:
            cols[scene.vary.param].append(float(v) if v is not None else math.nan)
        cols["a"].append(s.a)
        cols["contact_start"].append(s.contact_interval[0])
        cols["contact_end"].append(s.contact_interval[1])
        # Solutions are shared through lambda = radius * load: the drag
        # (int p x/R dx / P) scales as 1/radius, the indentation as the load.
        cols["drag"].append(s.drag * radius_ratio(s.radius, p["radius"]))
        cols["p0"].append(s.p0)
        cols["indentation"].append(given_indentation(s) * p["load"] / s.load)
        cols["zones"].append(float(len(s.contact_zones)))
        zones.append([[float(lo), float(hi)] for lo, hi in s.contact_zones])
        punches.append(_punch_dicts(s, p["load"] / s.load))
        cols["valid"].append(1.0 if s.valid else 0.0)
        cols["error_estimate"].append(s.error_estimate)
        cols["collocation_n"].append(float(s.collocation_n))
    details: dict[str, Any] = {"contact_zones": zones, "punches": punches}
    return OutputData(
        name="contact_width",
        title="Contact half-width",
        x_label=scene.vary.param if scene.vary is not None else "",
        y_label="a/h",
        columns={k: np.asarray(v, dtype=np.float64) for k, v in cols.items()},
        details=details,
    )


def _punch_dicts(s: ContactSolution, scale: float) -> list[dict[str, object]]:
    """``to_dict()`` of each punch of ``s`` (``ContactSolution.punches``: a
    single contact's one too); loads and indentations times ``scale`` (a
    solution shared through lambda = radius * load, like the indentation)."""
    out: list[dict[str, object]] = []
    for punch in s.punches:
        d = punch.to_dict()
        if scale != 1.0:
            d["load"] = punch.load * scale
            d["zone_loads"] = [x * scale for x in punch.zone_loads]
            given = d["indentation"]  # None where the medium does not give it
            d["indentation"] = None if given is None else punch.indentation * scale
        out.append(d)
    return out


def _hull_range(
    solutions: _Solutions, default: tuple[float, float]
) -> tuple[float, float]:
    """``default``, widened to the hull of the contact zones and 1 h beyond
    where a solution has several zones (a separated contact, a train)."""
    lo, hi = default
    for s in solutions.values():
        if len(s.contact_zones) > 1:
            start, end = s.contact_interval
            lo, hi = min(lo, start - 1.0), max(hi, end + 1.0)
    return lo, hi


def _out_pressure(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    # 1.25 x the farthest contact end of every curve (the hull of several
    # zones: contact_interval), so that an off-centre contact is covered too.
    reach = max(abs(e) for s in solutions.values() for e in s.contact_interval)
    default = (-1.25 * reach, 1.25 * reach)
    x = _x_grid(spec.x, default, spec.resolved_points())
    curves = _curves(
        run, "pressure", solutions, x, lambda s, p: np.asarray(s.pressure(x))
    )
    return OutputData(
        "pressure",
        "Contact pressure",
        "x/h",
        "p/(P/h)",
        _curve_columns("x", "p", curves),
        curves,
    )


def _curve_output(
    run: RunState,
    solutions: _Solutions,
    kind: str,
    labels: tuple[str, str, str],
    grid: tuple[str, FloatArray],
    evaluate: Callable[[ContactSolution, Mapping[str, float]], FloatArray],
) -> OutputData:
    """One curve per solution of ``evaluate`` on the grid, as the output
    ``kind`` with (title, x label, y label) and the column names
    (grid name, "sigma_x")."""
    name, x = grid
    curves = _curves(run, kind, solutions, x, evaluate)
    return OutputData(kind, *labels, _curve_columns(name, "sigma_x", curves), curves)


def _out_surface_stress(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    x = _x_grid(spec.x, _hull_range(solutions, (-3.0, 3.0)), spec.resolved_points())
    return _curve_output(
        run,
        solutions,
        "surface_stress",
        ("In-plane stress on the top surface", "x/h", "sigma_x(x, 0)/(P/h)"),
        ("x", x),
        lambda s, p: np.asarray(s.surface_stress(x), dtype=np.float64),
    )


def _out_depth_stress(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    lo, hi = spec.resolved_y()
    y = np.linspace(lo, hi, spec.resolved_points())
    return _curve_output(
        run,
        solutions,
        "depth_stress",
        ("In-plane stress under the centre", "y/h", "sigma_x(0, y)/(P/h)"),
        ("y", y),
        lambda s, p: np.asarray(s.depth_stress(y), dtype=np.float64),
    )


def _out_displacement(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    x = _x_grid(spec.x, _hull_range(solutions, (-3.0, 3.0)), spec.resolved_points())
    depth = spec.resolved_depth()
    curves = _curves(
        run,
        "displacement",
        solutions,
        x,
        # v = load * V(x; lambda): rescale a solution shared through lambda.
        lambda s, p: s.displacement(x, depth) * (p["load"] / s.load),
    )
    return OutputData(
        "displacement",
        f"Vertical displacement at y/h = {depth:g}",
        "x/h",
        "v/h",
        _curve_columns("x", "v", curves),
        curves,
    )


def _out_stress_field(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    scene = run.scene
    x = _x_grid(spec.x, _hull_range(solutions, (-2.0, 2.0)), spec.resolved_points())
    lo, hi = spec.resolved_y()
    y = np.linspace(lo, hi, spec.resolved_depth_points())
    param = scene.vary.param if scene.vary is not None else None
    fields_: list[tuple[str, StressField]] = []
    cols: dict[str, list[FloatArray]] = {}
    for v, s in solutions.items():
        with run.timed("stress_field"):
            f = s.stress_field(x, y)
        label = curve_label(param, v)
        fields_.append((label, f))
        gx, gy = np.meshgrid(f.x, f.y)
        if param is not None:
            cols.setdefault(param, []).append(
                np.full(gx.size, float(v) if v is not None else math.nan)
            )
        cols.setdefault("x", []).append(gx.ravel())
        cols.setdefault("y", []).append(gy.ravel())
        for comp in STRESS_COMPONENTS:
            cols.setdefault(comp, []).append(np.asarray(getattr(f, comp)).ravel())
    return OutputData(
        "stress_field",
        "Stresses in the layer",
        "x/h",
        "y/h",
        {k: np.concatenate(v) for k, v in cols.items()},
        (),
        tuple(fields_),
    )


def _out_medium_critical_speed(run: RunState, spec: Any, medium: Medium) -> OutputData:
    """V*_cr of a layered medium or a half-space base: one row per curve
    (its springs those of the curve's point), or a curve over spec.kw per
    curve (springs; validation refuses a kw range under a half-space). kw is
    nan under a half-space (no springs)."""
    scene = run.scene
    curves: list[Curve] = []
    rows: list[tuple[float, float, float, float, float, float]] = []
    several = len(scene.curve_values()) > 1
    param = scene.vary.param if scene.vary is not None else None
    for v in scene.curve_values():
        m = point_medium(medium, scene.point(v))
        media = [m]
        if spec.kw is not None:
            assert isinstance(m.base, Winkler)
            grid = np.geomspace(spec.kw[0], spec.kw[1], spec.resolved_points())
            media = [
                Medium(m.layers, Winkler(float(k), m.base.kp, m.base.damping))
                for k in grid
            ]
        start = len(rows)
        for mk in media:
            springs = mk.base if isinstance(mk.base, Winkler) else None
            with run.timed("critical_speed"):
                vcr = critical_vstar(layers=list(mk.layers), base=mk.base)
                alpha = critical_wavenumber(layers=list(mk.layers), base=mk.base)
            rows.append(
                (
                    springs.kw if springs else math.nan,
                    mk.nu,
                    vcr,
                    alpha,
                    rayleigh_vstar(mk.nu),
                    springs.kp if springs else math.nan,
                )
            )
        if spec.kw is not None:
            block = np.asarray(rows[start:], dtype=np.float64)
            label = curve_label(param, v) if several else ""
            curves.append(
                Curve(label, v if several else None, block[:, 0], block[:, 2])
            )
    table = np.asarray(rows, dtype=np.float64).reshape(-1, 6)
    names = ("kw", "nu", "critical_vstar", "critical_wavenumber", "rayleigh_vstar")
    return OutputData(
        "critical_speed",
        f"Critical speed ({medium.describe()})",
        "kw = k_w h/mu",
        "V*_cr",
        {n: table[:, i] for i, n in enumerate(names)},
        tuple(curves),
    )


def _out_critical_speed(run: RunState, spec: Any, solutions: _Solutions) -> OutputData:
    scene = run.scene
    if scene.medium is not None and not scene.medium.homogeneous:
        return _out_medium_critical_speed(run, spec, scene.medium)
    # (kw, nu, kp): kp (the Pasternak shear layer) 0 unless the scene sets it.
    combos: list[tuple[float, float, float]] = []
    for v in scene.curve_values():
        p = scene.point(v)
        if (p["kw"], p["nu"], p.get("kp", 0.0)) not in combos:
            combos.append((p["kw"], p["nu"], p.get("kp", 0.0)))
    pairs = list(dict.fromkeys((nu, kp) for _, nu, kp in combos))
    pasternak = any(kp for _, _, kp in combos)
    curves: list[Curve] = []
    if spec.kw is not None:
        grid = np.geomspace(spec.kw[0], spec.kw[1], spec.resolved_points())
        combos = [(float(k), nu, kp) for nu, kp in pairs for k in grid]
    rows = []
    for kw, nu, kp in combos:
        with run.timed("critical_speed"):
            vcr, alpha = critical_speed(kw, nu, kp)
        rows.append((kw, nu, vcr, alpha, rayleigh_vstar(nu), kp))
    table = np.asarray(rows, dtype=np.float64).reshape(-1, 6)
    if spec.kw is not None:
        n = spec.resolved_points()
        kps = list(dict.fromkeys(kp for _, kp in pairs))
        for i, (nu, kp) in enumerate(pairs):
            block = table[i * n : (i + 1) * n]
            # One curve per nu (and per kp where a scene varies it).
            param, value = ("kp", kp) if len(kps) > 1 else ("nu", nu)
            several = len(pairs) > 1
            label = curve_label(param, value) if several else ""
            curves.append(
                Curve(label, value if several else None, block[:, 0], block[:, 2])
            )
    names: tuple[str, ...] = (
        "kw",
        "nu",
        "critical_vstar",
        "critical_wavenumber",
        "rayleigh_vstar",
    )
    if pasternak:  # the kp column only where the scene sets kp
        names += ("kp",)
    return OutputData(
        "critical_speed",
        "Critical speed",
        "kw = k_w h/mu",
        "V*_cr",
        {n: table[:, i] for i, n in enumerate(names)},
        tuple(curves),
    )


OUTPUTS: dict[str, Callable[[RunState, Any, _Solutions], OutputData]] = {
    "contact_width": _out_contact_width,
    "pressure": _out_pressure,
    "surface_stress": _out_surface_stress,
    "depth_stress": _out_depth_stress,
    "stress_field": _out_stress_field,
    "displacement": _out_displacement,
    "critical_speed": _out_critical_speed,
}
