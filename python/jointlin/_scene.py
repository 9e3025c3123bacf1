"""The harness from Python: scenes and Abaqus-format decks, their checks, modes, runs
and backbones.

``Scene.load`` and ``Scene.set`` check the input in this process through the harness's
one input path (a bad scene raises ``InputError`` with file:line:column and key). The
commands themselves run the harness's command line in a child process of the same
extension (``python -m jointlin``): the numbers and files are the ``jointlin``
program's, bit for bit; the GIL is free while it runs; its progress lines arrive
through the logger ``jointlin``; Ctrl-C (KeyboardInterrupt) stops it with its outputs
complete or absent, as the program leaves them.
"""

from __future__ import annotations

import dataclasses
import json
import logging
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

import pandas as pd

from . import _native
from ._errors import InputError, RunError

log = logging.getLogger("jointlin")


def _toml_value(value) -> str:
    """A Python value as the TOML text of ``--set KEY=VALUE``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InputError(f"a scene value must be finite, not {value}")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if value is None:
        return ""
    raise TypeError(f"a scene value must be a bool, number, string or list, not {type(value).__name__}")


def _command(args: list[str]) -> str:
    """Runs ``jointlin ARGS`` in a child process: its stderr lines to the logger, its
    stdout returned. Exit 2 raises InputError, any other failure RunError, both with
    the command's error lines; Ctrl-C interrupts the child, waits for it and re-raises."""
    env = dict(os.environ)
    # Batch-mode progress (a pipe): one line per stage and at least every few seconds.
    env.setdefault("JOINTLIN_PROGRESS_SECONDS", "5")
    child = subprocess.Popen(
        [sys.executable, "-m", "jointlin", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    errors: list[str] = []
    stdout: list[str] = []

    def forward() -> None:
        for line in child.stderr:
            line = line.rstrip("\n")
            if line.startswith("error"):
                errors.append(line.removeprefix("error: "))
                log.error(line)
            elif line.startswith("warning"):
                log.warning(line)
            elif line:
                log.info(line)

    readers = [
        threading.Thread(target=forward, daemon=True),
        threading.Thread(target=lambda: stdout.append(child.stdout.read()), daemon=True),
    ]
    for r in readers:
        r.start()
    try:
        # Polled, so that a Ctrl-C reaches this thread whichever thread the signal hit.
        while True:
            try:
                code = child.wait(timeout=0.2)
                break
            except subprocess.TimeoutExpired:
                continue
    except KeyboardInterrupt:
        # From a terminal the child has the signal too; from elsewhere (a notebook's
        # interrupt, a signal to this process) it is passed on. Its outputs are then
        # complete or absent, as the program leaves them.
        if child.poll() is None:
            child.send_signal(signal.SIGINT)
        child.wait()
        raise
    finally:
        for r in readers:
            r.join()
    message = "\n".join(errors) or f"jointlin {' '.join(args[:1])} ended with exit code {code}"
    if code == 2:
        raise InputError(message)
    if code != 0:
        raise RunError(message)
    return "".join(stdout)


# pandas 3 parses floats correctly rounded by default (and deprecates the option);
# earlier versions need the round-trip parser for the last bit.
_EXACT = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}


def _read_csv(path: Path) -> pd.DataFrame:
    """A CSV of the commands, every number to the bit (they write round-trip digits)."""
    return pd.read_csv(path, **_EXACT)


def _csv(path: Path) -> pd.DataFrame | None:
    return _read_csv(path) if path.exists() else None


@dataclasses.dataclass
class Result:
    """A run's outputs, read from the files the command wrote (docs/outputs.md).

    frf: results.csv (results_time.csv for a time-domain run), the columns with units in
    their names; points: points.csv (points_time.csv); harmonics: harmonics.csv
    (harmonic balance); frf_down: results_down.csv (sweep up and down); meta: run.json;
    out: the output directory (None when the run used a temporary one, removed after
    reading)."""

    frf: pd.DataFrame
    points: pd.DataFrame | None
    harmonics: pd.DataFrame | None
    frf_down: pd.DataFrame | None
    meta: dict
    out: Path | None

    @classmethod
    def read(cls, out: Path, time_domain: bool = False) -> "Result":
        """The outputs of a complete run in ``out`` (run.json written last)."""
        suffix = "_time" if time_domain else ""
        return cls(
            frf=_read_csv(out / f"results{suffix}.csv"),
            points=_csv(out / f"points{suffix}.csv"),
            harmonics=_csv(out / "harmonics.csv"),
            frf_down=_csv(out / "results_down.csv"),
            meta=json.loads((out / "run.json").read_text()),
            out=out,
        )

    def plot(self, ax=None, phase: bool = False):
        """The FRF of every output's amplitude (or phase) against frequency, log scale,
        the columns' units on the axes (matplotlib, the optional dependency ``plot``).
        Returns the axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        freq = self.frf.columns[0]
        kind = "_phase_deg" if phase else "_amp_"
        for c in self.frf.columns[1:]:
            if kind in c:
                ax.plot(self.frf[freq], self.frf[c], label=c)
        ax.set_xlabel(freq)
        ax.set_ylabel("phase (deg)" if phase else "amplitude (" + self._length_unit() + ")")
        if not phase:
            ax.set_yscale("log")
        ax.legend()
        ax.grid(True, which="both", alpha=0.3)
        return ax

    def _length_unit(self) -> str:
        units = self.meta.get("scene", {}).get("spec", {}).get("units", {})
        return units.get("length", "length") if isinstance(units, dict) else "length"


class Scene:
    """A scene (TOML) or an Abaqus-format deck (.inp) with its overrides."""

    def __init__(self, path: str | os.PathLike, sets: list[str] | None = None):
        self.path = Path(path)
        self._sets = list(sets or [])
        self.file, self.kind = _native.check_input(str(self.path), self._sets)

    @classmethod
    def load(cls, path: str | os.PathLike) -> "Scene":
        """Reads and checks ``path`` (InputError with file:line:column and key, or a
        deck's file:line and keyword, when the harness refuses it)."""
        return cls(path)

    def set(self, key: str, value) -> "Scene":
        """Changes a value before the scene is read, as ``--set KEY=VALUE``: ``key`` a
        dotted path (``iteration.mode``, ``interfaces.*.mu``, ``interfaces.0.mu``),
        ``value`` a bool, number, string or list (None removes the key). Checked at
        once: a value the scene's rules refuse raises InputError and is not kept.
        Returns the scene, so calls chain."""
        sets = [*self._sets, f"{key}={_toml_value(value)}"]
        self.file, self.kind = _native.check_input(str(self.path), sets)
        self._sets = sets
        return self

    @property
    def overrides(self) -> list[str]:
        """The ``KEY=VALUE`` overrides given so far."""
        return list(self._sets)

    def _args(self, command: str) -> list[str]:
        args = [command, str(self.path)]
        for s in self._sets:
            args += ["--set", s]
        return args

    def check(self, modes: bool = False, forecast: bool = False) -> str:
        """``jointlin check``: the summary of the model (free DOFs, contact points; with
        ``modes`` the stuck modes, with ``forecast`` the time a run will take)."""
        return _command(self._args("check") + ["--modes"] * modes + ["--forecast"] * forecast)

    def modes(self, count: int | None = None) -> pd.DataFrame:
        """``jointlin modes``: the modes with every closed joint stuck after the static
        step, modes.csv as a DataFrame (frequency in the scene's units)."""
        with tempfile.TemporaryDirectory(prefix="jointlin-modes-") as d:
            args = self._args("modes") + ["--out", d]
            if count is not None:
                args += ["--count", str(int(count))]
            _command(args)
            return _read_csv(Path(d) / "modes.csv")

    def run(
        self,
        mode: str | None = None,
        harmonics: int | None = None,
        samples: int | None = None,
        out: str | os.PathLike | None = None,
        plots: bool = False,
        time_domain: bool = False,
    ) -> Result:
        """``jointlin run``: the static step, the sweep and the reports. ``mode`` "fast",
        "thesis" or "harmonic_balance" (with ``harmonics``, ``samples``) overrides the
        scene's; ``time_domain`` runs the time-domain reference instead. With ``out``
        the files stay there (and the SVG plots with ``plots``); without, a temporary
        directory is read and removed."""
        args = self._args("run")
        if mode is not None:
            args += ["--mode", mode.replace("_", "-")]
        if harmonics is not None:
            args += ["--harmonics", str(int(harmonics))]
        if samples is not None:
            args += ["--samples", str(int(samples))]
        if time_domain:
            args.append("--time-domain")
        if not plots or out is None:
            args.append("--no-plots")
        with _output_dir(out) as d:
            _command(args + ["--out", str(d)])
            r = Result.read(d, time_domain)
            if out is None:
                r.out = None
            return r


class _output_dir:
    """``out`` (created) or a temporary directory removed on exit."""

    def __init__(self, out):
        self.out, self.temp = out, None

    def __enter__(self) -> Path:
        if self.out is not None:
            Path(self.out).mkdir(parents=True, exist_ok=True)
            return Path(self.out)
        self.temp = tempfile.mkdtemp(prefix="jointlin-")
        return Path(self.temp)

    def __exit__(self, *exc) -> None:
        if self.temp is not None:
            shutil.rmtree(self.temp, ignore_errors=True)


def backbone(
    scene: Scene | str | os.PathLike,
    mode: int = 1,
    harmonics: int | None = None,
    amplitudes=None,
    out: str | os.PathLike | None = None,
) -> pd.DataFrame:
    """``jointlin backbone``: natural frequency and damping ratio of a mode against its
    modal amplitude (first order, or with ``harmonics`` the extended periodic motion
    concept), backbone.csv as a DataFrame; run.json in ``.attrs["meta"]``.
    ``amplitudes``: (from, to, count), log spaced (default: the command's)."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    args = scene._args("backbone") + ["--mode", str(int(mode))]
    if harmonics is not None:
        args += ["--harmonics", str(int(harmonics))]
    if amplitudes is not None:
        lo, hi, count = amplitudes
        args += ["--amplitudes", f"{float(lo)!r},{float(hi)!r},{int(count)}"]
    with _output_dir(out) as d:
        _command(args + ["--out", str(d)])
        table = _read_csv(d / "backbone.csv")
        table.attrs["meta"] = json.loads((d / "run.json").read_text())
        return table


def reduce(
    scene: Scene | str | os.PathLike,
    out: str | os.PathLike,
    modes: int | None = None,
) -> Scene:
    """``jointlin reduce``: an FE scene or deck reduced onto its contact directions,
    outputs and load plus interior modes (Craig–Bampton), written into ``out`` as a
    ``[[matrices]]`` model with its scene; returns that scene, its run.json in
    ``.meta``. ``modes``: the interior modes (default: the command's band)."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    args = scene._args("reduce") + ["--out", str(out)]
    if modes is not None:
        args += ["--modes", str(int(modes))]
    _command(args)
    reduced = Scene.load(Path(out) / "scene.toml")
    reduced.meta = json.loads((Path(out) / "run.json").read_text())
    return reduced
