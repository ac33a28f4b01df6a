"""The medium options of the command line (``movingpunch solve`` and
``movingpunch critical``): ``--layer T,MU,NU[,RHO]`` and
``--graded T,GAMMA_H,NU[,MU,RHO]`` (repeated, top to bottom, in command-line
order), ``--half-space MU,NU[,RHO][,bonded|smooth]``, the top sublayer's
material ``--zener RATIO,DEBORAH`` or ``--prony W1,D1[,W2,D2...]`` (with
``--shift A_T``; ``--visco-layer I`` puts it on another sublayer); and the
medium they give (``movingpunch.media``). Every error names the option and
its form.
"""

from __future__ import annotations

import argparse
import dataclasses
from typing import TypeVar

from movingpunch.errors import InvalidParameterError
from movingpunch.media import (
    GradedLayer,
    HalfSpace,
    Layer,
    Medium,
    Prony,
    Sublayer,
    ValueType,
    Zener,
    resolve_medium,
)
from movingpunch.params import SPECS

__all__ = ["add_medium_options", "medium_of"]

MediumType = type[ValueType]

_V = TypeVar("_V", bound=ValueType)


def _optional_units(cls: MediumType) -> list[tuple[str, ...]]:
    """The optional positions of ``cls.CLI`` as the units given together."""
    units: list[tuple[str, ...]] = []
    for name in cls.CLI[cls.CLI_REQUIRED :]:
        if units and name in cls.CLI_TOGETHER and units[-1][0] in cls.CLI_TOGETHER:
            units[-1] = (*units[-1], name)
        else:
            units.append((name,))
    return units


def _counts(cls: MediumType) -> list[int]:
    """How many comma-separated numbers the option takes."""
    out = [cls.CLI_REQUIRED]
    for unit in _optional_units(cls):
        out.append(out[-1] + len(unit))
    return out


def cli_form(cls: MediumType) -> str:
    """The option's metavar from the field table: ``T,MU,NU[,RHO]``,
    ``T,GAMMA_H,NU[,MU,RHO]``, ``MU,NU[,RHO][,bonded|smooth]``."""
    meta = [SPECS[n].cli_name for n in cls.CLI]
    out = ",".join(meta[: cls.CLI_REQUIRED])
    units = _optional_units(cls)
    for unit in units:
        out += "[," + ",".join(SPECS[n].cli_name for n in unit)
    out += "]" * len(units)
    for words in cls.CHOICES.values():
        out += "[," + "|".join(words) + "]"
    return out


def cli_fields_help(cls: MediumType) -> str:
    """Each position's range (and default) from the parameter table."""
    parts = []
    for k, name in enumerate(cls.CLI):
        spec = SPECS[name]
        text = f"{spec.cli_name}: {spec.text}"
        if k >= cls.CLI_REQUIRED:
            text += f" (default {cls.default(name):g})"
        parts.append(text)
    for name, words in cls.CHOICES.items():
        default = cls.default(name)
        parts.append(f"{'|'.join(words)}: the {name} (default {default})")
    return "; ".join(parts)


def parse_cli(option: str, cls: type[_V], text: str) -> _V:
    """The value of ``option`` (``--layer``, ``--graded``, ``--half-space``):
    comma-separated numbers in the positions ``cls.CLI``, then a word of each
    of ``cls.CHOICES``. Raises argparse.ArgumentTypeError naming the option,
    its form, and for a bad value the parameter and its range."""
    form = cli_form(cls)
    parts = [p.strip() for p in text.split(",")]
    words: dict[str, str] = {}
    for name, allowed in reversed(cls.CHOICES.items()):
        if parts and parts[-1].lower() in allowed:
            words[name] = parts.pop().lower()
    counts = _counts(cls)
    try:
        if not counts[0] <= len(parts) <= counts[-1]:
            raise ValueError
        numbers = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{option} must be {form}: {counts[0]} to {counts[-1]} comma-separated "
            f"numbers, got {text!r}"
        ) from None
    if len(numbers) not in counts:
        together = " and ".join(SPECS[n].cli_name for n in cls.CLI_TOGETHER)
        raise argparse.ArgumentTypeError(
            f"{option} must be {form}: give {together} together, got {text!r}"
        )
    values: dict[str, object] = dict(zip(cls.CLI, numbers, strict=False))
    values.update(words)
    try:
        return cls(**values)
    except InvalidParameterError as err:
        raise argparse.ArgumentTypeError(f"{option} {text}: {err}") from None


def _layer(text: str) -> Sublayer:
    """argparse type of --layer: a homogeneous sublayer."""
    return parse_cli("--layer", Layer, text)


def _graded(text: str) -> Sublayer:
    """argparse type of --graded: an exponentially graded sublayer."""
    return parse_cli("--graded", GradedLayer, text)


def _half_space(text: str) -> HalfSpace:
    """argparse type of --half-space: an elastic substrate under the stack."""
    return parse_cli("--half-space", HalfSpace, text)


def _times(option: str, form: str, text: str) -> tuple[list[float], list[float], bool]:
    """The numbers of --zener/--prony split into the moduli (odd places) and
    the times (even places), and whether the times are relaxation times
    (each written tau=T) rather than deborah numbers."""
    parts = [p.strip() for p in text.split(",")]
    taus = [p.lower().startswith("tau=") for p in parts[1::2]]
    if any(taus) and not all(taus):
        raise argparse.ArgumentTypeError(
            f"{option} must be {form}: give every time as a deborah number or every "
            f"one as tau=T (h/c_T0), got {text!r}"
        )
    parts[1::2] = [p[4:] if t else p for p, t in zip(parts[1::2], taus, strict=True)]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{option} must be {form}: comma-separated numbers, got {text!r}"
        ) from None
    return values[0::2], values[1::2], bool(taus) and all(taus)


def _zener(text: str) -> Zener:
    """argparse type of --zener: a standard linear solid (the top sublayer's),
    RATIO,DEBORAH or RATIO,tau=TAU."""
    form = "RATIO,DEBORAH or RATIO,tau=TAU"
    ratios, times, by_tau = _times("--zener", form, text)
    if len(ratios) != 1 or len(times) != 1:
        raise argparse.ArgumentTypeError(
            f"--zener must be {form}: two numbers, got {text!r}"
        )
    try:
        if by_tau:
            return Zener(ratios[0], tau=times[0])
        return Zener(ratios[0], times[0])
    except InvalidParameterError as err:
        raise argparse.ArgumentTypeError(f"--zener {text}: {err}") from None


def _prony(text: str) -> tuple[tuple[float, ...], tuple[float, ...], bool]:
    """argparse type of --prony: the branches' weights, their deborah numbers
    (or relaxation times, each tau=T), and whether they are times."""
    form = "W1,D1[,W2,D2...] or W1,tau=T1[,W2,tau=T2...]"
    weights, times, by_tau = _times("--prony", form, text)
    if not weights or len(weights) != len(times):
        raise argparse.ArgumentTypeError(
            f"--prony must be {form}: pairs of a weight and a deborah number (or a "
            f"relaxation time), got {text!r}"
        )
    return tuple(weights), tuple(times), by_tau


OPTIONS: dict[str, MediumType] = {
    "--layer": Layer,
    "--graded": GradedLayer,
    "--half-space": HalfSpace,
}
"""The medium's options and the value type each makes."""


def add_medium_options(p: argparse.ArgumentParser) -> None:
    """--layer, --graded (both into ``args.layers``, in command-line order)
    and --half-space."""
    p.add_argument(
        "--layer",
        dest="layers",
        type=_layer,
        action="append",
        default=None,
        metavar=cli_form(Layer),
        help="a homogeneous sublayer of the stack, top to bottom (repeat it; "
        "with --graded in command-line order), bonded: "
        f"{cli_fields_help(Layer)}. The thicknesses sum to 1; the top "
        "sublayer's MU and RHO are 1. Instead of --nu; the springs are --kw, "
        "--kp (or a --half-space). E.g. --layer 0.25,1,0.35 --layer 0.75,0.1,0.3",
    )
    p.add_argument(
        "--graded",
        dest="layers",
        type=_graded,
        action="append",
        metavar=cli_form(GradedLayer),
        help="an exponentially graded sublayer (mu and rho vary as "
        "exp(gamma y), y up: GAMMA_H > 0 softens with depth; the wave speeds "
        f"stay constant; MU, RHO at its top): {cli_fields_help(GradedLayer)}; "
        "repeat it, with --layer, top to bottom",
    )
    p.add_argument(
        "--half-space",
        dest="half_space",
        type=_half_space,
        default=None,
        metavar=cli_form(HalfSpace),
        help="an elastic half-space under the layer (or the --layer stack) "
        f"instead of springs: {cli_fields_help(HalfSpace)} (smooth: "
        "frictionless). Not with --kw, --kp, --damping",
    )
    material = p.add_mutually_exclusive_group()
    material.add_argument(
        "--zener",
        type=_zener,
        default=None,
        metavar="RATIO,DEBORAH",
        help="the top sublayer (or --visco-layer's) is a standard linear solid: "
        "mu_inf/mu_0 = RATIO "
        ">= 1 (its MU is mu_0), DEBORAH = V tau/h >= 0; solved moving at "
        "--vstar with the layer's inertia (or at rest), giving the drag and the "
        "dissipation (docs/theory.md section 17). RATIO,tau=TAU gives the "
        "relaxation time in h/c_T0 instead (deborah = sqrt(vstar) TAU; "
        "--quasi-static neglects the inertia)",
    )
    material.add_argument(
        "--prony",
        type=_prony,
        default=None,
        metavar="W1,D1[,W2,D2...]",
        help="the top sublayer (or --visco-layer's) is a generalised Maxwell "
        "solid: each branch's "
        "modulus over mu_0 (W > 0) and deborah number V tau/h (or tau=T, its "
        "relaxation time in h/c_T0); with --shift",
    )
    p.add_argument(
        "--quasi-static",
        dest="quasi_static",
        action="store_true",
        help="neglect the layer's inertia: the solve runs at vstar 0 and --vstar "
        "sets only the relaxation of a --zener/--prony given by tau= (deborah "
        "= sqrt(vstar) tau; docs/media.md)",
    )
    p.add_argument(
        "--shift",
        type=float,
        default=None,
        metavar="A_T",
        help="the time-temperature shift factor a_T > 0 of --prony (default 1)",
    )
    p.add_argument(
        "--visco-layer",
        dest="visco_layer",
        type=int,
        default=None,
        metavar="I",
        help="the sublayer (0: the top, counted down the --layer stack) that "
        "--zener/--prony makes viscoelastic (default 0)",
    )


def medium_of(args: argparse.Namespace) -> Medium | None:
    """The medium of the options (None: none given, the homogeneous layer of
    --nu on the springs of --kw); conflicts name the options."""
    layers: list[Sublayer] | None = args.layers
    base: HalfSpace | None = args.half_space
    material = _material_of(args)
    quasi_static = bool(getattr(args, "quasi_static", False))
    if layers is None and base is None and material is None:
        if quasi_static:
            raise InvalidParameterError(
                "--quasi-static needs a layer whose material takes its relaxation "
                "from the speed: --zener RATIO,tau=TAU or --prony W1,tau=T1,...",
                parameter="inertia",
            )
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
    at: int | None = getattr(args, "visco_layer", None)
    if at is not None and material is None:
        raise InvalidParameterError(
            "--visco-layer says which sublayer --zener/--prony makes "
            "viscoelastic; give --zener or --prony too",
            parameter="visco_layer",
        )
    if material is not None:
        index = 0 if at is None else at
        if not 0 <= index < len(layers):
            raise InvalidParameterError(
                f"--visco-layer {index}: the stack has {len(layers)} "
                f"sublayer{'s' if len(layers) > 1 else ''} (0 ... {len(layers) - 1}, "
                "top to bottom in --layer order)",
                parameter="visco_layer",
                allowed=f"0 ... {len(layers) - 1}",
            )
        sub = layers[index]
        if not isinstance(sub, Layer):
            raise InvalidParameterError(
                f"--zener/--prony: sublayer {index} must be a homogeneous --layer "
                "(a graded one cannot be viscoelastic)",
                parameter="layers",
            )
        replaced = dataclasses.replace(sub, viscoelastic=material)
        layers = [*layers[:index], replaced, *layers[index + 1 :]]
    try:
        kp = getattr(args, "kp", 0.0)
        damping = getattr(args, "damping", 0.0)
        return resolve_medium(
            layers=layers,
            base=base,
            kw=None if base is not None else args.kw,
            kp=None if base is not None else kp,
            damping=None if base is not None else damping,
            inertia=not quasi_static,
        )
    except InvalidParameterError as err:
        if err.parameter == "layers":
            raise InvalidParameterError(
                "--layer/--graded: " + str(err).removeprefix("layers: "),
                parameter="layers",
                allowed=err.allowed,
            ) from None
        raise


def _material_of(args: argparse.Namespace) -> Zener | Prony | None:
    """The top sublayer's material of --zener or --prony (with --shift)."""
    zener: Zener | None = getattr(args, "zener", None)
    pairs: tuple[tuple[float, ...], tuple[float, ...], bool] | None = getattr(
        args, "prony", None
    )
    shift: float | None = getattr(args, "shift", None)
    if shift is not None and pairs is None:
        raise InvalidParameterError(
            "--shift is the time-temperature shift of --prony; give --prony too",
            parameter="shift",
        )
    if zener is not None:
        return zener
    if pairs is None:
        return None
    try:
        weights, times, by_tau = pairs
        shift_ = 1.0 if shift is None else shift
        if by_tau:
            return Prony(weights, shift=shift_, taus=times)
        return Prony(weights, times, shift_)
    except InvalidParameterError as err:
        raise InvalidParameterError(
            f"--prony/--shift: {err}", parameter=err.parameter, allowed=err.allowed
        ) from None
