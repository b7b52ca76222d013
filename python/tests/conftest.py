"""Fixtures of the Python suite: the `swm` command line (to compare bytes
with), the shared corpus and the generated corpus.

tests/python.rs (run by `cargo test`) sets SWM_BIN, SWM_SHARED_CORPUS and
SWM_GENERATED_CORPUS. Run by hand, the suite takes the newer of
../target/{debug,release}/swm as the CLI and the shared corpus at
../../shared/corpus, and skips what it cannot find, saying so.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import List, Optional

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _existing(*candidates: Optional[str]) -> Optional[Path]:
    for c in candidates:
        if c and Path(c).exists():
            return Path(c)
    return None


@pytest.fixture(scope="session")
def swm_bin() -> Path:
    # Without SWM_BIN, the newer of the two builds: an old debug build
    # beside a fresh release one would compare with yesterday's encoder.
    builds = [p for p in (ROOT / "target" / "debug" / "swm", ROOT / "target" / "release" / "swm") if p.exists()]
    builds.sort(key=lambda p: p.stat().st_mtime, reverse=True)
    found = _existing(os.environ.get("SWM_BIN"), *map(str, builds))
    if found is None:
        pytest.skip("the swm CLI not found (cargo build -p swm-cli, or set SWM_BIN)")
    return found


@pytest.fixture(scope="session")
def shared_corpus() -> Path:
    found = _existing(os.environ.get("SWM_SHARED_CORPUS"), str(ROOT.parent / "shared" / "corpus"))
    if found is None or not (found / "README.md").is_file():
        pytest.skip("../shared/corpus not found")
    return found


@pytest.fixture(scope="session")
def generated_corpus() -> Path:
    found = _existing(os.environ.get("SWM_GENERATED_CORPUS"))
    if found is None:
        pytest.skip(
            "generated corpus not found (cargo run --release -p swm-corpus -- --out DIR, "
            "then set SWM_GENERATED_CORPUS=DIR)"
        )
    return found


def run_cli(swm_bin: Path, *args: object) -> subprocess.CompletedProcess:
    """Runs the CLI; fails the test with its stderr if it fails."""
    out = subprocess.run([str(swm_bin), *map(str, args)], capture_output=True)
    assert out.returncode == 0, out.stderr.decode()
    return out


def cli_error(swm_bin: Path, *args: object) -> str:
    """The message of a failing CLI run, without `swm: error: FILE: `."""
    out = subprocess.run([str(swm_bin), *map(str, args)], capture_output=True)
    assert out.returncode == 1, out
    line = out.stderr.decode().strip()
    prefix = "swm: error: "
    assert line.startswith(prefix), line
    # `FILE: message`; the file name is the first argument that fails.
    return line[len(prefix):].split(": ", 1)[1]


def mesh_files(folder: Path) -> List[Path]:
    return sorted(p for p in folder.iterdir() if p.suffix in (".obj", ".ply", ".off", ".stl"))
