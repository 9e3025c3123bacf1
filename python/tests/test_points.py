"""jointlin.Point and Point3d: the time-domain points, stepped one by one and over
histories, against the linearization of the same loop."""

import numpy as np
import pytest

import jointlin


def loop_history(amplitude, top, samples=400, cycles=3):
    """From slip 0 up to `top`, then `cycles` cosine cycles of half-width `amplitude`
    between `top` and `top - 2 amplitude` (`samples` per cycle)."""
    rise = np.linspace(0.0, top, samples // 4 + 1)
    t = np.linspace(0.0, 2 * np.pi * cycles, samples * cycles + 1)
    return np.concatenate([rise, (top - amplitude) + amplitude * np.cos(t[1:])])


def loop_top(law, rule, lin, mu, fn, k):
    """The steady loop's upper tip (docs/model.md): A for Masing's rule and for sliding;
    for the thesis rule in Mindlin microslip the loop is shifted towards the first
    loading, its tips at g^-1(F) = d*(1 - v^2) and -F/k_T0, v = (1 - F/(mu F_N))^(1/3)."""
    a, f = float(lin.amplitude_ratio * lin.slip_limit), float(lin.peak_force)
    if rule == "masing" or law == "jenkins" or f >= mu * fn * (1 - 1e-12):
        return a
    v = np.cbrt(1 - f / (mu * fn))
    return float(lin.slip_limit * (1 - v * v))


@pytest.mark.parametrize("law", ["mindlin", "jenkins"])
@pytest.mark.parametrize("rule", ["thesis", "masing"])
def test_steady_loop_dissipates_the_linearizations_energy(law, rule):
    # The same loop in the time domain and in the energy balance (3.14): the energy of
    # one closed cycle is A_hys, and k* the first harmonic's in-phase part (3.8).
    mu, fn, k = 0.3, 2.0, 1282.7
    for ratio in (0.1, 0.3, 0.6, 0.9, 3.0):
        slip_limit = jointlin.linearize(law, rule, mu, fn, k, amplitude=1.0, omega=1.0).check().slip_limit
        a = ratio * slip_limit
        lin = jointlin.linearize(law, rule, mu, fn, k, amplitude=a, omega=1.0).check()
        top = loop_top(law, rule, lin, mu, fn, k)
        assert top - 2 * a == pytest.approx(-lin.peak_force / k if rule == "thesis" and top != a else -a)
        p = jointlin.Point(law, rule, mu, fn, k)
        loop = p.run(loop_history(a, top))
        last = loop.iloc[-401:]
        energy = last["dissipated"].iloc[1:].sum()
        assert energy == pytest.approx(lin.energy_per_cycle, rel=1e-9), (ratio, energy, lin.energy_per_cycle)
        assert np.abs(loop["force"]).max() <= mu * fn * (1 + 1e-12)
        t = np.linspace(0.0, 2 * np.pi, 401)
        f = last["force"].to_numpy()
        k_star = np.trapezoid(f * np.cos(t), t) / np.pi / a
        assert k_star == pytest.approx(lin.k_star, rel=1e-4), (ratio, k_star, lin.k_star)


def test_run_equals_steps_and_keeps_the_state():
    slips = loop_history(1e-3, 1e-3, samples=48, cycles=2)
    a = jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1282.7)
    b = jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1282.7)
    run = a.run(slips)
    steps = [b.step(u) for u in slips]
    assert run["force"].tolist() == [s.force for s in steps]
    assert run["tangent"].tolist() == [s.tangent for s in steps]
    assert np.array_equal(a.state, b.state)
    a.reset()
    assert not a.state.any()
    # A failed sample raises with its index; the state stays at the last good sample.
    before = b.state
    with pytest.raises(jointlin.NonFiniteError, match="sample 2"):
        b.run([1e-4, 2e-4, np.nan, 3e-4])
    c = jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1282.7)
    c.run(np.concatenate([slips, [1e-4, 2e-4]]))
    b2 = jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1282.7)
    b2.run(slips)
    assert not np.array_equal(before, b.state)
    assert np.array_equal(b.state, c.state)


def test_invalid_points_raise_at_once():
    with pytest.raises(jointlin.OutOfRangeError):
        jointlin.Point(mu=-0.3, normal_force=2.0, k_t0=1.0)
    with pytest.raises(jointlin.NonFiniteError):
        jointlin.Point(mu=0.3, normal_force=np.inf, k_t0=1.0)
    with pytest.raises(jointlin.OutOfRangeError):
        jointlin.Point3d(mu=0.3, k_t0=1.0, normal_stiffness=0.0)
    with pytest.raises(ValueError):
        jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1.0).run(np.zeros((2, 2)))


def test_point3d_run_and_the_coulomb_circle():
    p = jointlin.Point3d(law="jenkins", mu=0.3, k_t0=1000.0, normal_stiffness=1e4)
    q = jointlin.Point3d(law="jenkins", mu=0.3, k_t0=1000.0, normal_stiffness=1e4)
    t = np.linspace(0, 4 * np.pi, 801)
    r_path = 3e-3
    h = np.column_stack([r_path * np.cos(t), r_path * np.sin(t), np.full_like(t, 2e-4)])
    r = p.run(h)
    assert r.force.shape == (801, 3) and r.stiffness.shape == (801, 3, 3)
    steps = [q.step(row) for row in h]
    assert np.array_equal(r.force, np.array([s.force for s in steps]))
    # N = k_N h; the tangential force stays inside the circle mu N.
    assert np.allclose(r.force[:, 2], 1e4 * 2e-4)
    tangential = np.hypot(r.force[:, 0], r.force[:, 1])
    assert tangential.max() <= 0.3 * 2.0 * (1 + 1e-12)
    # Steady sliding round the circle: the spring, stretched by mu N / k_T0, trails the
    # slider along its velocity, tangent to the slider's circle of radius
    # rho = (r^2 - (mu N / k_T0)^2)^(1/2); a cycle dissipates mu N 2 pi rho (the chords
    # of 400 steps per cycle shorten it by 1e-5).
    want = 0.3 * 2.0 * 2 * np.pi * np.sqrt(r_path**2 - (0.3 * 2.0 / 1000.0) ** 2)
    assert r.dissipated[401:].sum() == pytest.approx(want, rel=1e-4)
    # Lifted off: no force.
    s = q.step((0.0, 0.0, -1e-3))
    assert not s.force.any() and s.regime == jointlin.Regime.OPEN
