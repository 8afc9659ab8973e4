"""Shared fixtures of the Python package's tests: where the repository and the `nullpath` program are.

The tests compare the module with the command-line program built from the same tree. The program is
`$NULLPATH_BIN` when set, else the release build in the cargo target folder (`$CARGO_TARGET_DIR`,
default `target/`); `.ci/python.sh` builds it before running pytest.
"""

import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    """The repository's root folder."""
    return REPO


@pytest.fixture(scope="session")
def nullpath_bin() -> pathlib.Path:
    """The `nullpath` program built from this tree."""
    explicit = os.environ.get("NULLPATH_BIN")
    if explicit:
        path = pathlib.Path(explicit)
    else:
        target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
        path = target / "release" / "nullpath"
    if not path.is_file():
        pytest.fail(f"the nullpath program is not built at {path}: run `cargo build --release` first")
    return path
