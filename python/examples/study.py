"""A parameter study over the friction coefficient and the clamping pressure of the
three-beam scene: the peak amplitude of the middle beam's tip and the power lost in the joints
there (the first bending resonance, 301 frequencies over 1050–1200 Hz), one run per pair (docs/python.md shows the first ten lines).

    python python/examples/study.py OUT_DIR      (writes OUT_DIR/study.csv, study.svg)"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import jointlin  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/python-study")
out.mkdir(parents=True, exist_ok=True)
scene = Path(__file__).resolve().parents[2] / "scenes" / "three-beams.toml"

# --- the study (docs/python.md) ---
rows = []
for mu in (0.05, 0.1, 0.2, 0.4):
    for pressure in (0.25, 0.5, 1.0, 2.0):
        s = jointlin.Scene.load(scene).set("interfaces.*.mu", mu).set("preload.*.pressure", pressure)
        s.set("sweep.f_min", 1050.0).set("sweep.f_max", 1200.0).set("sweep.count", 301).set("sweep.refine", None)
        frf = s.run().frf
        peak = frf["middle_tip_amp_mm"].idxmax()
        rows.append(dict(mu=mu, pressure_MPa=pressure, **frf.loc[peak, ["frequency_Hz", "middle_tip_amp_mm", "dissipated_power_N_mm_per_s"]]))
table = pd.DataFrame(rows)
# --- end of the study ---

table.to_csv(out / "study.csv", index=False)
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for mu, g in table.groupby("mu"):
    axes[0].plot(g["pressure_MPa"], g["middle_tip_amp_mm"], "o-", label=f"μ = {mu}")
    axes[1].plot(g["pressure_MPa"], g["dissipated_power_N_mm_per_s"], "o-", label=f"μ = {mu}")
axes[0].set_ylabel("peak amplitude of the middle tip (mm)")
axes[1].set_ylabel("power lost in the joints at the peak (N·mm/s)")
for ax in axes:
    ax.set_xlabel("clamping pressure (N/mm² = MPa)")
    ax.set_xscale("log")
    ax.set_xticks([0.25, 0.5, 1.0, 2.0], ["0.25", "0.5", "1", "2"])
    ax.minorticks_off()
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
fig.suptitle("Three beams: first bending resonance against friction and clamping pressure")
fig.tight_layout()
fig.savefig(out / "study.svg")
print(table.to_string(index=False))
