"""jointlin.linearize, linearize3d and screw_preload against the C API and the
documented numbers."""

import threading

import numpy as np
import pytest

import jointlin
from conftest import Contact, Linearization


def test_hello_numbers():
    # examples/c/hello.c: the thesis's block at A = 4.401e-4 mm, omega = 1.3 rad/s.
    r = jointlin.linearize(
        law="mindlin", rule="thesis", mu=0.3, normal_force=2.0, k_t0=1282.7, amplitude=4.401e-4, omega=1.3
    )
    assert r.status == jointlin.Status.OK and r.ok
    assert f"{r.k_star:.6g}" == "1157.41"
    assert f"{r.d_star:.6g}" == "91.8424"
    assert r.regime == jointlin.Regime.MICROSLIP
    assert np.ndim(r.k_star) == 0


def grid():
    """10^4 inputs: both laws and rules, amplitudes over 1e-6..1e2 of the slip limit,
    frequencies, normal forces (open ones among them) and friction coefficients."""
    rng = np.random.default_rng(7)
    n = 10_000
    return dict(
        law=rng.integers(0, 2, n),
        rule=rng.integers(0, 2, n),
        mu=rng.choice([0.0, 0.1, 0.3, 0.8], n),
        normal_force=rng.choice([-1.0, 0.0, 1e-3, 2.0, 5e3], n),
        k_t0=10 ** rng.uniform(0, 6, n),
        amplitude=10 ** rng.uniform(-9, 1, n),
        omega=10 ** rng.uniform(-2, 5, n),
    )


def test_bit_equal_to_the_c_api_on_a_grid(capi):
    g = grid()
    laws, rules = ["mindlin", "jenkins"], ["thesis", "masing"]
    checked = 0
    for law in (0, 1):
        for rule in (0, 1):
            sel = (g["law"] == law) & (g["rule"] == rule)
            r = jointlin.linearize(
                laws[law], rules[rule], g["mu"][sel], g["normal_force"][sel], g["k_t0"][sel],
                g["amplitude"][sel], g["omega"][sel],
            )
            for j, i in enumerate(np.flatnonzero(sel)):
                c = Contact(law, rule, g["mu"][i], g["normal_force"][i], g["k_t0"][i])
                out = Linearization()
                status = capi.jointlin_linearize(c, g["amplitude"][i], g["omega"][i], None, out)
                assert status == r.status[j]
                if status != 0:
                    assert np.isnan(r.k_star[j]) and r.regime[j] == -1
                    continue
                for field in ("k_star", "d_star", "eta", "energy_per_cycle", "peak_force", "slip_limit", "amplitude_ratio"):
                    a, b = getattr(out, field), getattr(r, field)[j]
                    assert a.hex() == float(b).hex(), (field, i, a, b)
                assert out.regime == r.regime[j]
                checked += 1
    # Most of the grid succeeds: the comparison is of numbers, not of statuses.
    assert checked > 9000


def test_broadcasting_and_shapes():
    a = np.logspace(-6, -2, 5)[:, None]
    f = np.array([0.5, 1.0, 2.0])
    r = jointlin.linearize(mu=0.3, normal_force=f, k_t0=1282.7, amplitude=a, omega=1.3)
    assert r.k_star.shape == (5, 3) and r.status.shape == (5, 3)
    for i in range(5):
        for j in range(3):
            s = jointlin.linearize(mu=0.3, normal_force=f[j], k_t0=1282.7, amplitude=a[i, 0], omega=1.3)
            assert s.k_star == r.k_star[i, j] and s.d_star == r.d_star[i, j]
    # k* falls with the amplitude at fixed F_N (microslip softening).
    assert np.all(np.diff(r.k_star[:, 2]) <= 0)
    with pytest.raises(ValueError, match="broadcast"):
        jointlin.linearize(mu=0.3, normal_force=[1.0, 2.0], k_t0=1e3, amplitude=[1e-3, 2e-3, 3e-3], omega=1.0)
    assert jointlin.linearize(mu=0.3, normal_force=2.0, k_t0=1e3, amplitude=np.empty((0, 4)), omega=1.0).k_star.shape == (0, 4)
    frame = r.to_frame()
    assert len(frame) == 15 and "k_star" in frame and "status" in frame


def test_statuses_per_element_and_named_errors():
    r = jointlin.linearize(
        mu=[0.3, -0.1, 0.3, 0.3], normal_force=[2.0, 2.0, np.nan, 2.0], k_t0=1282.7,
        amplitude=[1e-4, 1e-4, 1e-4, 1e-4], omega=[1.0, 1.0, 1.0, 5e-324],
    )
    assert list(r.status) == [jointlin.Status.OK, jointlin.Status.OUT_OF_RANGE, jointlin.Status.NON_FINITE, jointlin.Status.OVERFLOW]
    assert np.isfinite(r.k_star[0]) and np.isnan(r.k_star[1:]).all()
    assert list(r.regime[1:]) == [jointlin.Regime.FAILED] * 3
    with pytest.raises(jointlin.OutOfRangeError, match=r"3 of 4 elements failed; the first at index \(1,\)"):
        r.check()
    with pytest.raises(jointlin.NonFiniteError):
        jointlin.check(r.status[2:])
    with pytest.raises(jointlin.ResultOverflowError):
        jointlin.check(r.status[3])
    assert jointlin.check(r.status[:1]) is None
    assert jointlin.Status.NON_FINITE.message == "an input was NaN or infinite"
    assert issubclass(jointlin.NonFiniteError, ValueError)


def test_wrong_types_raise():
    base = dict(mu=0.3, normal_force=2.0, k_t0=1e3, amplitude=1e-3, omega=1.0)
    for key, bad in [("mu", None), ("amplitude", "1e-3"), ("omega", 1j), ("normal_force", [1.0, None]), ("k_t0", object())]:
        with pytest.raises(TypeError, match=key):
            jointlin.linearize(**{**base, key: bad})
    with pytest.raises(ValueError, match="law"):
        jointlin.linearize(law="coulomb", **base)
    with pytest.raises(ValueError, match="rule"):
        jointlin.linearize(rule=None, **base)
    with pytest.raises(TypeError, match="points"):
        jointlin.linearize(points=2.5, **base)
    bad_points = jointlin.linearize(method="simpson", points=3, **base)
    assert bad_points.status == jointlin.Status.OUT_OF_RANGE


def test_methods_converge_to_the_default():
    base = dict(mu=0.3, normal_force=2.0, k_t0=1282.7, amplitude=np.array([1e-4, 4e-4, 1e-3]), omega=1.3)
    exact = jointlin.linearize(**base).check()
    simpson = jointlin.linearize(method="simpson", points=4096, **base).check()
    assert np.allclose(simpson.k_star, exact.k_star, rtol=1e-7)
    coarse = jointlin.linearize(method="simpson", points=16, **base).check()
    assert not np.allclose(coarse.k_star, exact.k_star, rtol=1e-7)


def test_threads_give_the_same_numbers():
    a = np.logspace(-7, -1, 20_000)
    want = jointlin.linearize(mu=0.3, normal_force=2.0, k_t0=1282.7, amplitude=a, omega=1.3).k_star
    got = [None] * 4

    def work(i):
        got[i] = jointlin.linearize(mu=0.3, normal_force=2.0, k_t0=1282.7, amplitude=a, omega=1.3).k_star

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for g in got:
        assert np.array_equal(g, want)


def test_linearize3d_reduces_to_the_jenkins_point_on_a_line():
    # A straight path (A2 = 0) of a Jenkins point is the one-direction Jenkins element.
    a = np.array([1e-4, 1e-3, 1e-2])
    r3 = jointlin.linearize3d(law="jenkins", mu=0.3, k_t0=1000.0, normal_force=2.0, amplitude_1=a, amplitude_2=0.0, omega=2.0).check()
    r1 = jointlin.linearize(law="jenkins", rule="masing", mu=0.3, normal_force=2.0, k_t0=1000.0, amplitude=a, omega=2.0).check()
    assert r3.k_star.shape == (3, 2)
    assert np.allclose(r3.k_star[:, 0], r1.k_star, rtol=1e-9)
    assert np.allclose(r3.energy_per_cycle, r1.energy_per_cycle, rtol=1e-9)
    bad = jointlin.linearize3d(mu=0.3, k_t0=1e3, normal_force=2.0, amplitude_1=-1.0, omega=1.0)
    assert bad.status == jointlin.Status.OUT_OF_RANGE


def test_screw_preload():
    # F = T / (0.16 P + 0.58 d2 mu_thread + d_km/2 mu_head), VDI 2230 R13.
    t, p, d2, mt, mh, dk = 10_000.0, 1.5, 9.026, 0.12, 0.12, 13.0
    want = t / (0.16 * p + 0.58 * d2 * mt + dk / 2 * mh)
    r = jointlin.screw_preload(t, p, d2, mt, mh, dk).check()
    assert r.preload == pytest.approx(want, rel=1e-14)
    r = jointlin.screw_preload([t, -1.0], p, d2, mt, mh, dk)
    assert list(r.status) == [0, jointlin.Status.OUT_OF_RANGE]
