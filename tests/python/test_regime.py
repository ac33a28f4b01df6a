"""Plausibility hints (``movingpunch.regime``): a result outside small-strain
linear theory, or hypersensitive near its speed limit, says so in one short
clause; a plausible one says nothing."""

from __future__ import annotations

import math

import pytest

import movingpunch as mp
from movingpunch.regime import NEAR_CRITICAL, hints_for, regime_hints

FIG4 = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "nu": 0.2}


def test_paper_case_is_plausible() -> None:
    s = mp.solve(load=0.002, **FIG4)
    assert hints_for(s, s.stress_peaks()) == ()


def test_large_load_names_indentation_contact_and_strain() -> None:
    # The case: P/(μh) = 50 gives δ/h 2.4 and a/h 21.6.
    s = mp.solve(load=50.0, **FIG4)
    assert s.indentation == pytest.approx(2.4, abs=0.01)
    assert s.a == pytest.approx(21.6, abs=0.05)
    hints = hints_for(s, s.stress_peaks())
    text = " ".join(hints)
    assert "δ/h 2.4 > 0.05" in text
    assert "a/h 21.6 > 5" in text
    assert "strain" in text
    assert text.endswith("beyond small-strain linear theory")


def test_each_threshold_alone() -> None:
    base = {
        "indentation": 0.01,
        "half_length": 0.3,
        "peak_strain": 0.001,
        "vstar": 0.2,
        "critical_vstar": 0.57,
    }
    assert regime_hints(**base) == ()
    assert regime_hints(**{**base, "indentation": 0.051})[0].startswith("δ/h 0.051")
    assert regime_hints(**{**base, "half_length": 5.1})[0].startswith("a/h 5.1")
    assert "strain" in regime_hints(**{**base, "peak_strain": 0.06})[0]
    # On the threshold: nothing.
    assert regime_hints(**{**base, "indentation": 0.05, "half_length": 5.0}) == ()
    # Non-finite numbers (a rigid base's δ is finite; a NaN is judged by no one).
    assert regime_hints(**{**base, "indentation": math.nan}) == ()


@pytest.mark.parametrize(("fraction", "hinted"), [(0.995, True), (0.98, False)])
def test_near_the_critical_speed(fraction: float, hinted: bool) -> None:
    vcr = mp.solve(load=0.002, **FIG4).critical_vstar
    s = mp.solve(load=0.002, **{**FIG4, "vstar": fraction * vcr})
    hints = hints_for(s)
    assert any("of V*_cr" in h for h in hints) is hinted
    assert 1 - fraction < NEAR_CRITICAL or not hinted


def test_damped_limit_is_the_rayleigh_speed() -> None:
    base = {
        "indentation": 0.01,
        "half_length": 0.3,
        "peak_strain": 0.001,
        "critical_vstar": 0.57,
        "rayleigh_vstar": 0.83,
    }
    # Damped: V* above V*_cr is fine, near V*_R is not.
    assert regime_hints(vstar=0.575, damped=True, **base) == ()
    assert "of V*_R" in regime_hints(vstar=0.829, damped=True, **base)[0]
    assert "of V*_cr" in regime_hints(vstar=0.569, **base)[0]


def test_train_is_judged_per_punch() -> None:
    # Two punches 8 h apart: the hull is 8.7 h long, each contact 0.37 h.
    train = mp.solve_punches(
        [mp.Punch(100.0, 0.002, at=-4.0), mp.Punch(100.0, 0.002, at=4.0)],
        vstar=0.2,
        kw=1.0,
        nu=0.2,
    )
    assert train.contact_interval[1] > 4.0
    assert hints_for(train) == ()
