"""`python -m batstudy ...` is the `batstudy` command."""

from ._cli import main

main()
