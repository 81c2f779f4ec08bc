"""The field beside the model: a simulated population of swings and a tracked one
(:func:`tracking`)."""

from __future__ import annotations

import numpy as np


def tracking(simulated, measured, ax=None):
    """A simulated population of swings beside a tracked one (``batstudy.tracking``): the
    exit speed's and the launch angle's distributions as histograms on shared bins, each
    panel titled with the Kolmogorov–Smirnov and Wasserstein distances, and exit speed
    against bat speed for both. ``simulated``: a results file's ``/summary`` as a Dataset
    (or a path); ``measured``: what ``batstudy.tracking.read`` returns (or a CSV path).
    Returns the three axes."""
    import matplotlib.pyplot as plt
    import xarray as xr

    from .. import tracking as tr

    if not isinstance(simulated, xr.Dataset):
        with xr.open_dataset(simulated, engine="h5netcdf", group="summary") as s:
            simulated = s.load()
    if not isinstance(measured, xr.Dataset):
        measured = tr.read(measured)
    c = tr.compare(simulated, measured)
    if ax is None:
        _, ax = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    mph, deg = 1 / 0.44704, 180 / np.pi
    panels = [("exit_speed", "exit_speed_lab", "exit_speed", mph, "exit speed (mph)"),
              ("launch_angle", "launch_angle", "launch_angle", deg, "launch angle (deg)")]
    for a, (name, sim_name, meas_name, scale, label) in zip(ax, panels):
        s = np.ravel(simulated[sim_name].values) * scale
        m = np.ravel(measured[meas_name].values) * scale
        s, m = s[np.isfinite(s)], m[np.isfinite(m)]
        bins = np.linspace(min(s.min(), m.min()), max(s.max(), m.max()), 31)
        a.hist(s, bins=bins, density=True, alpha=0.5, color="C0", label=f"simulated ({len(s)})")
        a.hist(m, bins=bins, density=True, alpha=0.5, color="C1", label=f"tracked ({len(m)})")
        r = c.sel(quantity=name)
        a.set_title(f"KS {float(r.ks):.2f}, Wasserstein {float(r.wasserstein) * scale:.1f}", fontsize=9)
        a.set_xlabel(label)
        a.set_ylabel("density")
        a.legend(fontsize=8)
    b = ax[2]
    b.scatter(np.ravel(simulated.bat_speed_6in.values) * mph, np.ravel(simulated.exit_speed_lab.values) * mph,
              s=6, color="C0", alpha=0.6, label="simulated")
    b.scatter(measured.bat_speed.values * mph, measured.exit_speed.values * mph, s=6, color="C1", alpha=0.6,
              label="tracked")
    b.set_xlabel("bat speed 6 in from the end (mph)")
    b.set_ylabel("exit speed (mph)")
    b.legend(fontsize=8)
    return ax
