"""The medium options of the command line (``movingpunch solve`` and
``movingpunch critical``): ``--layer T,MU,NU[,RHO]`` and
``--graded T,GAMMA_H,NU[,MU,RHO]`` (repeated, top to bottom, in command-line
order), ``--half-space MU,NU[,RHO][,bonded|smooth]``; and the medium they give
(``movingpunch.media``). Every error names the option and its form.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import TypeVar

from movingpunch.errors import InvalidParameterError
from movingpunch.media import (
    INTERFACES,
    GradedLayer,
    HalfSpace,
    Layer,
    Medium,
    Sublayer,
    resolve_medium,
)

__all__ = ["add_medium_options", "medium_of"]

_T = TypeVar("_T")

LAYER_FORM = "T,MU,NU[,RHO] (thickness h_i/h, mu and rho per the top sublayer's)"
GRADED_FORM = "T,GAMMA_H,NU[,MU,RHO] (thickness h_i/h, gamma h, mu and rho at its top)"
HALF_SPACE_FORM = "MU,NU[,RHO][,bonded|smooth] (mu and rho per the top sublayer's)"


def _numbers(option: str, form: str, text: str, lo: int, hi: int) -> list[float]:
    parts = [p.strip() for p in text.split(",")]
    try:
        if not lo <= len(parts) <= hi:
            raise ValueError
        return [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{option} must be {form}: {lo} to {hi} comma-separated numbers, got "
            f"{text!r}"
        ) from None


def _made(option: str, text: str, make: Callable[[], _T]) -> _T:
    try:
        return make()
    except InvalidParameterError as err:
        raise argparse.ArgumentTypeError(f"{option} {text}: {err}") from None


def _layer(text: str) -> Sublayer:
    """argparse type of --layer: a homogeneous sublayer."""
    v = _numbers("--layer", LAYER_FORM, text, 3, 4)
    return _made(
        "--layer",
        text,
        lambda: Layer(
            thickness=v[0], mu=v[1], nu=v[2], rho=v[3] if len(v) > 3 else 1.0
        ),
    )


def _graded(text: str) -> Sublayer:
    """argparse type of --graded: an exponentially graded sublayer."""
    v = _numbers("--graded", GRADED_FORM, text, 3, 5)
    if len(v) == 4:
        raise argparse.ArgumentTypeError(
            f"--graded must be {GRADED_FORM}: give MU and RHO together, got {text!r}"
        )
    mu, rho = (v[3], v[4]) if len(v) == 5 else (1.0, 1.0)
    return _made(
        "--graded",
        text,
        lambda: GradedLayer(gamma_h=v[1], nu=v[2], thickness=v[0], mu=mu, rho=rho),
    )


def _half_space(text: str) -> HalfSpace:
    """argparse type of --half-space: an elastic substrate under the stack."""
    parts = [p.strip() for p in text.split(",")]
    interface = "bonded"
    if parts and parts[-1].lower() in INTERFACES:
        interface = parts.pop().lower()
    v = _numbers("--half-space", HALF_SPACE_FORM, ",".join(parts), 2, 3)
    return _made(
        "--half-space",
        text,
        lambda: HalfSpace(
            mu=v[0], nu=v[1], rho=v[2] if len(v) > 2 else 1.0, interface=interface
        ),
    )


def add_medium_options(p: argparse.ArgumentParser) -> None:
    """--layer, --graded (both into ``args.layers``, in command-line order)
    and --half-space."""
    p.add_argument(
        "--layer",
        dest="layers",
        type=_layer,
        action="append",
        default=None,
        metavar="T,MU,NU[,RHO]",
        help="a homogeneous sublayer of the stack, top to bottom (repeat it; "
        "with --graded in command-line order): thickness h_i/h (they sum to 1), "
        "shear modulus and density per the top sublayer's (the top one: 1, 1; "
        "RHO defaults to 1), Poisson's ratio; bonded. Instead of --nu; the "
        "springs are --kw, --kp (or a --half-space). E.g. --layer 0.25,1,0.35 "
        "--layer 0.75,0.1,0.3",
    )
    p.add_argument(
        "--graded",
        dest="layers",
        type=_graded,
        action="append",
        metavar="T,GAMMA_H,NU[,MU,RHO]",
        help="an exponentially graded sublayer (mu and rho vary as "
        "exp(gamma y), y up: GAMMA_H > 0 softens with depth; the wave speeds "
        "stay constant): thickness, gamma h, Poisson's ratio, and mu, rho at "
        "its top (default 1, 1); repeat it, with --layer, top to bottom",
    )
    p.add_argument(
        "--half-space",
        dest="half_space",
        type=_half_space,
        default=None,
        metavar="MU,NU[,RHO][,bonded|smooth]",
        help="an elastic half-space under the layer (or the --layer stack) "
        "instead of springs: shear modulus and density per the top sublayer's "
        "(RHO defaults to 1), Poisson's ratio, and the interface: bonded "
        "(default) or smooth (frictionless). Not with --kw, --kp, --damping",
    )


def medium_of(args: argparse.Namespace) -> Medium | None:
    """The medium of the options (None: none given, the homogeneous layer of
    --nu on the springs of --kw); conflicts name the options."""
    layers: list[Sublayer] | None = args.layers
    base: HalfSpace | None = args.half_space
    if layers is None and base is None:
        return None
    if layers is not None and args.nu is not None:
        raise InvalidParameterError(
            "--nu cannot be used with --layer/--graded (each sublayer has its own "
            "Poisson's ratio: --layer T,MU,NU[,RHO])",
            parameter="nu",
        )
    if base is not None:
        for name in ("kw", "kp", "damping"):
            value = getattr(args, name, None)
            if value is not None and (name == "kw" or value != 0.0):
                raise InvalidParameterError(
                    f"--{name} cannot be used with --half-space (a half-space base "
                    "has no springs)",
                    parameter=name,
                )
    elif args.kw is None:
        raise InvalidParameterError(
            "--kw is required: the springs under the --layer stack (or a "
            "--half-space base)",
            parameter="kw",
        )
    if layers is None:
        layers = [Layer(nu=0.2 if args.nu is None else args.nu)]
    try:
        kp = getattr(args, "kp", 0.0)
        damping = getattr(args, "damping", 0.0)
        return resolve_medium(
            layers=layers,
            base=base,
            kw=None if base is not None else args.kw,
            kp=None if base is not None else kp,
            damping=None if base is not None else damping,
        )
    except InvalidParameterError as err:
        if err.parameter == "layers":
            raise InvalidParameterError(
                "--layer/--graded: " + str(err).removeprefix("layers: "),
                parameter="layers",
                allowed=err.allowed,
            ) from None
        raise
