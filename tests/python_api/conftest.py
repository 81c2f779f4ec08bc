"""The API tests run against the *installed* package (the wheel in a clean venv in CI:
scripts/test_wheel.sh), never against the sources."""

import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def small_study(tmp_path_factory) -> pathlib.Path:
    """A small study: 4 cases (wood, aluminum, aluminum with a hoop, denser wood) × 2 swings
    × 9 impact positions, histories at 0.58 m on the still bat."""
    d = tmp_path_factory.mktemp("study")
    p = d / "small.yaml"
    p.write_text(
        """name: small
model: wave
base:
  bat: {preset: r161}
  ball: {speed: 40}
grid:
  swing.omega: [0, -40]
  impact.z: {range: [0.50, 0.84, 0.04]}
points:
  name: case
  sets:
    - {}
    - {bat.preset: aluminum}
    - {bat.preset: aluminum, hoop.frequency: 1500, hoop.mass: 0.03}
    - {bat.material.density: 700}
history:
  fields: [force, compression, displacement]
  interval: 2.0e-5
  duration: 2.0e-3
  z_step: 0.02
  only: {impact.z: [0.58], swing.omega: [0]}
"""
    )
    return p
