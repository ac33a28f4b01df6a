"""Layered media against independent anchors (issue 26's acceptance).

* K identical sublayers are the homogeneous layer (an independent solver
  path: the stack medium's global matrix against LayerModel's closed-form
  basis) to 1e-12;
* a bonded half-space of the layer's own material is a half-plane: the moving
  half-plane's closed form a^2 = 2 phi1 R P/pi, p0 = 2P/(pi a) (the moving
  Hertz contact; docs/theory.md section 3) to 1e-10;
* a stiff half-space in frictionless contact tends to the smooth rigid base
  (kw = inf), the difference falling like 1/mu_2;
* every new case: int p = P, p >= 0, no penetration (valid);
* at a bonded interface sigma_y, tau_xy and eps_x are continuous and sigma_x
  jumps by Hooke's law of the two materials (the state form's
  Sx = 4 mu (l + 1)/(l + 2) eps_x + l/(l + 2) sigma_y, l = 2 nu/(1 - 2 nu)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp

R, P = 100.0, 0.002


def _solve(**kw: object) -> mp.Solution:
    s = mp.solve(vstar=0.2, radius=R, load=P, tol=1e-12, **kw)  # type: ignore[arg-type]
    assert isinstance(s, mp.Solution)
    return s


def _check_physical(s: mp.Solution) -> None:
    """int p = P (Gauss-Chebyshev on the contact), p >= 0, valid."""
    assert s.valid, s.validity
    a = s.a
    n = 400
    t = np.cos((2 * np.arange(1, n + 1) - 1) * math.pi / (2 * n))
    # a int p(a t) dt by Gauss-Chebyshev: p(a t) sqrt(1 - t^2) / sqrt(1 - t^2).
    p = np.asarray(s.pressure(a * t))
    total = a * math.pi / n * float(np.sum(p * np.sqrt(1 - t**2)))
    assert total == pytest.approx(1.0, rel=1e-9)  # p is per P/h
    assert float(np.min(p)) >= -1e-9 * float(np.max(p))


@pytest.mark.parametrize(
    "thicknesses", [(0.5, 0.5), (0.3, 0.45, 0.25), (0.1, 0.2, 0.3, 0.4)]
)
@pytest.mark.parametrize("base", [mp.Winkler(1.0), mp.Winkler(3.0, kp=0.2)])
def test_stack_identical_sublayers_are_the_homogeneous_layer(
    thicknesses: tuple[float, ...], base: mp.Winkler
) -> None:
    ref = _solve(kw=base.kw, kp=base.kp, nu=0.25)
    s = _solve(layers=[mp.Layer(t, nu=0.25) for t in thicknesses], base=base)
    assert not s.medium.homogeneous
    bound = 1e-12 * ref.a + ref.error_estimate + s.error_estimate
    assert abs(s.a - ref.a) <= bound
    assert s.critical_vstar == pytest.approx(ref.critical_vstar, rel=1e-10)
    x = np.array([0.0, 0.5 * ref.a, 2.0 * ref.a, 1.3])
    y = np.array([0.0, -thicknesses[0], -0.7, -1.0])
    fa, fb = ref.stress_field(x, y), s.stress_field(x, y)
    scale = float(np.max(np.abs(fa.sigma_x)))
    for comp in ("sigma_x", "sigma_y", "tau_xy"):
        np.testing.assert_allclose(
            getattr(fb, comp), getattr(fa, comp), rtol=0, atol=1e-9 * scale
        )
    assert s.indentation == pytest.approx(ref.indentation, rel=1e-9)
    _check_physical(s)


@pytest.mark.parametrize(("vstar", "nu"), [(0.0, 0.3), (0.2, 0.25), (0.5, 0.2)])
def test_stack_bonded_half_space_of_its_own_material_is_the_moving_hertz_contact(
    vstar: float, nu: float
) -> None:
    s = mp.solve(
        vstar=vstar,
        radius=R,
        load=P,
        tol=1e-12,
        layers=[mp.Layer(0.4, nu=nu), mp.Layer(0.6, nu=nu)],
        base=mp.HalfSpace(1.0, nu),
    )
    phi1 = mp.phi1(vstar, nu)
    a = math.sqrt(2 * phi1 * R * P / math.pi)
    assert s.a == pytest.approx(a, rel=1e-10)
    assert s.pressure(0.0) == pytest.approx(2 / (math.pi * s.a), rel=1e-10)
    # The half-plane's critical speed is its Rayleigh speed.
    assert s.critical_vstar == pytest.approx(mp.rayleigh_vstar(nu), rel=1e-9)
    _check_physical(s)


def test_stack_smooth_stiff_half_space_tends_to_the_rigid_base() -> None:
    rigid = _solve(kw=math.inf, nu=0.3)
    gaps = []
    for mu2 in (1e3, 1e4):
        s = _solve(
            layers=[mp.Layer(0.5, nu=0.3), mp.Layer(0.5, mu=2.0, nu=0.3, rho=2.0)],
            base=mp.HalfSpace(mu2, 0.3, rho=mu2, interface="smooth"),
        )
        _check_physical(s)
        gaps.append(
            s.a
            - _solve(
                layers=[mp.Layer(0.5, nu=0.3), mp.Layer(0.5, mu=2.0, nu=0.3, rho=2.0)],
                kw=math.inf,
            ).a
        )
    assert gaps[0] > 0  # a softer base: a wider contact
    assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.05)
    assert rigid.a > 0


def test_stack_bonded_interface_continuity_and_jump() -> None:
    nu1, nu2, mu2 = 0.3, 0.2, 0.25
    s = _solve(
        layers=[mp.Layer(0.4, nu=nu1), mp.Layer(0.6, mu=mu2, nu=nu2, rho=0.5)],
        base=mp.Winkler(1.0),
    )
    _check_physical(s)
    x = np.array([0.0, 0.3, 1.0, 2.5])
    y = np.array([-0.4])
    up, down = s.stress_field(x, y, "above"), s.stress_field(x, y, "below")
    scale = float(np.max(np.abs(up.sigma_y)))
    np.testing.assert_allclose(down.sigma_y, up.sigma_y, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(down.tau_xy, up.tau_xy, rtol=0, atol=1e-12 * scale)
    eu, ed = s.strain_field(x, y, "above"), s.strain_field(x, y, "below")
    np.testing.assert_allclose(ed.eps_x, eu.eps_x, rtol=1e-9, atol=1e-12 * scale)

    def sx(mu: float, nu: float, ex: np.ndarray, sy: np.ndarray) -> np.ndarray:
        lam = 2 * nu / (1 - 2 * nu)
        return 4 * mu * (lam + 1) / (lam + 2) * ex + lam / (lam + 2) * sy

    np.testing.assert_allclose(
        up.sigma_x - down.sigma_x,
        sx(1.0, nu1, eu.eps_x, up.sigma_y) - sx(mu2, nu2, eu.eps_x, up.sigma_y),
        rtol=1e-8,
        atol=1e-11 * scale,
    )
    assert np.max(np.abs(up.sigma_x - down.sigma_x)) > 1e-3 * scale  # a real jump
    d = s.design_strains()
    assert len(d.bottom_horizontal) == 2
    assert d.bottom_horizontal[0] == pytest.approx(float(eu.eps_x[0, 0]), rel=1e-12)
    assert d.base_vertical is None


def test_stack_a_flat_punch_on_a_graded_top_sublayer_is_refused_by_name() -> None:
    with pytest.raises(mp.InvalidParameterError, match="flat punch") as info:
        mp.solve(
            vstar=0.2,
            load=P,
            layers=[mp.GradedLayer(1.0, thickness=1.0)],
            kw=1.0,
            profile=mp.Flat(half_width=0.2),
        )
    assert info.value.parameter == "profile"


def test_stack_unsupported_combinations_are_refused_by_name() -> None:
    # Friction, asymmetric tables and several zones run on a stack
    # (test_media_asymmetric.py); damped springs under it do not yet.
    stack = [mp.Layer(0.5), mp.Layer(0.5, mu=0.5)]
    with pytest.raises(mp.InvalidParameterError, match="damped base") as info:
        _solve(layers=stack, base=mp.Winkler(1.0, damping=0.2))
    assert info.value.parameter == "damping"


@pytest.mark.parametrize(
    "medium",
    [
        mp.Medium((mp.Layer(0.4), mp.Layer(0.6, mu=0.3, nu=0.3)), mp.Winkler(1.0)),
        mp.Medium(
            (mp.Layer(0.5), mp.Layer(0.5, mu=2.0, rho=2.0)), mp.HalfSpace(0.5, 0.3)
        ),
    ],
    ids=["springs", "half-space"],
)
def test_stack_accuracy_report_references_the_same_medium(medium: mp.Medium) -> None:
    """The ladder's reference is solved on the scene's medium (a reference on
    the homogeneous layer would put the errors near 1e-2)."""
    from movingpunch.accuracy import accuracy_report
    from movingpunch.scene import OutputSpec, Scene

    params = {"vstar": 0.05, "radius": R, "load": P}
    if isinstance(medium.base, mp.Winkler):
        params["kw"] = medium.base.kw
    scene = Scene(
        params=params,
        outputs={"contact_width": OutputSpec("contact_width")},
        medium=medium,
        name="stack",
    )
    report = accuracy_report(scene, tols=(1e-4, 1e-8))
    assert report is not None
    for rung in report.rungs:
        assert rung.error_a <= max(rung.tol * 0.3, 1e-12), (rung.tol, rung.error_a)
        assert rung.error_a <= rung.error_estimate + 1e-14


@pytest.mark.parametrize(
    "medium",
    [
        {"layers": [mp.Layer(0.4), mp.Layer(0.6, mu=0.3, nu=0.3)], "kw": 1.0},
        {
            "layers": [mp.Layer(0.5), mp.Layer(0.5, mu=2.0)],
            "base": mp.HalfSpace(0.5, 0.3),
        },
    ],
    ids=["springs", "half-space"],
)
def test_stack_stress_estimates_bound_the_stress_error(
    medium: dict[str, object],
) -> None:
    """The stress error estimate re-solves on the same medium, and the peak
    search uses the medium's own critical wavenumber: a loose solve's
    sigma_x is within its estimate of a tight one's."""
    loose = mp.solve(vstar=0.05, radius=R, load=P, tol=1e-5, **medium)  # type: ignore[arg-type]
    tight = mp.solve(vstar=0.05, radius=R, load=P, tol=1e-12, **medium)  # type: ignore[arg-type]
    # Points 1e-3 a or more from the contact's edges (the estimate's domain:
    # sigma_x has a square-root cusp at |x| = a).
    x = tight.a * np.array([0.0, 0.3, 0.9, 0.99, 1.01, 1.5, 3.0, 8.0])
    y = np.array([0.0, -0.5, -1.0])
    err = np.max(
        np.abs(loose.stress_field(x, y).sigma_x - tight.stress_field(x, y).sigma_x)
    )
    assert math.isfinite(loose.stress_error_estimate)
    assert err <= loose.stress_error_estimate
    peaks = loose.stress_peaks()
    ref = tight.stress_peaks()
    assert abs(peaks.top_compressive - ref.top_compressive) <= peaks.error_bound
    assert not peaks.warnings


@pytest.mark.parametrize(
    "base", [mp.HalfSpace(0.5, 0.3), mp.HalfSpace(3.0, 0.25, interface="smooth")]
)
def test_stack_half_space_displacements_from_the_reference_point(
    base: mp.HalfSpace,
) -> None:
    """Under a half-space (M1 -> m0 != 0: a logarithmic far field) every
    displacement is measured from the surface at |x| = 100 h: the surface
    Green's-function path (contact.cpp) and the mode-field path (stresses.cpp)
    take m0 e^-alpha/alpha out independently and agree; v(100 h, 0) = 0; the
    indentation is -v(0, 0)."""
    s = mp.solve(
        vstar=0.05,
        radius=R,
        load=P,
        tol=1e-10,
        layers=[mp.Layer(0.4), mp.Layer(0.6, mu=2.0)],
        base=base,
    )
    x = np.array([0.0, 0.2, 1.0, 5.0, 30.0, 100.0])
    surface = np.asarray(s.surface_displacement(x))
    field = np.asarray(s.displacement(x, 0.0))
    np.testing.assert_allclose(field, surface, rtol=1e-9, atol=1e-12 * s.indentation)
    assert abs(surface[-1]) <= 1e-12 * s.indentation
    assert s.indentation == pytest.approx(-surface[0], rel=1e-12)
    assert np.all(np.diff(surface) > 0)  # the surface rises away from the punch


def test_accuracy_report_of_a_parameter_mapping_on_a_medium() -> None:
    """``accuracy_report(mapping, medium=)`` (the TUI's accuracy tab) runs
    the ladder and its reference on the medium: the mapping's nu and springs
    are the medium's; the 1e-8 rung's a/h matches the medium's own tight
    solve, far from the homogeneous layer's."""
    from movingpunch.accuracy import accuracy_report

    medium = mp.Medium((mp.Layer(0.4), mp.Layer(0.6, mu=0.3, nu=0.3)), mp.Winkler(1.0))
    case = {"vstar": 0.05, "radius": R, "load": P, "kw": 3.0, "nu": 0.45}
    report = accuracy_report(case, tols=(1e-4, 1e-8), medium=medium)
    assert report is not None
    assert report.scene.medium == medium
    assert report.scene.params["kw"] == 1.0  # the medium's springs, not the mapping's
    for rung in report.rungs:
        assert not rung.failure, rung
        assert rung.error_a <= rung.error_estimate + 1e-14, rung
    own = mp.solve(
        vstar=0.05, radius=R, load=P, tol=1e-12, layers=medium.layers, kw=1.0
    )
    homogeneous = mp.solve(vstar=0.05, radius=R, load=P, tol=1e-12, kw=1.0, nu=0.2)
    solved = report.scene.run().solutions[0]
    assert abs(solved.a - own.a) <= 1e-7 * own.a
    assert abs(own.a - homogeneous.a) > 1e-3 * own.a
