"""jointlin.Scene, Result and backbone: the same numbers, columns and messages as the
`jointlin` program."""

import json
import logging
import os
import signal
import subprocess
import threading
import time

import pandas as pd
import pytest

import jointlin
from jointlin._scene import _read_csv as read_csv


def cli(program, *args):
    return subprocess.run([str(program), *map(str, args)], capture_output=True, text=True)


def test_run_equals_the_program_bit_for_bit(repo, program, tmp_path):
    scene = repo / "scenes" / "three-beams.toml"
    done = cli(program, "run", scene, "--out", tmp_path / "cli", "--no-plots", "--quiet")
    assert done.returncode == 0, done.stderr
    r = jointlin.Scene.load(scene).run(out=tmp_path / "py")
    for name in ("results.csv", "points.csv", "stick_slip.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    want = read_csv(tmp_path / "cli" / "results.csv")
    assert list(r.frf.columns) == list(want.columns)
    # Every number of the file, read by Python's own float, is the DataFrame's to the bit.
    lines = (tmp_path / "cli" / "results.csv").read_text().splitlines()[1:]
    for row, line in zip(r.frf.itertuples(index=False), lines):
        for value, text in zip(row[:-1], line.split(",")[:-1]):
            assert float(text).hex() == float(value).hex()
    assert list(r.frf.columns[:3]) == ["frequency_Hz", "middle_tip_amp_mm", "middle_tip_phase_deg"]
    pd.testing.assert_frame_equal(r.frf, want, check_exact=True)
    assert len(r.frf) == 100 and r.meta["all_converged"] is True
    assert r.meta["command"] == "run" and r.out == tmp_path / "py"
    # Without `out`, a temporary directory is read and removed: the same table.
    r2 = jointlin.Scene.load(scene).run()
    assert r2.out is None
    pd.testing.assert_frame_equal(r2.frf, want, check_exact=True)


def test_backbone_equals_the_program(repo, program, tmp_path):
    scene = repo / "scenes" / "jenkins-chain.toml"
    done = cli(program, "backbone", scene, "--out", tmp_path / "cli")
    assert done.returncode == 0, done.stderr
    want = read_csv(tmp_path / "cli" / "backbone.csv")
    got = jointlin.backbone(scene)
    pd.testing.assert_frame_equal(got, want, check_exact=True)
    assert got.attrs["meta"]["command"] == "backbone"
    h3 = jointlin.backbone(jointlin.Scene.load(scene), mode=1, harmonics=3, amplitudes=(0.05, 5.0, 6))
    done = cli(program, "backbone", scene, "--harmonics", 3, "--amplitudes", "0.05,5.0,6", "--out", tmp_path / "h3")
    assert done.returncode == 0, done.stderr
    pd.testing.assert_frame_equal(h3, read_csv(tmp_path / "h3" / "backbone.csv"), check_exact=True)
    assert len(h3) == 6


def test_reduce_writes_a_scene_that_runs_as_the_fe_model(repo, tmp_path):
    full = jointlin.Scene.load(repo / "scenes" / "three-beams-coarse.toml")
    reduced = jointlin.reduce(full, tmp_path / "reduced", modes=16)
    assert reduced.meta["joints"] == 72 and reduced.meta["interior_modes"] == 16
    assert reduced.meta["largest_relative_difference"] < 1e-9
    a = full.set("iteration.tolerance", 1e-10).run().frf
    b = reduced.run().frf
    assert (b["status"] == "converged").all()
    for col in ("middle_tip_amp_mm", "top_tip_amp_mm"):
        assert ((b[col] / a[col] - 1).abs() < 1e-7).all(), col


def test_errors_carry_the_programs_message(repo, program, tmp_path):
    text = (repo / "scenes" / "block-stick.toml").read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("mu = 0.3", "mu = -0.3", 1))
    done = cli(program, "check", bad)
    assert done.returncode == 2
    line = done.stderr.strip().splitlines()[-1]
    with pytest.raises(jointlin.InputError) as e:
        jointlin.Scene.load(bad)
    assert f"error: {e.value}" == line
    assert f"{bad}:" in str(e.value) and ":1: key `interfaces[0].mu`" in str(e.value)
    # A refused override is not kept; the scene stays usable.
    s = jointlin.Scene.load(repo / "scenes" / "block-stick.toml")
    with pytest.raises(jointlin.InputError, match="interfaces"):
        s.set("interfaces.0.mu", -1.0)
    assert s.overrides == []
    with pytest.raises(jointlin.InputError):
        jointlin.Scene.load(tmp_path / "missing.toml")
    with pytest.raises(TypeError):
        s.set("sweep.points", object())


def test_set_changes_the_run(repo):
    scene = repo / "scenes" / "three-beams.toml"
    base = jointlin.Scene.load(scene).run()
    s = jointlin.Scene.load(scene).set("interfaces.*.mu", 0.05).set("iteration.mode", "fast")
    assert s.overrides == ["interfaces.*.mu=0.05", 'iteration.mode="fast"']
    less = s.run()
    # Less friction, more slip: more joint damping at the first resonance's peak.
    col = "middle_tip_amp_mm"
    assert less.frf[col].max() < base.frf[col].max()
    assert less.meta["command_line"].count("--set") == 2


def test_modes_and_check(repo):
    s = jointlin.Scene.load(repo / "scenes" / "three-beams.toml")
    m = s.modes(count=4)
    assert len(m) == 4 and m.columns[0] == "mode" and m.columns[1] == "frequency_Hz"
    assert (m["frequency_Hz"].diff().dropna() > 0).all()
    summary = s.check()
    assert "contact points" in summary or "free DOFs" in summary


def test_progress_through_logging(repo, caplog):
    with caplog.at_level(logging.INFO, logger="jointlin"):
        jointlin.Scene.load(repo / "scenes" / "three-beams.toml").run()
    messages = [r.getMessage() for r in caplog.records if r.name == "jointlin"]
    assert any("free DOFs" in m for m in messages)
    assert any(m.startswith("wrote ") for m in messages)


def test_ctrl_c_leaves_the_outputs_absent(repo, tmp_path):
    # The thesis-mode sweep of the three beams takes seconds; a SIGINT to this process
    # after 1 s becomes KeyboardInterrupt, the child is interrupted and run.json (the
    # marker of a complete run, written last) is absent.
    s = jointlin.Scene.load(repo / "scenes" / "three-beams.toml")
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.run(mode="thesis", out=tmp_path / "out")
    timer.join()
    assert time.monotonic() - started < 3.5, "the child was not stopped"
    assert not (tmp_path / "out" / "run.json").exists()
    assert not list((tmp_path / "out").glob("*.partial"))


def test_python_m_jointlin_is_the_program(repo, program):
    import sys

    a = subprocess.run([sys.executable, "-m", "jointlin", "--version"], capture_output=True, text=True)
    b = cli(program, "--version")
    assert a.returncode == b.returncode == 0 and a.stdout == b.stdout
    a = subprocess.run([sys.executable, "-m", "jointlin", "run"], capture_output=True, text=True)
    assert a.returncode == 2 and "--out" in a.stderr


def test_plot_draws_every_output(repo):
    import matplotlib

    matplotlib.use("Agg")
    r = jointlin.Scene.load(repo / "scenes" / "three-beams.toml").run()
    ax = r.plot()
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels == ["middle_tip_amp_mm", "top_tip_amp_mm"]
    assert ax.get_xlabel() == "frequency_Hz" and ax.get_ylabel() == "amplitude (mm)"
    assert ax.get_yscale() == "log"
    phase = r.plot(phase=True)
    assert [line.get_label() for line in phase.get_lines()] == ["middle_tip_phase_deg", "top_tip_phase_deg"]
