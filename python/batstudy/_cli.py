"""The `batstudy` command of the wheel: the Rust binary's command line (the native module's
`cli_main`), and two commands of the Python package, `figures` and `report`."""

import os
import sys

# name -> (arguments, what it does) of the commands the Python package answers itself
PYTHON_COMMANDS = {
    "figures": ("RESULTS [-o DIR]", "Draw every figure a results file has data for (batstudy.plot)"),
    "report": ("RESULTS [-o FILE]", "Write a results file's explorer, one HTML file (batstudy.report)"),
}
HELP_REQUESTS = (["-h"], ["--help"], ["help"], [])


def python_help() -> str:
    """The lines `batstudy --help` adds for the Python package's commands."""
    lines = ["Commands of the Python package (matplotlib, plotly: pip install 'batstudy[plot]'):"]
    lines += [f"  {name:9} {usage}: {what}" for name, (usage, what) in PYTHON_COMMANDS.items()]
    return "\n".join(lines)


def run_python_command(name: str, argv: list) -> int:
    if name == "figures":
        from .plot import main
    else:
        from ._report import main
    return main(argv, prog=f"batstudy {name}")


def invocation() -> list:
    """The words that start this command again on another node (the Slurm scripts use
    them): the installed `batstudy` script itself, or `python -m batstudy` (never the
    interpreter alone, which is what the native module sees as its executable)."""
    script = os.path.abspath(sys.argv[0])
    if os.path.basename(script) != "__main__.py" and os.access(script, os.X_OK):
        return [script]
    return [sys.executable, "-m", "batstudy"]


def main() -> None:
    args = sys.argv[1:]
    if args[:1] == ["help"] and args[1:2] and args[1] in PYTHON_COMMANDS:
        args = [args[1], "--help"]
    if args[:1] and args[0] in PYTHON_COMMANDS:
        sys.exit(run_python_command(args[0], args[1:]))
    from . import _native

    code = _native.cli_main(["batstudy", *args], invocation())
    if args in HELP_REQUESTS:  # without arguments the help goes to stderr (exit status 2)
        print(f"\n{python_help()}", file=sys.stdout if args else sys.stderr)
    sys.exit(code)


if __name__ == "__main__":
    main()
