"""Mechanisms for the force tests that are not bundled examples."""

from importlib import resources

import velplan

YOKE_EXTRA = """
[[group]]
kind = "PRP"
name = "4-5"
links = ["4", "5"]
point = "C"
guides = [{ link = "3", through = "D", angle_deg = 0.0 }, { link = "0", through = "O", angle_deg = 0.0, offset = 0.1 }]

[link.2]
mass = 4.0
centre = "S2"

[link.3]
mass = 3.0
inertia = 0.02
centre = "S3"

[link.4]
mass = 1.5
inertia = 0.004
centre = "C"

[link.5]
mass = 5.0
centre = "C"

[[load]]
kind = "force"
name = "Q"
point = "C"
link = "5"
fx = -300.0

[[load]]
kind = "moment"
name = "M3"
link = "3"
moment = 15.0
"""


def example_text(name: str) -> str:
    return resources.files("velplan.examples").joinpath(f"{name}.toml").read_text("utf-8")


def four_bar_with_prp():
    """The bundled four-bar plus a PRP group: a block 4 sliding along the rocker 3 and a
    slider 5 on the frame line y = 0.1 m, joined at C; masses, a force and a moment."""
    return velplan.parse(example_text("four-bar") + YOKE_EXTRA, name="four-bar-prp")


def with_loads(name: str, extra: str):
    """A bundled example with extra TOML appended (loads, masses)."""
    return velplan.parse(example_text(name) + "\n" + extra, name=name)
