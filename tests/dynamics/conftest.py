from pathlib import Path

import pytest

import velplan

DATA = Path(__file__).parent / "data"
EXAMPLES = Path(velplan.__file__).parent / "examples"


@pytest.fixture
def with_dynamics(tmp_path):
    """Write a bundled example with ``text`` appended (a [dynamics] section) to a temporary
    file and return its path."""

    def make(example: str, text: str) -> Path:
        path = tmp_path / f"{example}-dyn.toml"
        path.write_text((EXAMPLES / f"{example}.toml").read_text() + "\n" + text)
        return path

    return make
