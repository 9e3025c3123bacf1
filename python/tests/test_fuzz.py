"""Hard and wrong inputs from Python: a status or a Python exception, never a crash,
never a NaN in an element whose status is OK (hypothesis)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jointlin

# Every double: NaN, ±Inf, subnormals, ±0, the largest and smallest.
anything = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)
arrays = st.lists(anything, min_size=0, max_size=6).map(np.array)
scalar_or_array = st.one_of(anything, arrays)
RESULT_FIELDS = ("k_star", "d_star", "eta", "energy_per_cycle", "peak_force", "slip_limit", "amplitude_ratio")


@settings(max_examples=400, deadline=None)
@given(
    law=st.sampled_from(["mindlin", "jenkins"]),
    rule=st.sampled_from(["thesis", "masing"]),
    mu=scalar_or_array,
    normal_force=scalar_or_array,
    k_t0=anything,
    amplitude=scalar_or_array,
    omega=anything,
    method=st.sampled_from(["graded", "simpson", "gauss"]),
    points=st.integers(-5, 300),
)
def test_linearize_never_crashes(law, rule, mu, normal_force, k_t0, amplitude, omega, method, points):
    try:
        r = jointlin.linearize(law, rule, mu, normal_force, k_t0, amplitude, omega, method=method, points=points)
    except ValueError as e:
        assert "broadcast" in str(e)
        return
    ok = np.asarray(r.status) == 0
    for field in RESULT_FIELDS:
        values = np.asarray(getattr(r, field))
        assert np.isfinite(values[ok]).all(), field
        assert np.isnan(values[~ok]).all(), field
        assert (values[ok] >= 0).all() or field == "peak_force"
    k = np.broadcast_to(np.asarray(k_t0, dtype=float), np.shape(r.k_star))
    assert (np.asarray(r.k_star)[ok] <= k[ok] * (1 + 1e-12)).all()
    assert set(np.unique(r.status)) <= {int(s) for s in jointlin.Status}
    if not ok.all():
        with pytest.raises(jointlin.JointlinError):
            r.check()


@settings(max_examples=200, deadline=None)
@given(
    law=st.sampled_from(["mindlin", "jenkins"]),
    rule=st.sampled_from(["thesis", "masing"]),
    mu=st.floats(0, 2),
    normal_force=st.floats(-10, 1e6),
    k_t0=st.floats(1e-6, 1e9),
    slips=st.lists(anything, min_size=0, max_size=40),
)
def test_point_run_never_crashes(law, rule, mu, normal_force, k_t0, slips):
    p = jointlin.Point(law, rule, mu, normal_force, k_t0)
    try:
        run = p.run(np.array(slips, dtype=float))
    except jointlin.JointlinError as e:
        assert e.status in (jointlin.Status.NON_FINITE, jointlin.Status.OVERFLOW)
        assert "sample" in str(e)
        return
    assert len(run) == len(slips)
    assert np.isfinite(run[["force", "tangent", "dissipated"]].to_numpy()).all()
    assert (np.abs(run["force"]) <= max(mu * normal_force, 0) * (1 + 1e-12)).all()
    assert (run["dissipated"] >= 0).all()


@settings(max_examples=100, deadline=None)
@given(history=st.lists(st.tuples(anything, anything, anything), min_size=0, max_size=20))
def test_point3d_run_never_crashes(history):
    p = jointlin.Point3d(law="mindlin", mu=0.3, k_t0=1e3, normal_stiffness=1e4, cells=4)
    try:
        run = p.run(np.array(history, dtype=float).reshape(-1, 3))
    except jointlin.JointlinError as e:
        assert e.status in (jointlin.Status.NON_FINITE, jointlin.Status.OVERFLOW)
        return
    assert np.isfinite(run.force).all() and (run.force[:, 2] >= 0).all()


@pytest.mark.parametrize(
    "bad",
    [None, "x", b"1", 1j, [1.0, "a"], [[1.0], [2.0, 3.0]], {"a": 1}, object()],
)
def test_wrong_types_are_exceptions(bad):
    with pytest.raises((TypeError, ValueError)):
        jointlin.linearize(mu=bad, normal_force=2.0, k_t0=1e3, amplitude=1e-3, omega=1.0)
    with pytest.raises((TypeError, ValueError)):
        jointlin.Point(mu=0.3, normal_force=2.0, k_t0=1e3).run(bad)
    with pytest.raises((TypeError, ValueError)):
        jointlin.Point3d(mu=0.3, k_t0=1e3, normal_stiffness=1e4).step(bad)
