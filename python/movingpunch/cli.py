"""Command-line interface: ``movingpunch solve ...`` and ``movingpunch critical ...``.

``solve --stress`` adds the peaks of sigma_x/(P/h) (``Solution.stress_peaks``).

Bad arguments and every MovingPunchError/ValueError end in one line
``movingpunch: error: ...`` on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import dataclasses
import io
import json
import math
import sys
from collections.abc import Callable, Sequence
from typing import NoReturn

from movingpunch.errors import MovingPunchError
from movingpunch.fields import StressPeaks
from movingpunch.solver import (
    Solution,
    critical_vstar,
    critical_wavenumber,
    rayleigh_vstar,
    solve,
)

PROG = "movingpunch"
EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line: ``movingpunch: error: ...``."""

    def error(self, message: str) -> NoReturn:
        hint = f" (see `{self.prog} --help`)"
        _fail(message + hint)


def _fail(message: str) -> NoReturn:
    one_line = " ".join(message.split())
    sys.stderr.write(f"{PROG}: error: {one_line}\n")
    raise SystemExit(EXIT_USAGE)


def _number(what: str) -> Callable[[str], float]:
    """argparse type: a float (``inf`` and ``nan`` parse; ranges are checked
    by the solver, which names the parameter and its range)."""

    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be a real number ({what}), got {text!r}"
            ) from None

    return parse


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG,
        description=(
            "Rigid cylindrical punch sliding over an elastic layer on a Winkler "
            "foundation. All inputs are dimensionless (h = 1, mu = 1)."
        ),
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    solve_p = sub.add_parser(
        "solve",
        help="solve the contact problem",
        description="Solve the contact problem and print a/h, p0, indentation, ...",
    )
    solve_p.add_argument(
        "--vstar",
        type=_number("0 <= V* < V*_cr"),
        required=True,
        help="V* = rho V^2/mu, 0 <= V* < V*_cr",
    )
    solve_p.add_argument(
        "--kw",
        type=_number("0 < k_w h/mu <= inf"),
        required=True,
        help="k_w h/mu in [1e-12, inf] ('inf': smooth rigid base)",
    )
    solve_p.add_argument(
        "--radius", type=_number("R/h > 0"), required=True, help="R/h > 0"
    )
    solve_p.add_argument(
        "--load",
        type=_number("P/(mu h) > 0"),
        required=True,
        help="P/(mu h) > 0 (the paper's mu/(P/h) = 500 is 0.002)",
    )
    solve_p.add_argument(
        "--nu",
        type=_number("0 <= nu < 0.5"),
        default=0.2,
        help="Poisson's ratio in [0, 0.5) (default 0.2)",
    )
    solve_p.add_argument(
        "--tol",
        type=_number("1e-14 <= tol <= 1e-2"),
        default=1e-8,
        help="relative tolerance on a/h in [1e-14, 1e-2] (default 1e-8)",
    )
    solve_p.add_argument(
        "--allow-unphysical",
        action="store_true",
        help="return a solution with p < 0 or penetration, flagged invalid, "
        "instead of failing",
    )
    solve_p.add_argument(
        "--stress",
        action="store_true",
        help="also print the peaks of sigma_x/(P/h): most compressive and most "
        "tensile on the top surface, most tensile at the bottom (with their x/h), "
        "and sigma_x(0, 0), sigma_x(0, -h)",
    )
    solve_p.add_argument("--json", action="store_true", help="print JSON")
    solve_p.set_defaults(handler=_cmd_solve)

    crit_p = sub.add_parser(
        "critical",
        help="critical speed of the layer on springs",
        description="Print V*_cr, alpha h at the minimum and the Rayleigh V*_R.",
    )
    crit_p.add_argument(
        "--kw",
        type=_number("0 < k_w h/mu <= inf"),
        required=True,
        help="k_w h/mu in [1e-12, inf] ('inf': smooth rigid base)",
    )
    crit_p.add_argument(
        "--nu",
        type=_number("0 <= nu < 0.5"),
        default=0.2,
        help="Poisson's ratio in [0, 0.5) (default 0.2)",
    )
    crit_p.add_argument("--json", action="store_true", help="print JSON")
    crit_p.set_defaults(handler=_cmd_critical)
    return parser


def _fmt(value: float | int | bool | str) -> str:
    if isinstance(value, (bool, int, str)):
        return str(value)
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return f"{value:.10g}"


def _tables(*sections: tuple[str, Sequence[tuple[str, str]]]) -> str:
    """Titled sections of label/value rows, values aligned across sections."""
    width = max(len(label) for _, rows in sections for label, _ in rows)
    blocks = []
    for title, rows in sections:
        lines = [title] + [f"  {label:<{width}}  {value}" for label, value in rows]
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def _json_number(value: float) -> float | str:
    return value if math.isfinite(value) else str(value)


def _cmd_solve(args: argparse.Namespace) -> int:
    s: Solution = solve(
        vstar=args.vstar,
        kw=args.kw,
        radius=args.radius,
        load=args.load,
        nu=args.nu,
        tol=args.tol,
        allow_unphysical=args.allow_unphysical,
    )
    peaks = s.stress_peaks() if args.stress else None
    if args.json:
        data = s.to_dict()
        if peaks is not None:
            data["stress"] = dataclasses.asdict(peaks)
        print(json.dumps(data, indent=2))
        return 0
    inputs = [
        ("V* = ρV²/μ", _fmt(s.vstar)),
        ("k_w h/μ", _fmt(s.kw)),
        ("R/h", _fmt(s.radius)),
        ("P/(μh)", _fmt(s.load)),
        ("μ/(P/h)", _fmt(s.mu_over_load)),
        ("ν", _fmt(s.nu)),
        ("tolerance", _fmt(s.tol)),
    ]
    results = [
        ("a/h", _fmt(s.a)),
        ("p0/(P/h)", _fmt(s.p0)),
        ("indentation δ/h", _fmt(s.indentation)),
        ("V*_cr", _fmt(s.critical_vstar)),
        ("V*_R", _fmt(s.rayleigh_vstar)),
        ("φ1", _fmt(s.phi1)),
        ("collocation N", _fmt(s.collocation_n)),
        ("iterations", _fmt(s.iterations)),
        ("error estimate (a/h)", f"{s.error_estimate:.2e}"),
        ("solve time", f"{s.elapsed * 1e3:.1f} ms"),
        ("valid", "yes" if s.valid else "NO"),
        ("validity", s.validity or "-"),
    ]
    sections = [("Inputs", inputs), ("Results", results)]
    if peaks is not None:
        sections.append(("Stress sigma_x/(P/h)", _stress_rows(peaks)))
    print(_tables(*sections))
    return 0


def _stress_rows(peaks: StressPeaks) -> list[tuple[str, str]]:
    """Rows of the stress section: the peaks of sigma_x/(P/h) with their x/h."""
    return [
        ("top, most compressive", _fmt(peaks.top_compressive)),
        ("top, most compressive x/h", _fmt(peaks.top_compressive_x)),
        ("top, most tensile", _fmt(peaks.top_tensile)),
        ("top, most tensile x/h", _fmt(peaks.top_tensile_x)),
        ("bottom, most tensile", _fmt(peaks.bottom_tensile)),
        ("bottom, most tensile x/h", _fmt(peaks.bottom_tensile_x)),
        ("centre, top (0, 0)", _fmt(peaks.centre_top)),
        ("centre, bottom (0, -h)", _fmt(peaks.centre_bottom)),
        ("searched on 0 <= x/h <=", _fmt(peaks.search_extent)),
    ]


def _cmd_critical(args: argparse.Namespace) -> int:
    vcr = critical_vstar(args.kw, args.nu)
    t = critical_wavenumber(args.kw, args.nu)
    vr = rayleigh_vstar(args.nu)
    if args.json:
        data = {
            "kw": _json_number(args.kw),
            "nu": args.nu,
            "critical_vstar": _json_number(vcr),
            "critical_wavenumber": _json_number(t),
            "rayleigh_vstar": _json_number(vr),
        }
        print(json.dumps(data, indent=2))
        return 0
    rows = [
        ("k_w h/μ", _fmt(float(args.kw))),
        ("ν", _fmt(float(args.nu))),
        ("V*_cr", _fmt(vcr)),
        ("αh at the minimum", _fmt(t)),
        ("V*_R (Rayleigh)", _fmt(vr)),
    ]
    print(_tables(("Critical speed", rows)))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``movingpunch`` command; returns the exit status."""
    if isinstance(sys.stdout, io.TextIOWrapper):
        # Labels use Greek letters; never fail on a terminal that lacks them.
        sys.stdout.reconfigure(errors="backslashreplace")
    parser = _build_parser()
    args = parser.parse_args(argv)
    handler: Callable[[argparse.Namespace], int] | None = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 0
    try:
        return handler(args)
    except (MovingPunchError, ValueError) as exc:
        _fail(str(exc))
    except KeyboardInterrupt:
        sys.stderr.write(f"{PROG}: interrupted\n")
        return 130
