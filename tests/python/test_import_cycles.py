"""No import circles: in every crate of the workspace, no file imports one that imports it back,
directly or through others (scripts/import_cycles.py), so that each module has one place in the
data flow (docs/architecture.md)."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CRATES = ["crates/physics/src", "crates/store/src", "src", "python/src"]


def test_no_crate_has_an_import_circle():
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "import_cycles.py"), *(str(ROOT / c) for c in CRATES)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_the_check_finds_a_circle(tmp_path):
    # a crate whose two files import each other, through a brace group and through `super`
    (tmp_path / "a").mkdir()
    (tmp_path / "lib.rs").write_text("pub mod a;\n")
    (tmp_path / "a" / "mod.rs").write_text("pub mod b;\npub mod c;\n")
    (tmp_path / "a" / "b.rs").write_text("use super::{c::C, d};\npub struct B;\n")
    (tmp_path / "a" / "c.rs").write_text("use crate::a::b::B; // a comment naming crate::x\npub struct C;\n")
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "import_cycles.py"), str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 1 and "a::b ↔ a::c" in r.stdout, r.stdout
