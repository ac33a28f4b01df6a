"""Independent checks of a solution, and a worker process that applies them
under a per-call time bound (issue 25: the honesty fuzz of test_fuzz.py).

A result is checked without the solver's own verdicts (``valid``,
``min_pressure``, ``min_gap``):

* equilibrium: int p dx = 1 (p over P/h) by Gauss-Legendre in the angle,
  x = c + w cos(theta) (the square-root ends, bounded or singular, become
  smooth);
* p >= 0 on the contact up to its own error estimate;
* the gap -delta + f(x) - v(x, 0) is >= 0 beside the contact and 0 on it, up
  to a/h's error estimate carried into it;
* the error estimate bounds the actual error: the contact's ends (a flat
  punch's end coefficients) against a reference at automatic N and 1e-3 of
  the tol (1e-8 at most, 1e-10 at least), whose own estimate is allowed for,
  above a round-off floor of 1e-10 relative.

A result that says it is not to be trusted (``valid`` False, or a warning
that tol is not met or that a sign is not resolved) is exempt from the
accuracy checks; its estimate must still bound its error (a fixed small N
must not claim 1e-13). ``Worker`` runs ``check_case`` in a spawned process
and kills it when a call exceeds its time bound.
"""

from __future__ import annotations

import itertools
import math
import multiprocessing
import time
import traceback
from typing import Any

import numpy as np
import psutil

# Relative floor of the sign and gap checks (the solver's own floor: a
# pressure below -1e-6 of its peak is negative).
FLOOR = 1e-6
REFERENCE_TOL = 1e-10
# Errors below this (relative) are round-off of the kernel tables (built to
# 1e-10 at the loosest), not a dishonest estimate.
ROUNDOFF = 1e-10


def _warned(sol: Any) -> bool:
    """The result names something it does not meet (every warning of the
    solvers says that a tol, an estimate or a sign is not met: the zone
    solver's "exceeds tol" and "did not converge at N" too)."""
    from movingpunch.solver import result_warnings

    return bool(result_warnings(sol))


def _load(sol: Any, lo: float, hi: float) -> float:
    """int_lo^hi p dx by composite Gauss-Legendre in theta (x = c + w cos
    theta; 64 panels of 16 nodes: a rounded flat's pressure has kinks)."""
    t, wts = np.polynomial.legendre.leggauss(16)
    edges = np.linspace(0.0, math.pi, 65)
    half = 0.5 * (edges[1:] - edges[:-1])
    theta = (0.5 * (edges[1:] + edges[:-1]))[:, None] + half[:, None] * t[None, :]
    weights = (half[:, None] * wts[None, :]).ravel()
    theta = theta.ravel()
    c, w = 0.5 * (lo + hi), 0.5 * (hi - lo)
    p = np.asarray(sol.pressure(c + w * np.cos(theta)), dtype=float)
    return float(np.sum(weights * p * w * np.sin(theta)))


def _zones(sol: Any) -> list[tuple[float, float]]:
    return [(float(lo), float(hi)) for lo, hi in sol.contact_zones]


def _height(sol: Any, x: np.ndarray) -> np.ndarray:
    return np.asarray(sol.profile.height(x), dtype=float)


def _ends(sol: Any) -> np.ndarray:
    return np.array([z for zone in _zones(sol) for z in zone])


def _pressure_slack(sol: Any, pmax: float) -> float:
    est = getattr(sol, "pressure_error_estimate", 0.0)
    return FLOOR * pmax + (float(est) if math.isfinite(est) else math.inf)


def _reference(kind: str, args: dict[str, Any]) -> Any:
    import movingpunch as mp

    tol = float(args.get("tol", 1e-8))
    ref_tol = max(REFERENCE_TOL, min(1e-8, 1e-3 * tol))
    # the same contact mode (a separated contact's reference separates too)
    ref_args = {**args, "tol": ref_tol, "n": None}
    if kind == "punches":
        return mp.solve_punches(**ref_args)
    return mp.solve(**ref_args)


def _surface_points(
    zones: list[tuple[float, float]],
) -> tuple[np.ndarray, np.ndarray]:
    """Points on the contact (41 in each zone, clear of its ends) and beside
    it (in every gap between zones and out to twice the hull's half-width on
    either side): the surface must follow the punch on every zone, and
    clear it between and beside the zones."""
    theta = np.linspace(0.05, math.pi - 0.05, 41)
    inside = np.concatenate(
        [0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(theta) for lo, hi in zones]
    )
    lo, hi = zones[0][0], zones[-1][1]
    w = 0.5 * (hi - lo)
    q = np.linspace(0.05, 1.0, 24)
    g = np.linspace(0.0, 1.0, 26)[1:-1]
    beside = [lo - 2 * w * q * q, hi + 2 * w * q * q]
    beside += [r + (left - r) * g for (_, r), (left, _) in itertools.pairwise(zones)]
    return inside, np.concatenate(beside)


def checks(kind: str, args: dict[str, Any], sol: Any) -> list[str]:
    """The independent checks of a valid ``sol`` of ``args``: the failures
    (empty if it passes)."""
    fails: list[str] = []
    trusted = bool(sol.valid) and not _warned(sol)
    zones = _zones(sol)
    flat = sol.profile.kind == "flat"
    # equilibrium
    # (to the pressure's error estimate over the contact's width)
    # (the undamped Solution's: its series' truncation, a profile's kinks)
    est_p = float(
        getattr(
            sol,
            "pressure_error_estimate",
            getattr(getattr(sol, "_impl", None), "series_truncation", 0.0),
        )
    )
    width = sum(hi - lo for lo, hi in zones)
    slack = 1e-6 + width * est_p
    if kind == "punches":
        for k, punch in enumerate(sol.punches):
            got = sum(_load(punch, lo, hi) for lo, hi in punch.contact_zones)
            if not abs(got - 1.0) <= slack * sol.load / punch.load:
                fails.append(f"punch {k}: int p = {got!r}, not 1")
    else:
        got = sum(_load(sol, lo, hi) for lo, hi in zones)
        if not abs(got - 1.0) <= slack:
            fails.append(f"int p = {got!r}, not 1 (estimate {est_p!r})")
    # p >= 0 on the contact (a flat punch's inner points: p is infinite at
    # its edges)
    r = np.cos(np.linspace(0.0, math.pi, 401))[1:-1]
    pmin, pmax = math.inf, 0.0
    for lo, hi in zones:
        c, w = 0.5 * (lo + hi), 0.5 * (hi - lo)
        p = np.asarray(sol.pressure(c + w * r), dtype=float)
        weight = np.sqrt(1.0 - r * r)
        g = p * weight if flat else p
        pmin = min(pmin, float(np.min(g)))
        pmax = max(pmax, float(np.max(np.abs(g))))
    if trusted and pmin < -_pressure_slack(sol, pmax):
        fails.append(f"p < 0 on the contact: min {pmin!r} (max {pmax!r})")
    # the gap (single punches: one indentation)
    if kind == "solve" and not flat:
        lo, hi = zones[0][0], zones[-1][1]
        w = 0.5 * (hi - lo)
        delta = float(sol.indentation)
        scale = max(abs(delta), float(np.max(np.abs(_height(sol, np.array([lo, hi]))))))
        rel = float(sol.error_estimate) / w if math.isfinite(sol.error_estimate) else 0
        slack = max(FLOOR, 10.0 * rel) * scale
        inside, outside = _surface_points(zones)
        table = getattr(sol.profile, "x", None)
        if table is not None:  # beyond a table: no punch there
            outside = outside[(outside >= table[0]) & (outside <= table[-1])]
        gap = -delta + _height(sol, outside) - sol.surface_displacement(outside)
        if trusted and outside.size and float(np.min(gap)) < -slack:
            fails.append(f"penetration beside the contact: min gap {np.min(gap)!r}")
        on = -delta + _height(sol, inside) - sol.surface_displacement(inside)
        if trusted and float(np.max(np.abs(on))) > max(1e-3 * scale, slack):
            fails.append(
                f"surface off the punch on the contact: {np.max(np.abs(on))!r}"
            )
    # estimate >= error, against a reference
    try:
        ref = _reference(kind, args)
    except Exception:  # the reference refused (tol 1e-10 out of reach): no comparison
        return fails
    if flat and kind == "solve":
        got_k = np.asarray(sol.end_coefficients, dtype=float)
        ref_k = np.asarray(ref.end_coefficients, dtype=float)
        est = float(sol.end_coefficient_error)
        est_ref = float(ref.end_coefficient_error)
        err = float(np.max(np.abs(got_k - ref_k)))
        if not err <= est + est_ref + ROUNDOFF * float(np.max(np.abs(ref_k))):
            fails.append(f"end coefficients off by {err!r}, estimate {est!r}")
        return fails
    got_e, ref_e = _ends(sol), _ends(ref)
    if got_e.shape != ref_e.shape:
        if trusted:
            fails.append(
                f"contact set {_zones(sol)} differs from the reference's {_zones(ref)}"
            )
        return fails
    err = float(np.max(np.abs(got_e - ref_e)))
    est = float(sol.error_estimate)
    est_ref = float(ref.error_estimate)
    if not err <= est + est_ref + ROUNDOFF * float(np.max(np.abs(ref_e))):
        fails.append(
            f"ends off by {err!r}, error_estimate {est!r} (reference's {est_ref!r})"
        )
    return fails


def check_case(case: dict[str, Any]) -> dict[str, Any]:
    """Solves ``case`` ({"kind": "solve" | "punches", "args": ...}) and checks
    it: {"outcome": "valid" | "flagged" | error class name, "fails": [...]}."""
    import movingpunch as mp
    from movingpunch import errors

    kind, args = case["kind"], dict(case["args"])
    call = dict(args)
    if kind == "punches":
        call["punches"] = [mp.Punch(*p[:2], at=p[2]) for p in args["punches"]]
    try:
        sol = mp.solve_punches(**call) if kind == "punches" else mp.solve(**call)
    except Exception as exc:
        ok = type(exc).__module__ == errors.__name__
        return {"outcome": type(exc).__name__, "fails": [] if ok else [repr(exc)]}
    try:
        fails = checks(kind, call, sol)
    except Exception:
        fails = ["checking raised: " + traceback.format_exc(limit=3)]
    return {
        "outcome": "valid" if sol.valid else "flagged",
        "warned": _warned(sol),
        "fails": fails,
    }


def _serve(conn: Any) -> None:
    while True:
        try:
            case = conn.recv()
        except EOFError:
            return
        conn.send(check_case(case))


class Worker:
    """One spawned process answering check_case; a call that takes longer
    than its bound is killed (the process is then restarted)."""

    def __init__(self) -> None:
        self._ctx = multiprocessing.get_context("spawn")
        self._start()

    def _start(self) -> None:
        self._conn, child = self._ctx.Pipe()
        self._proc = self._ctx.Process(target=_serve, args=(child,), daemon=True)
        self._proc.start()
        child.close()

    def _cpu(self) -> float:
        try:
            t = psutil.Process(self._proc.pid).cpu_times()
        except psutil.Error:
            return 0.0
        return float(t.user + t.system)

    def call(self, case: dict[str, Any], timeout: float) -> dict[str, Any]:
        """The worker's answer; "timeout" when the call used more than
        `timeout` seconds of the worker's CPU (a loaded machine stretches the
        wall clock, not the work), or ten times that of wall time."""
        start_cpu = self._cpu()
        deadline = time.monotonic() + 10.0 * timeout
        self._conn.send(case)
        while not self._conn.poll(0.25):
            if self._cpu() - start_cpu > timeout or time.monotonic() > deadline:
                self._restart()
                return {"outcome": "timeout", "fails": []}
        try:
            answer: dict[str, Any] = self._conn.recv()
            return answer
        except (EOFError, OSError):  # the worker died mid-answer
            pass
        self._restart()
        return {"outcome": "crash", "fails": ["the worker died"]}

    def _restart(self) -> None:
        self._proc.kill()
        self._proc.join()
        self._conn.close()
        self._start()

    def close(self) -> None:
        self._conn.close()
        self._proc.join(5.0)
        if self._proc.is_alive():
            self._proc.kill()
            self._proc.join()
