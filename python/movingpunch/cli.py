"""Command-line interface: ``movingpunch solve ...`` and ``movingpunch critical ...``.

``solve --stress`` adds the peaks of sigma_x/(P/h) (``Solution.stress_peaks``).

``movingpunch`` with no command, or ``movingpunch tui [SCENE]``, starts the
terminal UI (``movingpunch.tui``, imported only then); ``movingpunch serve``
serves it in a browser through textual-serve, behind a per-start token
(``movingpunch.tui.serve``, docs/tui.md).

``movingpunch run SCENE``, ``movingpunch scenes`` and ``movingpunch scene show
NAME`` run, list and print scenes (``movingpunch.scene``, docs/scenes.md).

``movingpunch accuracy [SCENE]`` shows what accuracy costs in time
(``movingpunch.accuracy``, docs/performance.md).

Bad arguments and every MovingPunchError/ValueError end in one line
``movingpunch: error: ...`` on stderr and exit status 2, never a traceback;
so do output problems (``OutputError``: the path and the reason), which
``run --out`` and ``accuracy --out`` check before computing. A reader that
closes stdout early (``movingpunch run fig4 | head -1``) ends the command
quietly with status 141 (128 + SIGPIPE), after any files were written.

``run`` and ``accuracy`` stop promptly on SIGINT (Ctrl-C) or SIGTERM: their
worker processes are ended, nothing is written, and the process exits with
one line ``movingpunch: interrupted`` (``... (SIGTERM)``) and status 130
(143 for SIGTERM).
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import io
import json
import math
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from types import FrameType
from typing import Any, NoReturn

from movingpunch._cli_media import add_medium_options, medium_of
from movingpunch._display import drag_scale, shown
from movingpunch.contract import ContactSolution, SolvedPunch
from movingpunch.errors import ClusterError, InvalidParameterError, MovingPunchError
from movingpunch.fields import StressPeaks
from movingpunch.media import Medium, Winkler
from movingpunch.params import help_text, range_text
from movingpunch.profiles import (
    PROFILE_KINDS,
    Flat,
    Profile,
    PunchProfile,
    RoundedFlat,
)
from movingpunch.regime import hints_for
from movingpunch.solver import (
    critical_vstar,
    critical_wavenumber,
    rayleigh_vstar,
    result_warnings,
    solve,
    solve_punches,
)
from movingpunch.zones import Punch

PROG = "movingpunch"
EXIT_USAGE = 2
EXIT_BROKEN_PIPE = 128 + 13  # 128 + SIGPIPE
_STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM arrived (``signum``) while a command was working."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


class _StopSignals:
    """SIGINT and SIGTERM handlers for a command that must stop promptly.

    While ``armed``, the first signal raises _Interrupted in the main thread
    (unwinding ends the worker processes: ``scene._executors.pool_map``); any
    signal after it, or one that arrives once the work is over, is only
    recorded in ``received``, so that stopping and reporting are never cut
    short. The previous handlers come back on ``restore()``."""

    def __init__(self) -> None:
        self.received: int | None = None
        self.armed = False
        self._old: dict[int, Any] = {}
        if threading.current_thread() is threading.main_thread():
            for sig in _STOP_SIGNALS:
                self._old[sig] = signal.signal(sig, self._handle)

    def _handle(self, signum: int, frame: FrameType | None) -> None:
        first = self.received is None
        if first:
            self.received = signum
        if first and self.armed:
            raise _Interrupted(signum)

    def restore(self) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old if old is not None else signal.SIG_DFL)
        self._old.clear()


def _interrupted(signum: int) -> int:
    """Reports an interrupt in one line; the exit status, 128 + signum."""
    name = "" if signum == signal.SIGINT else f" ({signal.Signals(signum).name})"
    sys.stderr.write(f"{PROG}: interrupted{name}\n")
    sys.stderr.flush()
    return 128 + int(signum)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line: ``movingpunch: error: ...``,
    and which takes no abbreviated options (``--n 8`` was read as ``--nu 8``)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        hint = f" (see `{self.prog} --help`)"
        _fail(message + hint)


def _fail(message: str) -> NoReturn:
    one_line = " ".join(message.split())
    sys.stderr.write(f"{PROG}: error: {one_line}\n")
    raise SystemExit(EXIT_USAGE)


def _number(name: str) -> Callable[[str], float]:
    """argparse type of the parameter ``name``: a float (``inf`` and ``nan``
    parse; ranges are checked by the solver, which names the parameter and
    its range from the table movingpunch.params.SPECS)."""

    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} must be a real number ({range_text(name)}), got {text!r}"
            ) from None

    return parse


def _punch_arg(text: str) -> tuple[float, float]:
    """argparse type of --punch: LOAD@AT, two real numbers (their ranges
    are checked by movingpunch.Punch)."""
    load, sep, at = text.partition("@")
    try:
        if not sep:
            raise ValueError
        return float(load), float(at)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--punch must be LOAD@AT (two numbers, e.g. 0.002@-1.5), got {text!r}"
        ) from None


def _tol(text: str) -> float | str:
    """argparse type of --tol: a number or a preset name (checked by the
    solver, whose message names the range and the presets)."""
    try:
        return float(text)
    except ValueError:
        return text


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
    # Help texts and ranges: the table of parameters (movingpunch.params).
    solve_p.add_argument(
        "--vstar", type=_number("vstar"), required=True, help=help_text("vstar")
    )
    solve_p.add_argument(
        "--kw",
        type=_number("kw"),
        default=None,
        help=help_text("kw") + " (required, except with --half-space)",
    )
    solve_p.add_argument(
        "--load",
        type=_number("load"),
        default=None,
        help=help_text("load") + " (required, except with --punch)",
    )
    solve_p.add_argument(
        "--punch",
        type=_punch_arg,
        action="append",
        default=None,
        metavar="LOAD@AT",
        help="a punch of a train: its load P/(mu h) and the x/h of its axis, "
        "e.g. --punch 0.002@-1.5 --punch 0.002@1.5 (repeat it; each the shape "
        "of --profile and its options, a cylinder of --radius by default; "
        "instead of --load; docs/theory.md section 15)",
    )
    solve_p.add_argument(
        "--contact",
        choices=("auto", "single"),
        default="auto",
        help="auto (default): several contact zones where the single contact "
        "is unphysical (it separates); single: the single contact only "
        "(an unphysical one fails, or is flagged with --allow-unphysical)",
    )
    solve_p.add_argument(
        "--radius",
        type=_number("radius"),
        default=None,
        help=help_text("radius") + " (of a cylinder, or of a rounded flat's corners)",
    )
    solve_p.add_argument(
        "--profile",
        choices=PROFILE_KINDS,
        default="cylinder",
        help="the punch's shape (docs/theory.md section 13): cylinder (--radius), "
        "flat (--half-width: a flat face, singular ends), rounded_flat "
        "(--half-width, --radius of the corners) or table (--table FILE)",
    )
    solve_p.add_argument(
        "--half-width",
        type=_number("half_width"),
        default=None,
        help=help_text("half_width"),
    )
    solve_p.add_argument(
        "--table",
        type=_named_path("a file"),
        default=None,
        metavar="FILE",
        help="the profile table of --profile table: two columns x/h and y/h "
        "(whitespace or comma separated; # comments), symmetric and convex",
    )
    solve_p.add_argument(
        "--nu", type=_number("nu"), default=None, help=help_text("nu") + "; default 0.2"
    )
    solve_p.add_argument("--tol", type=_tol, default=1e-8, help=help_text("tol"))
    add_medium_options(solve_p)
    # The foundation's optional terms, 0 by default (the paper's model).
    for name, more in (
        (
            "damping",
            "; > 0 gives the asymmetric contact (-b, a) and the drag, at any "
            "speed below the Rayleigh speed (docs/damped.md)",
        ),
        (
            "kp",
            "; the base condition sigma_y = kw v - kp v'' (docs/theory.md section 12)",
        ),
    ):
        solve_p.add_argument(
            f"--{name}", type=_number(name), default=0.0, help=help_text(name) + more
        )
    solve_p.add_argument(
        "--friction",
        type=_number("friction"),
        default=0.0,
        help=help_text("friction") + "; > 0 gives the asymmetric contact (-b, a), "
        "the end exponents and the tangential force (docs/theory.md section 14)",
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
        type=_number("kw"),
        default=None,
        help=help_text("kw") + " (required, except with --half-space)",
    )
    crit_p.add_argument(
        "--nu", type=_number("nu"), default=None, help=help_text("nu") + "; default 0.2"
    )
    crit_p.add_argument("--kp", type=_number("kp"), default=0.0, help=help_text("kp"))
    add_medium_options(crit_p)
    crit_p.add_argument("--json", action="store_true", help="print JSON")
    crit_p.set_defaults(handler=_cmd_critical)

    tui_p = sub.add_parser(
        "tui",
        help="the terminal UI (also: movingpunch with no command)",
        description="Edit the parameters and watch the contact pressure and "
        "stresses in the terminal. Starts on the paper's Fig. 4 case.",
    )
    tui_p.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="a scene file (TOML) or the name of a bundled scene (fig2 ... fig6)",
    )
    tui_p.add_argument(
        "--no-timing",
        action="store_true",
        help="hide the solve time (reproducible screens)",
    )
    tui_p.add_argument(
        "--root",
        default=None,
        type=_named_path("a folder"),
        metavar="DIR",
        help="the working folder: Open, Save and Export stay inside it "
        "(default: the current directory; ~/movingpunch inside the source "
        "checkout)",
    )
    tui_p.set_defaults(handler=_cmd_tui)

    serve_p = sub.add_parser(
        "serve",
        help="serve the terminal UI in a web browser (needs the 'serve' extra)",
        description="Serve the terminal UI through textual-serve (pip install "
        "'movingpunch[serve]'). Each start prints one URL with a random "
        "token, http://HOST:PORT/?token=...; requests without it get 403.",
    )
    serve_p.add_argument(
        "scene", nargs="?", default=None, help="a scene file or bundled name"
    )
    serve_p.add_argument(
        "--host", default="127.0.0.1", help="default 127.0.0.1 (this machine only)"
    )
    serve_p.add_argument(
        "--port", type=int, default=8000, help="default 8000; 0: any free port"
    )
    serve_p.add_argument(
        "--allow-remote",
        action="store_true",
        help="allow a --host other machines can reach (e.g. 0.0.0.0); "
        "without it such a host is refused",
    )
    serve_p.add_argument(
        "--root",
        default=None,
        type=_named_path("a folder"),
        metavar="DIR",
        help="the working folder of every visitor's app: Open, Save and "
        "Export stay inside it (default: the current directory; "
        "~/movingpunch inside the source checkout)",
    )
    serve_p.set_defaults(handler=_cmd_serve)
    _add_scene_commands(sub)
    _add_accuracy_command(sub)
    return parser


def _indentation_text(s: ContactSolution) -> str:
    """The indentation, or "n/a" and why where it is not given
    (``regime.given_indentation``: the solver's refusal names the reason)."""
    try:
        return _fmt(float(s.indentation))
    except InvalidParameterError as exc:
        said = str(exc)
        why = (
            "a logarithmic far field under a half-space"
            if "logarithmic far field" in said
            else said.split(":", 1)[-1].strip().split(" (")[0]
        )
        return f"n/a ({why})"


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


def _cli_profile(args: argparse.Namespace) -> PunchProfile | None:
    """The punch of ``solve``'s options (None: a cylinder of --radius).
    Options a shape does not take are errors naming them."""
    kind = args.profile
    needs = {
        "cylinder": ("radius",),
        "flat": ("half_width",),
        "rounded_flat": ("half_width", "radius"),
        "table": ("table",),
    }[kind]
    for name in ("radius", "half_width", "table"):
        given = getattr(args, name) is not None
        option = "--" + name.replace("_", "-")
        if given and name not in needs:
            raise InvalidParameterError(
                f"{option} is not an option of --profile {kind} "
                f"(it takes {', '.join('--' + n.replace('_', '-') for n in needs)})",
                parameter=name,
            )
        if not given and name in needs:
            raise InvalidParameterError(
                f"--profile {kind} needs {option}", parameter=name
            )
    if kind == "cylinder":
        return None
    if kind == "flat":
        return Flat(args.half_width)
    if kind == "rounded_flat":
        return RoundedFlat(args.half_width, args.radius)
    return _read_table(args.table)


def _read_table(path: str) -> Profile:
    """A profile table from a text file of two columns x/h, y/h: a regular
    file of at most MAX_SCENE_BYTES (1 MiB), read as a scene file is (no
    device, FIFO or huge file is read; the refusal names the file)."""
    from pathlib import Path

    from movingpunch.scene._model import MAX_SCENE_BYTES
    from movingpunch.scene._toml import read_bounded_file

    def refuse(problem: str, allowed: str) -> InvalidParameterError:
        return InvalidParameterError(
            f"--table {path}: {problem} (allowed: {allowed})",
            parameter="table",
            allowed=allowed,
        )

    data = read_bounded_file(Path(path), MAX_SCENE_BYTES, refuse)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise refuse(
            f"not UTF-8 text (byte {exc.start})", "UTF-8 text, two numbers a line"
        ) from None
    xs: list[float] = []
    ys: list[float] = []
    for number, line in enumerate(text.splitlines(), 1):
        body = line.split("#", 1)[0].replace(",", " ").split()
        if not body:
            continue
        try:
            x, y = (float(v) for v in body)
        except ValueError:
            raise InvalidParameterError(
                f"--table {path}: line {number} must hold two numbers x y, "
                f"got {line.strip()!r}",
                parameter="table",
            ) from None
        xs.append(x)
        ys.append(y)
    return Profile(tuple(xs), tuple(ys))


def _solve_train(
    args: argparse.Namespace, profile: PunchProfile | None, medium: Medium | None
) -> ContactSolution:
    """``solve --punch LOAD@AT ...``: the train, by solve_punches."""
    for given, option in (
        (args.load is not None, "--load"),
        (args.allow_unphysical, "--allow-unphysical"),
        (args.contact != "auto", "--contact single"),
    ):
        if given:
            raise InvalidParameterError(
                f"{option} cannot be used with --punch (each punch has its load; "
                "a train finds its contact zones)",
                parameter="punch",
            )
    shape: PunchProfile | float
    if profile is not None:
        shape = profile
    elif args.radius is not None:
        shape = args.radius
    else:
        raise InvalidParameterError(
            "--punch needs --radius (the cylinders' R/h) or a --profile",
            parameter="radius",
        )
    punches = [Punch(shape, load, at) for load, at in args.punch]
    if medium is not None and not medium.inertia:
        raise InvalidParameterError(
            "--quasi-static cannot be used with --punch (a train is solved with "
            "the layer's inertia)",
            parameter="inertia",
        )
    # On a medium solve_punches refuses what it cannot take yet, naming it (a
    # train under a half-space, damped springs under a stack).
    spring_args = _medium_args(args, medium)
    spring_args.pop("inertia", None)  # (True: refused above otherwise)
    return solve_punches(
        punches,
        vstar=args.vstar,
        tol=args.tol,
        friction=args.friction,
        **spring_args,
    )


def _medium_args(args: argparse.Namespace, medium: Medium | None) -> dict[str, Any]:
    """The medium as solve and solve_punches take it: the springs' and the
    layer's shorthand, or ``layers=``/``base=``."""
    if medium is None:
        nu = 0.2 if args.nu is None else args.nu
        return {"kw": args.kw, "nu": nu, "damping": args.damping, "kp": args.kp}
    return medium.solve_args()


def _zone_text(zones: Sequence[tuple[float, float]]) -> str:
    """Contact zones as "(-1.78, -0.72) (0.72, 1.78)"."""
    return " ".join(f"({lo:.6g}, {hi:.6g})" for lo, hi in zones)


def _cmd_solve(args: argparse.Namespace) -> int:
    if args.load is None and not args.punch:
        raise InvalidParameterError(
            "solve: --load is required (or a train: --punch LOAD@AT, repeated)",
            parameter="load",
        )
    profile = _cli_profile(args)
    medium = medium_of(args)
    if medium is None and args.kw is None:
        raise InvalidParameterError(
            "solve: --kw is required (or --half-space)", parameter="kw"
        )
    s: ContactSolution
    if args.punch:
        s = _solve_train(args, profile, medium)
    else:
        spring_args = _medium_args(args, medium)
        s = solve(
            vstar=args.vstar,
            radius=args.radius if profile is None else None,
            profile=profile,
            load=args.load,
            tol=args.tol,
            allow_unphysical=args.allow_unphysical,
            friction=args.friction,
            contact=args.contact,
            **spring_args,
        )
    peaks = s.stress_peaks() if args.stress else None
    _print_warnings(s)
    hints = hints_for(s, peaks)
    if hints:  # never blocking: the exit status stays 0
        print("hint: " + "; ".join(hints), file=sys.stderr)
    if args.json:
        data = s.to_dict()
        if medium is not None:
            data["medium"] = medium.to_dict()
            if not medium.inertia:  # the solve's vstar is 0; the speed's:
                data["quasi_static_vstar"] = args.vstar
        if peaks is not None:
            data["stress"] = dataclasses.asdict(peaks)
        data["hints"] = list(hints)
        print(json.dumps(data, indent=2))
        return 0
    springs = medium is None or isinstance(medium.base, Winkler)
    speed = [("V* = ρV²/μ", _fmt(s.vstar))]
    if medium is not None and not medium.inertia:
        speed = [("V* = ρV²/μ", f"{_fmt(args.vstar)} (quasi-static: solved at 0)")]
    if medium is not None and medium.speed_dependent:
        speed.append(("medium at V*", medium.at_speed(args.vstar).describe()))
    inputs = [
        *speed,
        *([("medium", medium.describe())] if medium is not None else []),
        ("k_w h/μ", _fmt(s.kw) if springs else "- (half-space)"),
        ("k_p/(μh) (Pasternak)", _fmt(s.kp)),
        ("damping c_w c_T/μ", _fmt(s.damping)),
        ("friction f", _fmt(s.friction)),
        ("R/h", _fmt(s.radius)),
        ("profile", s.profile.describe()),
        ("P/(μh)", _fmt(s.load)),
        ("μ/(P/h)", _fmt(1.0 / s.load)),
        ("ν", _fmt(s.nu)),
        ("tolerance", _fmt(s.tol)),
    ]
    back, front = s.contact_interval
    zones = s.contact_zones
    # Round-off is shown as 0 (movingpunch._display): the drag of a
    # symmetric contact or of mirror-image punches sums to ~1e-19.
    drag = shown(s.drag, scale=drag_scale((back, front), s.radius))
    try:
        dissipation: float | str = shown(
            s.dissipation, scale=drag_scale((back, front), s.radius)
        )
    except MovingPunchError as exc:  # (said in warnings too)
        dissipation = f"n/a ({str(exc).split(': ', 1)[-1].split(' (')[0]})"
    several = [("contact zones", _zone_text(zones))] if len(zones) > 1 else []
    results = [
        ("a/h", _fmt(s.a)),
        ("contact (x_back/h, x_front/h)", f"({_fmt(back)}, {_fmt(front)})"),
        *several,
        ("p0/(P/h)", _fmt(s.p0)),
        ("indentation δ/h", _indentation_text(s)),
        ("drag (∫p x/R dx)/P", _fmt(drag)),
        ("tangential force/P", _fmt(s.tangential_force)),
        ("end exponents (back, front)", "({}, {})".format(*map(_fmt, s.end_exponents))),
        ("dissipation/(P V)", _fmt(dissipation)),
        ("V*_cr", _fmt(s.critical_vstar)),
        ("V*_R", _fmt(s.rayleigh_vstar)),
        ("φ1", _fmt(s.phi1)),
        ("collocation N", _fmt(s.collocation_n)),
        ("iterations", _fmt(s.iterations)),
        ("error estimate (a/h)", f"{s.error_estimate:.2e}"),
        ("error bound (σx/(P/h))", f"{s.stress_error_estimate:.2e}"),
        ("pressure margin", _fmt(s.pressure_margin)),
        *(
            [
                (
                    "end coefficient K/((P/h)√h)",
                    f"{_fmt(s.end_coefficients[1])} ± {s.end_coefficient_error:.1e}",
                )
                if s.end_coefficients[0] == s.end_coefficients[1]
                else (
                    "end coefficients (K_back, K_front)",
                    f"({_fmt(s.end_coefficients[0])}, {_fmt(s.end_coefficients[1])}) "
                    f"± {s.end_coefficient_error:.1e}",
                )
            ]
            if s.end_coefficients != (0.0, 0.0)
            else []
        ),
        ("warnings", str(len(s.warnings)) if s.warnings else "none"),
        ("solve time", f"{s.elapsed * 1e3:.1f} ms"),
        ("valid", "yes" if s.valid else "NO"),
        ("validity", s.validity or "-"),
    ]
    sections = [("Inputs", inputs), ("Results", results)]
    punches = s.punches
    if len(punches) > 1 or args.punch:
        sections.append(
            (
                "Punches",
                [
                    (
                        f"punch {k + 1} at x/h = {_fmt(q.at)}",
                        f"P/(μh) = {_fmt(q.load)}, zones {_zone_text(q.contact_zones)}"
                        f", δ/h = {_fmt(q.indentation)}, drag/P = "
                        f"{_fmt(shown(q.drag, scale=_punch_drag_scale(q, s.radius)))}",
                    )
                    for k, q in enumerate(punches)
                ],
            )
        )
    if peaks is not None:
        sections.append(("Stress sigma_x/(P/h)", _stress_rows(peaks)))
    print(_tables(*sections))
    return 0


def _print_warnings(result: object) -> None:
    """Every warning of a solution, one ``warning: ...`` line each on stderr."""
    for line in result_warnings(result):
        print(f"warning: {line}", file=sys.stderr)


def _stress_rows(peaks: StressPeaks) -> list[tuple[str, str]]:
    """Rows of the stress section: the peaks of sigma_x/(P/h) with their x/h.
    A peak value within its error bound of 0, or a position within round-off
    of the axis (1e-16 for x/h = 0), is shown as 0 (movingpunch._display)."""

    def value(v: float) -> str:
        return _fmt(shown(v, estimate=peaks.error_bound))

    def at(x: float) -> str:
        return _fmt(shown(x, scale=peaks.search_extent))

    return [
        ("top, most compressive", value(peaks.top_compressive)),
        ("top, most compressive x/h", at(peaks.top_compressive_x)),
        ("top, most tensile", value(peaks.top_tensile)),
        ("top, most tensile x/h", at(peaks.top_tensile_x)),
        ("bottom, most tensile", value(peaks.bottom_tensile)),
        ("bottom, most tensile x/h", at(peaks.bottom_tensile_x)),
        ("centre, top (0, 0)", value(peaks.centre_top)),
        ("centre, bottom (0, -h)", value(peaks.centre_bottom)),
        # |x| <= extent: the symmetric solver's half 0 <= x covers it by symmetry.
        ("searched on |x|/h <=", _fmt(peaks.search_extent)),
        ("error bound (peaks)", f"{peaks.error_bound:.2e}"),
        *(("warning", text) for text in peaks.warnings),
    ]


def _punch_drag_scale(punch: SolvedPunch, radius: float) -> float:
    """``drag_scale`` of one punch of a train: its zones' reach from its axis."""
    ends = [x - punch.at for zone in punch.contact_zones for x in zone]
    own = getattr(punch.profile, "radius", radius)  # a flat punch or table: none
    return drag_scale(ends, own if isinstance(own, float) else radius)


def _cmd_critical(args: argparse.Namespace) -> int:
    medium = medium_of(args)
    if medium is None:
        if args.kw is None:
            raise InvalidParameterError(
                "critical: --kw is required (or --half-space)", parameter="kw"
            )
        nu = 0.2 if args.nu is None else args.nu
        vcr = critical_vstar(args.kw, nu, args.kp)
        t = critical_wavenumber(args.kw, nu, args.kp)
    else:
        nu = medium.nu
        vcr = critical_vstar(layers=list(medium.layers), base=medium.base)
        t = critical_wavenumber(layers=list(medium.layers), base=medium.base)
    springs = medium is None or isinstance(medium.base, Winkler)
    vr = rayleigh_vstar(nu)
    if args.json:
        data: dict[str, Any] = {
            "kw": _json_number(args.kw) if springs else None,
            "nu": nu,
            "kp": args.kp,
            "critical_vstar": _json_number(vcr),
            "critical_wavenumber": _json_number(t),
            "rayleigh_vstar": _json_number(vr),
        }
        if medium is not None:
            data["medium"] = medium.to_dict()
        print(json.dumps(data, indent=2))
        return 0
    rows = [
        *([("medium", medium.describe())] if medium is not None else []),
        ("k_w h/μ", _fmt(float(args.kw)) if springs else "- (half-space)"),
        ("ν" if medium is None else "ν (top)", _fmt(float(nu))),
        ("k_p/(μh)", _fmt(float(args.kp))),
        ("V*_cr", _fmt(vcr)),
        ("αh at the minimum", _fmt(t)),
        ("V*_R (Rayleigh)", _fmt(vr)),
    ]
    print(_tables(("Critical speed", rows)))
    return 0


def _cmd_tui(args: argparse.Namespace) -> int:
    # Imported here: the numerical commands never load Textual.
    from movingpunch.tui import create_app

    app = create_app(args.scene, show_timing=not args.no_timing, root=args.root)
    app.run()
    return 0


def _cmd_serve(args: argparse.Namespace) -> int:
    try:
        from movingpunch.tui import serve
    except ImportError:
        _fail(
            "serve needs textual-serve: pip install 'movingpunch[serve]' "
            "(or pip install textual-serve)"
        )
    from movingpunch.tui import scene_files
    from movingpunch.tui.paths import WorkingFolder

    folder = WorkingFolder.at(args.root)  # a bad root fails here, in one line
    command = [sys.executable, "-m", "movingpunch", "tui", "--root", str(folder.root)]
    if args.scene is not None:
        scene_files.load(args.scene)  # a bad scene fails here, in one line
        command += ["--", args.scene]  # relative to this (the apps') directory
    serve.serve(
        command,
        host=args.host,
        port=args.port,
        allow_remote=args.allow_remote,
        title=PROG,
    )
    return 0


# --- Scenes: movingpunch run / scenes / scene show ---------------------------


def _add_scene_commands(sub: Any) -> None:
    """The ``run``, ``scenes`` and ``scene show`` subcommands (docs/scenes.md)."""
    run_p = sub.add_parser(
        "run",
        help="run a scene file or a bundled scene (table1, fig2 ... fig6, ...)",
        description="Run a scene: compute only the outputs it asks for, print a "
        "summary table and the stages with their times, optionally plot and "
        "write one CSV/JSON file per output (docs/scenes.md).",
    )
    run_p.add_argument("scene", help="a scene file (TOML) or a bundled scene name")
    run_p.add_argument(
        "--out",
        type=_named_path("a folder"),
        metavar="DIR",
        default=None,
        help="write one file per output into DIR (default: none; '.' when "
        "--format csv or --png is given)",
    )
    run_p.add_argument(
        "--format",
        choices=("csv", "json"),
        default=None,
        help="format of the files of --out (csv by default); --format json "
        "without --out prints the whole result as one JSON document on "
        "stdout instead (summary, every output's columns; nan/inf as "
        "strings), nothing else",
    )
    plot = run_p.add_mutually_exclusive_group()
    plot.add_argument(
        "--plot",
        action="store_true",
        default=None,
        help="ASCII plots in the terminal (default when stdout is a terminal)",
    )
    plot.add_argument(
        "--no-plot", dest="plot", action="store_false", help="no ASCII plots"
    )
    run_p.add_argument(
        "--png", action="store_true", help="PNG figures (needs the 'png' extra)"
    )
    run_p.add_argument(
        "--jobs",
        type=_jobs,
        default=None,
        metavar="N",
        help="at most N processes for a sweep (default: the cores this process "
        "may use); a sweep too short to gain from worker processes runs in "
        "this one (the summary's 'jobs 1')",
    )
    run_p.add_argument(
        "--dask",
        metavar="ADDRESS",
        default=None,
        help="run the sweep on a Dask scheduler, e.g. tcp://host:8786 "
        "(needs the 'dask' extra); stderr shows 'connecting to ADDRESS', the "
        "seconds left, then 'connected to ADDRESS (N workers)'",
    )
    run_p.add_argument(
        "--dask-timeout",
        type=_seconds,
        default=None,
        metavar="SECONDS",
        help="how long --dask waits for the scheduler (connecting, and any "
        f"stretch without a result); {_SECONDS_RANGE}, default "
        "20",
    )
    run_p.set_defaults(handler=_cmd_run, stop_on_signals=True)

    list_p = sub.add_parser(
        "scenes",
        help="list the bundled scenes",
        description="List the bundled scenes with a one-line description.",
    )
    list_p.set_defaults(handler=_cmd_scenes)

    scene_p = sub.add_parser(
        "scene",
        help="show a bundled scene as TOML",
        description="Print a bundled scene as TOML, to start a scene file from.",
    )
    scene_sub = scene_p.add_subparsers(dest="scene_command", metavar="ACTION")
    show_p = scene_sub.add_parser(
        "show",
        help="print a bundled scene as TOML",
        description="Print a bundled scene (or a scene file, validated) as TOML.",
    )
    show_p.add_argument("name", help="a bundled scene name (or a scene file)")
    show_p.set_defaults(handler=_cmd_scene_show)
    scene_p.set_defaults(handler=lambda _args: _fail("scene: missing ACTION: show"))


_SECONDS_MAX = 3600.0
_SECONDS_RANGE = f"0 < SECONDS <= {_SECONDS_MAX:g}"


def _seconds(text: str) -> float:
    """argparse type of --dask-timeout: seconds, 0 < SECONDS <= 3600."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value <= _SECONDS_MAX:  # nan fails too
        raise argparse.ArgumentTypeError(
            f"must be a number of seconds, {_SECONDS_RANGE}, got {text!r}"
        )
    return value


def _named_path(what: str) -> Callable[[str], str]:
    """argparse type of an option naming a file or folder: any path but the
    empty one, which would silently mean the current folder."""

    hint = " (use '.' for the current folder)" if what == "a folder" else ""

    def check(text: str) -> str:
        if not text:
            raise argparse.ArgumentTypeError(f"must name {what}, got ''{hint}")
        return text

    return check


def _jobs(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be an integer >= 1, got {text!r}"
        ) from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1, got {text!r}")
    return value


def _cmd_run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from movingpunch.outputs import Content, prepare, publish
    from movingpunch.scene import ascii_plots, format_summary, load_scene
    from movingpunch.scene._export import (
        format_json,
        format_tables,
        pyplot,
        render_pngs,
        stream_outputs,
    )

    # --format json without --out: the result as one JSON document on
    # stdout, and nothing else there (notes, file names: stderr).
    json_out = args.format == "json" and args.out is None
    if json_out and args.plot:
        _fail(
            "--plot cannot be used with --format json without --out (stdout "
            "holds the JSON document)"
        )
    if args.dask_timeout is not None and args.dask is None:
        _fail("--dask-timeout needs --dask ADDRESS")
    scene = load_scene(args.scene)
    if args.dask is not None and scene.sweep is None:
        sys.stderr.write(
            f"{PROG}: note: --dask: the scene has no [sweep], nothing to "
            "distribute: running here\n"
        )
    # Output problems are found before the work: the folder, the PNG extra.
    out_dir = None
    if args.out is not None or (args.format is not None and not json_out) or args.png:
        out_dir = prepare(Path(args.out or "."))
        if args.png:
            pyplot()
    bar = _ProgressBar() if sys.stderr.isatty() else None
    status = _DaskStatus(args.dask) if args.dask is not None else None
    try:
        result = scene.run(
            jobs=args.jobs,
            progress=bar,
            dask=args.dask,
            dask_timeout=args.dask_timeout,
            on_dask=status,
        )
    except ClusterError as exc:
        if status is not None and status.waiting:  # while connecting
            status.close()
            raise ClusterError(
                f"--dask {args.dask} (--dask-timeout {status.timeout:g} s): {exc}"
            ) from None
        raise
    finally:
        if status is not None:
            status.close()
        if bar is not None:
            bar.close()
    explicit_jobs = args.jobs is not None and args.jobs > 1
    if explicit_jobs and result.jobs == 1 and scene.sweep is not None:
        sys.stderr.write(
            f"{PROG}: note: --jobs {args.jobs}: the sweep ran in this "
            "process (too short for worker processes to pay for their "
            "start-up)\n"
        )
    hints = _scene_hints(result)
    # The files first (all of them or none), then the text: a reader that
    # closes stdout early (| head) does not cost the files.
    written = []
    if out_dir is not None:
        files: list[tuple[str, Content]] = []
        if not json_out:
            files += stream_outputs(result, args.format or "csv")
        if args.png:
            files += render_pngs(result)
        written = publish(out_dir, files)
    if json_out:
        sys.stdout.write(format_json(result, hints))
        for path in written:
            sys.stderr.write(f"{PROG}: wrote {path}\n")
        return 0
    print(format_summary(result, hints))
    show_plot = args.plot if args.plot is not None else sys.stdout.isatty()
    if show_plot:
        print()
        print(ascii_plots(result, color=sys.stdout.isatty()))
    elif not sys.stdout.isatty():
        # Piped or redirected: the numbers themselves, as plain text.
        print()
        print(format_tables(result))
    if out_dir is not None:
        print()
        print("Files")
        for path in written:
            print(f"  {path}")
    return 0


def _scene_hints(result: Any) -> tuple[str, ...]:
    """The plausibility hints (movingpunch.regime) of a scene's one
    solution: a scene without [vary] or [sweep] that solved one contact
    (elsewhere its solutions are shared, rescaled, between points, and no
    single one is the scene's)."""
    scene = result.scene
    if scene.vary is not None or scene.sweep is not None:
        return ()
    if len(result.solutions) != 1:
        return ()
    return hints_for(result.solutions[0])


class _ProgressBar:
    """``progress(done, total)`` drawn as one line on stderr (made only
    when stderr is a terminal: logs get no progress)."""

    def __init__(self) -> None:
        self.drawn = False

    def __call__(self, done: int, total: int) -> None:
        width = 30
        filled = width * done // max(total, 1)
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total}")
        sys.stderr.flush()
        self.drawn = True

    def close(self) -> None:
        if self.drawn:
            sys.stderr.write("\n")
            self.drawn = False


class _DaskStatus:
    """``on_dask(event, value)`` of ``run --dask``: "connecting to ADDRESS
    …" on stderr at once, then the seconds left until the timeout (on a
    terminal one line redrawn each second; otherwise a line every
    COUNTDOWN_EVERY seconds at most, so that logs stay short), then
    "connected to ADDRESS (N workers)"."""

    COUNTDOWN_EVERY = 5.0

    def __init__(self, address: str) -> None:
        self.address = address
        self.timeout = math.nan
        self.waiting = False
        self.tty = sys.stderr.isatty()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._lock = threading.Lock()
        self._line_open = False  # a terminal line without its newline yet

    def __call__(self, event: str, value: float) -> None:
        if event == "connecting":
            self.timeout = value
            self.waiting = True
            self._write(f"connecting to {self.address} … (timeout {value:g} s)")
            self._thread = threading.Thread(
                target=self._countdown, name="movingpunch-dask-countdown", daemon=True
            )
            self._thread.start()
        elif event == "connected":
            self._stop_countdown()
            workers = int(value)
            self._write(
                f"connected to {self.address} "
                f"({workers} worker{'' if workers == 1 else 's'})",
                end=True,
            )

    def _countdown(self) -> None:
        import time

        start = time.monotonic()
        step = 1.0 if self.tty else self.COUNTDOWN_EVERY
        while not self._stop.wait(step):
            left = self.timeout - (time.monotonic() - start)
            if left <= 0:
                return
            self._write(
                f"connecting to {self.address} … {math.ceil(left):d} s left",
                end=not self.tty,
            )

    def _write(self, text: str, *, end: bool | None = None) -> None:
        """One status line: on a terminal redrawn in place (``\\r``, the
        line left open unless ``end``), otherwise a line of its own."""
        with self._lock:
            if self.tty:
                sys.stderr.write(f"\r\x1b[K{text}" + ("\n" if end else ""))
                self._line_open = not end
            else:
                sys.stderr.write(f"{text}\n")
            sys.stderr.flush()

    def _stop_countdown(self) -> None:
        self.waiting = False
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
            self._thread = None

    def close(self) -> None:
        """Stops the countdown and ends its terminal line."""
        self._stop_countdown()
        with self._lock:
            if self._line_open:
                sys.stderr.write("\n")
                sys.stderr.flush()
                self._line_open = False


def _cmd_scenes(args: argparse.Namespace) -> int:
    from movingpunch.scene import bundled_scenes

    scenes = bundled_scenes()
    width = max(len(name) for name in scenes)
    for name, description in scenes.items():
        print(f"{name:<{width}}  {description}")
    return 0


def _cmd_scene_show(args: argparse.Namespace) -> int:
    from movingpunch.scene import bundled_scene_text, load_scene

    text = bundled_scene_text(args.name)
    print(text if text is not None else load_scene(args.name).to_toml(), end="")
    return 0


# --- movingpunch accuracy -----------------------------------------------------


def _add_accuracy_command(sub: Any) -> None:
    acc_p = sub.add_parser(
        "accuracy",
        help="what accuracy costs in time: errors and times for tol 1e-2 ... 1e-12",
        description="For tol = 1e-2, 1e-3, ..., 1e-12 run a case or a scene (cold "
        "kernel cache, then warm), compare a/h, p0 and the sigma_x peaks with a "
        "reference at a fixed large N and tol 1e-14, and print the table, the "
        "time per stage and a log-log plot of error against time. Without "
        "SCENE: the paper's Fig. 4 case (V* 0.2, kw 1, R/h 100, load 0.002, "
        "nu 0.2), solve + sigma_x peaks.",
    )
    acc_p.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="a scene file or bundled name (table1, fig2 ... fig6); default: "
        "the Fig. 4 case",
    )
    acc_p.add_argument(
        "--tols",
        type=_tol_list,
        default=None,
        metavar="T1,T2,...",
        help="the ladder of tolerances (default 1e-2,1e-3,...,1e-12; presets allowed)",
    )
    acc_p.add_argument(
        "--out",
        type=_named_path("a folder"),
        metavar="DIR",
        default=None,
        help="write <name>-accuracy.csv into DIR",
    )
    plot = acc_p.add_mutually_exclusive_group()
    plot.add_argument(
        "--plot",
        action="store_true",
        default=None,
        help="log-log plot of error against time (default when stdout is a terminal)",
    )
    plot.add_argument("--no-plot", dest="plot", action="store_false", help="no plot")
    acc_p.set_defaults(handler=_cmd_accuracy, stop_on_signals=True)


def _tol_list(text: str) -> list[float]:
    from movingpunch.solver import resolve_tol

    parts = [p for p in text.replace(";", ",").split(",") if p.strip()]
    if not parts:
        raise argparse.ArgumentTypeError("give one or more tolerances")
    try:
        return [resolve_tol(_tol(p.strip())) for p in parts]
    except MovingPunchError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _cmd_accuracy(args: argparse.Namespace) -> int:
    from pathlib import Path

    from movingpunch import accuracy
    from movingpunch.outputs import prepare, publish

    out_dir = prepare(Path(args.out)) if args.out is not None else None
    bar = _ProgressBar() if sys.stderr.isatty() else None
    try:
        report = accuracy.accuracy_report(
            args.scene, args.tols or accuracy.LADDER, progress=bar
        )
    finally:
        if bar is not None:
            bar.close()
    assert report is not None  # never cancelled here
    written = []
    if out_dir is not None:
        written = publish(out_dir, [accuracy.render_csv(report)])
    print(accuracy.format_table(report))
    show_plot = args.plot if args.plot is not None else sys.stdout.isatty()
    if show_plot:
        print()
        print(accuracy.ascii_plot(report, color=sys.stdout.isatty()))
    if written:
        print()
        print("Files")
        print(f"  {written[0]}")
    return 0


def _stdout_closed() -> int:
    """stdout's reader went away (``| head``): point stdout at /dev/null so
    that the interpreter's last flush cannot fail again, and end quietly
    with 128 + SIGPIPE, the status a shell shows for ``yes | head -1``."""
    with contextlib.suppress(OSError, ValueError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, sys.stdout.fileno())
        finally:
            os.close(devnull)
    return EXIT_BROKEN_PIPE


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``movingpunch`` command; returns the exit status."""
    for name in ("stdout", "stderr"):
        if getattr(sys, name) is None:  # started with the descriptor closed
            setattr(sys, name, open(os.devnull, "w", encoding="utf-8"))  # noqa: SIM115
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper):
            # Labels and hints use Greek letters; never fail on a terminal
            # that lacks them.
            stream.reconfigure(errors="backslashreplace")
    parser = _build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit:  # --help or a usage error
        with contextlib.suppress(BrokenPipeError):
            sys.stdout.flush()
            raise
        raise SystemExit(_stdout_closed()) from None
    handler: Callable[[argparse.Namespace], int] | None = getattr(args, "handler", None)
    if handler is None:
        handler = _cmd_tui  # no command: the terminal UI on the paper's Fig. 4
        args = argparse.Namespace(scene=None, no_timing=False, root=None)
    signals = _StopSignals() if getattr(args, "stop_on_signals", False) else None
    try:
        return _call(handler, args, signals)
    finally:
        if signals is not None:
            signals.restore()


def _call(
    handler: Callable[[argparse.Namespace], int],
    args: argparse.Namespace,
    signals: _StopSignals | None,
) -> int:
    """Runs a command: its status; one line on stderr for an error (status
    2) or an interrupt (130 / 143), which wins over an error it caused."""
    status, error = 0, None
    try:
        if signals is not None:
            signals.armed = True
        try:
            status = handler(args)
            sys.stdout.flush()  # a closed pipe shows here, not at exit
        finally:
            if signals is not None:
                signals.armed = False
    except BrokenPipeError:
        return _stdout_closed()
    except KeyboardInterrupt as exc:
        signum = int(getattr(exc, "signum", signal.SIGINT))
        if signals is None:
            return _interrupted(signum)
        if signals.received is None:
            signals.received = signum
    except (MovingPunchError, ValueError) as exc:
        error = str(exc)
    if signals is not None and signals.received is not None:
        return _interrupted(signals.received)
    if error is not None:
        _fail(error)
    return status
