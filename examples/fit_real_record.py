#!/usr/bin/python3
"""Fit the committed real record (a steel cantilever's free decay, ARTS-Lab, CC BY-SA 4.0) from Python, and plot its
spectrum with the fitted model's modes.

    PYTHONPATH=build/python /usr/bin/python3 examples/fit_real_record.py [spectrum.png]

The fit is the README's modal-cost fit of the same record (beamid fit ... --cost modal): EI, the Kelvin-Voigt and the
air damping of the bending model, started from the nominal beam file.
"""
import os
import sys

import matplotlib
import numpy as np

import beamid

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)

here = os.path.dirname(os.path.abspath(__file__))
record = os.path.join(here, "..", "studies", "data", "arts-steel-cantilever")
lvm = os.path.join(record, "timeseries_data.lvm")
output = sys.argv[1] if len(sys.argv) > 1 else "spectrum.png"

# The record as beamid reads it: 0.1 s after the impact, 8 s, converted from g to m/s^2.
data = beamid.read_record(lvm, start=1.2, duration=8)
result = beamid.fit(data=lvm, start=1.2, duration=8, beam=os.path.join(record, "steel_cantilever.toml"),
                    elements=16, estimate=["EI", "cDI", "gamma"], bounds="EI=50:200,cDI=1e-5:1e-2,gamma=0.001:5",
                    excitation="free-decay", cost="modal", spike_frequencies=[6.62, 41.38, 116.9, 229.8, 380.5])
print(result)
for row in result.parameters:
    print(f"{row['parameter']:6s} {row['estimate']:.6g} +- {row['standard_error']:.2g} (sandwich "
          f"{row['robust_standard_error']:.2g})")

y = data.values - np.mean(data.values)
spectrum = np.abs(np.fft.rfft(y))
frequency_hz = np.fft.rfftfreq(len(y), data.dt_s)
figure, axes = plt.subplots(figsize=(7, 3.5))
axes.semilogy(frequency_hz, spectrum, lw=0.7, label="record (|DFT|)")
for k, mode in enumerate(result.modes):
    axes.axvline(mode["model_hz"], color="C1", lw=0.8, ls="--", label="fitted model's modes" if k == 0 else None)
axes.set_xlim(0, 450)
axes.set_ylim(bottom=np.percentile(spectrum[1:], 1) / 2)  # not down to the bin the mean's removal emptied
axes.set_xlabel("frequency (Hz)")
axes.set_ylabel("|Z| (m/s^2)")
axes.set_title(f"steel cantilever, modal-cost fit: EI = {result.estimates['EI']:.4g} N m^2")
axes.legend()
figure.tight_layout()
figure.savefig(output, dpi=120)
print(f"spectrum: {output}")
