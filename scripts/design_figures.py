"""The uncertainty and design figures in docs/figures/ from the bundled studies' results files:
    .venv/bin/python scripts/design_figures.py UNCERTAINTY.h5 DESIGN_BBCOR.h5 DESIGN_WOOD.h5
(`batstudy run studies/uncertainty.yaml`, `batstudy optimize studies/design_*.yaml`)."""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from batstudy import plot  # noqa: E402

unc, bbcor, wood = sys.argv[1:4]
out = ROOT / "docs" / "figures"
ax = plot.uncertainty(unc)
ax[0].figure.savefig(out / "uncertainty.png", dpi=110)
fig, axes = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
plot.search(bbcor, ax=axes[0])
axes[0].set_title("design_bbcor: aluminum under the BBCOR rules", fontsize=9)
plot.search(wood, ax=axes[1])
axes[1].set_title("design_wood: wood within MLB rules, at 31 oz", fontsize=9)
fig.savefig(out / "design_search.png", dpi=110)
