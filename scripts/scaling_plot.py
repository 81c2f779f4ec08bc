"""Points/s against threads from a `batstudy bench --json` file (its `scaling` section).

    python scripts/scaling_plot.py docs/performance.json -o docs/figures/scaling.png
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("bench_json")
    ap.add_argument("-o", "--output", default="scaling.png")
    args = ap.parse_args(argv)
    b = json.load(open(args.bench_json))
    sc, wh = b["scaling"], b["writer_headroom"]
    t = [p["threads"] for p in sc["points"]]
    fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
    series = [("summary_points_per_second", f"summary only ({sc['summary_points']} points)"),
              ("history_points_per_second", f"full histories, displacement on the grid "
                                            f"({sc['history_points']} points)")]
    if "history_modal_points_per_second" in sc["points"][0]:
        series.append(("history_modal_points_per_second", "full histories, displacement in modal form"))
    colors = ["tab:blue", "tab:orange", "tab:olive"]
    for (key, label), color in zip(series, colors):
        rates = [p[key] for p in sc["points"]]
        ax.plot(t, rates, "o-", label=label, color=color)
        ax.plot(t, [rates[0] * n for n in t], ":", color=ax.lines[-1].get_color(), lw=1)
    if "history_uncompressed_points_per_second" in sc:
        ax.plot([t[-1]], [sc["history_uncompressed_points_per_second"]], "s", color="tab:green",
                label=f"full histories, `compression: none`: "
                      f"{sc['history_uncompressed_points_per_second']:.0f} points/s")
    if "history_scalar_points_per_second" in sc:
        ax.plot([t[-1]], [sc["history_scalar_points_per_second"]], "D", color="tab:purple",
                label=f"scalar histories only (no displacement): "
                      f"{sc['history_scalar_points_per_second']:.0f} points/s")
    if "history_compute_points_per_second" in sc:
        ax.plot([t[-1]], [sc["history_compute_points_per_second"]], "^", color="gray",
                label=f"full histories computed, not stored: "
                      f"{sc['history_compute_points_per_second']:.0f} points/s")
    if "history_modal_compute_points_per_second" in sc:
        ax.plot([t[-1]], [sc["history_modal_compute_points_per_second"]], "v", color="tab:olive",
                label=f"the same in modal form, computed, not stored: "
                      f"{sc['history_modal_compute_points_per_second']:.0f} points/s")
    ax.axhline(wh["writer_points_per_second"], color="firebrick", ls="--", lw=1,
               label=f"the writer alone, finish included (history study): "
                     f"{wh['writer_points_per_second']:.0f} points/s")
    if "modal_writer_points_per_second" in wh:
        ax.axhline(wh["modal_writer_points_per_second"], color="darkorange", ls="--", lw=1,
                   label=f"the same, modal form: {wh['modal_writer_points_per_second']:.0f} points/s")
    if "append_points_per_second" in wh:
        ax.axhline(wh["append_points_per_second"], color="firebrick", ls=":", lw=1,
                   label=f"the writer while the run computes: "
                         f"{wh['append_points_per_second']:.0f} points/s")
    ax.set_xlabel("threads")
    ax.set_ylabel("points/s (driver + store)")
    ax.set_xticks(t)
    ax.set_yscale("log")
    ax.grid(alpha=0.3, which="both")
    m = b["machine"]
    ax.set_title(f"Scaling on {m.get('nproc', '?')} cores ({m.get('cpu_model', '')}); dotted: linear", fontsize=9)
    ax.legend(fontsize=8)
    fig.savefig(args.output, dpi=110)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
