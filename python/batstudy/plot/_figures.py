"""Every figure a results file has data for, written to a folder: :func:`figures`, and the
command ``batstudy figures`` (:func:`main`)."""

from __future__ import annotations

import argparse
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Union

from ._curves import Results, Skip
from ._paper import FIGURES, OTHER_FIGURES

ALL_FIGURES = {**FIGURES, **OTHER_FIGURES}


def file_name(name: str, fmt: str = "png") -> str:
    return name + (".gif" if name.startswith("anim") else f".{fmt}")


def short(name: str) -> str:
    """``fig06_exit_speed_vs_omega`` -> ``fig6``; other names unchanged (``anim``, ``bat``...)."""
    m = re.match(r"fig0*(\d+[a-z]?)", name)
    return "fig" + m.group(1) if m else name.split("_")[0]


def wanted(only: Optional[str]) -> list[str]:
    """Figure names selected by `only` (short or full names, comma separated; None: all)."""
    if not only:
        return list(ALL_FIGURES)
    tokens = {t.strip() for t in only.split(",") if t.strip()}
    names = [n for n in ALL_FIGURES if n in tokens or short(n) in {short(t) for t in tokens}]
    unknown = {t for t in tokens if not any(t == n or short(t) == short(n) for n in ALL_FIGURES)}
    if unknown:
        raise ValueError(f"unknown figure(s): {', '.join(sorted(unknown))}; known: {', '.join(ALL_FIGURES)}")
    return names


@dataclass
class Outcome:
    """What became of one figure: written to `path`, skipped or failed (`message` says)."""

    name: str
    path: Optional[Path]
    message: str
    failed: bool = False


def draw(results: str, names: list[str], outdir: Path, fmt: str) -> list[Outcome]:
    """Draw `names` from one results file into `outdir`."""
    out = []
    with Results(results) as res:
        for name in names:
            path = outdir / file_name(name, fmt)
            try:
                ALL_FIGURES[name](res, path)
                out.append(Outcome(name, path, f"wrote {path}"))
            except Skip as why:
                out.append(Outcome(name, None, f"skip  {name}: {why}"))
            except Exception as err:  # one broken figure must not stop the others
                out.append(Outcome(name, None, f"FAIL  {name}: {type(err).__name__}: {err}", failed=True))
    return out


def draw_all(results, outdir, only=None, jobs=1, fmt="png") -> list[Outcome]:
    """:func:`draw` of the figures `only` names, on `jobs` processes."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    names, results = wanted(only), os.fspath(results)
    if jobs <= 1 or len(names) <= 1:
        return draw(results, names, outdir, fmt)
    from concurrent.futures import ProcessPoolExecutor

    # Round-robin shares: the costly figures (the animation, Fig. 14) land on different workers.
    shares = [names[k::jobs] for k in range(jobs)]
    with ProcessPoolExecutor(jobs) as pool:
        done = pool.map(draw, [results] * jobs, shares, [outdir] * jobs, [fmt] * jobs)
        return [outcome for share in done for outcome in share]


def figures(
    results: Union[str, os.PathLike],
    outdir: Union[str, os.PathLike] = "figures",
    only: Optional[str] = None,
    jobs: int = 1,
    format: str = "png",
) -> list[Path]:
    """Draw every figure of the paper (and the others of ``FIGURES``) that the results file
    has data for into `outdir`; return the files written. `only` selects figures by name
    (``"fig6,fig14,bat_profiles"``), `jobs` draws on that many processes, `format` is
    ``png`` (110 dpi), ``svg`` or ``pdf`` (the animation is always a GIF). A figure whose data
    the file lacks is skipped; one that fails raises RuntimeError once the others are drawn.
    """
    outcomes = draw_all(results, outdir, only, jobs, format)
    failed = [o.message for o in outcomes if o.failed]
    if failed:
        raise RuntimeError("\n".join(failed))
    return [o.path for o in outcomes if o.path is not None]


def main(argv=None, prog: str = "batstudy figures") -> int:
    """The command: one line per figure (written, skipped, FAIL); exit status 1 if one
    failed, 2 for a bad argument or a file that cannot be read."""
    what = ("Draw every figure a results file has data for: the paper's Figs. 2, 4-8, 10-15, bat profiles, "
            "sweet-spot definitions, an animation.")  # fmt: skip
    ap = argparse.ArgumentParser(prog=prog, description=what)
    ap.add_argument("results", help="batstudy results file (HDF5)")
    ap.add_argument("-o", "--outdir", default="figures", help="output directory (default: figures)")
    ap.add_argument("--only", help="comma-separated figures, e.g. fig6,fig14,anim,bat_profiles")
    ap.add_argument("-j", "--jobs", type=int, default=1, help="processes drawing in parallel (default 1)")
    ap.add_argument("--format", choices=["png", "svg", "pdf"], default="png",
                    help="figure format (png at 110 dpi; svg and pdf are vector, for print)")  # fmt: skip
    args = ap.parse_args(argv)
    try:
        outcomes = draw_all(args.results, args.outdir, args.only, args.jobs, args.format)
    except (OSError, ValueError) as err:
        print(f"{prog}: {err}", file=sys.stderr)
        return 2
    for o in outcomes:
        print(o.message, file=sys.stderr if o.failed else sys.stdout)
    return 1 if any(o.failed for o in outcomes) else 0
