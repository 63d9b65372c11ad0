"""``velplan convert``: a mechanism between the explicit file (groups), the drawn file
(joints) and a pyslvs/PMKS expression (``.pmks``)."""

from __future__ import annotations

import math
from pathlib import Path

from velplan.errors import VelplanError

FORMS = ("explicit", "drawn", "pmks")


def register(sub) -> None:
    """``velplan convert``: its arguments."""
    p = sub.add_parser("convert", help="convert a mechanism between the explicit TOML (groups), the drawn TOML "
                                       "(joints) and a pyslvs/PMKS expression (.pmks)")
    p.add_argument("mechanism", metavar="IN", help="bundled example name, TOML file (explicit or drawn) or .pmks file")
    p.add_argument("-o", "--output", metavar="OUT", help="OUT.toml or OUT.pmks (default: standard output)")
    p.add_argument("--form", choices=FORMS,
                   help="what to write: explicit (groups), drawn (joints) or pmks; default: pmks for OUT.pmks, "
                        "else drawn for an explicit input and explicit for a drawn or .pmks one")
    add_pmks_options(p)
    p.add_argument("--pose", metavar="DEG", type=float,
                   help="crank angle of the drawn pose written (default: the angle of 72 where every group is "
                        "best conditioned)")
    p.set_defaults(run=run_convert)


def add_pmks_options(p) -> None:
    """How a .pmks input is read: the input pair, the unit, the crank's speed, the joint names."""
    p.add_argument("--input", metavar="B,D",
                   help=".pmks: the input pair as pyslvs numbers joints: the crank is the link shared by joints "
                        "B and D and turns about B (default: the first frame joint's single moving link)")
    p.add_argument("--unit", choices=("mm", "m"), default="mm", help=".pmks coordinates in mm (default) or m")
    speed = p.add_mutually_exclusive_group()
    speed.add_argument("--omega", metavar="RAD/S", type=float, help=".pmks: the crank's speed, rad/s (default 1)")
    speed.add_argument("--rpm", metavar="REV/MIN", type=float, help=".pmks: the crank's speed, rev/min")
    p.add_argument("--names", metavar="N,…", help=".pmks: the joints' names in order (default P0, P1, …)")


def pmks_options(args) -> dict:
    """The keyword options of `velplan.mechanism.loader.load_pmks` from the arguments."""
    out: dict = {"unit": args.unit}
    if args.input is not None:
        parts = [x.strip() for x in args.input.split(",")]
        if len(parts) != 2 or not all(x.isdigit() for x in parts):
            raise VelplanError(f"--input must be two joint numbers B,D (e.g. 0,1), not {args.input!r}")
        if parts[0] == parts[1]:
            raise VelplanError(f"--input {args.input}: B and D must be two different joints")
        out["pair"] = (int(parts[0]), int(parts[1]))
    for key in ("omega", "rpm"):
        value = getattr(args, key)
        if value is not None:
            if not math.isfinite(value) or abs(value) > 1e9:
                raise VelplanError(f"--{key} must be a finite speed, not {value:g}")
            out[key] = value
    if args.names is not None:
        out["names"] = [x.strip() for x in args.names.split(",")]
        if not all(out["names"]):
            raise VelplanError(f"--names: an empty name in {args.names!r}")
    return out


def read(args):
    """The mechanism of ``args.mechanism`` (a .pmks file read with the options), its form, and
    for a drawn or .pmks input its drawn tables as given (their joints' colours kept)."""
    from velplan.mechanism.loader import load

    source = str(args.mechanism)
    if source.lower().endswith(".pmks"):
        from velplan.mechanism.loader import read_pmks

        mech, data = read_pmks(source, **pmks_options(args))
        return mech, "pmks", data
    path = Path(source)
    if path.suffix.lower() == ".toml" and path.is_file():
        import tomllib

        try:
            data = tomllib.loads(path.read_text("utf-8"))
        except (tomllib.TOMLDecodeError, OSError, UnicodeDecodeError):
            data = {}  # load says what is wrong
        if "joint" in data:
            return load(source), "drawn", data
    return load(source), "explicit", None


def pose(mech, deg: float | None = None):
    """Positions (m, complex) and link angles (rad) at the drawn pose (`velplan.analysis.pose`)."""
    from velplan.analysis.pose import pose as at_pose

    if deg is not None and not math.isfinite(deg):
        raise VelplanError(f"--pose must be a finite angle in degrees, not {deg}")
    return at_pose(mech, deg)


def convert_text(mech, form: str, *, unit: str = "mm", pose_deg: float | None = None,
                 drawn: dict | None = None) -> str:
    """``mech`` written in ``form``; ``drawn``: its drawn tables as read, written as they are
    (colours kept) unless another pose is asked for."""
    from velplan.mechanism import pmks
    from velplan.mechanism.drawn_write import drawn_tables
    from velplan.mechanism.tables import dumps, explicit_tables

    if form == "explicit":
        return dumps(explicit_tables(mech))
    tables = drawn if drawn is not None and pose_deg is None else drawn_tables(mech, *pose(mech, pose_deg))
    if form == "drawn":
        return dumps(tables)
    joints = list(tables["joint"])
    blocks = {j["block"] for j in joints if j.get("block")}
    joints += [{"name": p["name"], "at": p["at"], "links": [p["link"]]} for p in tables.get("point", ())
               if p["link"] not in blocks]
    return pmks.dumps(joints, unit=unit)


def run_convert(args) -> int:
    """Write the mechanism in the form asked (by --form, else by the output's suffix), or print it."""
    from velplan.cli.common import emit

    mech, form_in, drawn = read(args)
    out = args.output
    form = args.form
    if form is None:
        if out and out.lower().endswith(".pmks"):
            form = "pmks"
        else:
            form = "drawn" if form_in == "explicit" else "explicit"
    if out and form == "pmks" and not out.lower().endswith(".pmks"):
        raise VelplanError(f"-o {out}: a PMKS expression is written to a .pmks file")
    if out and form != "pmks" and not out.lower().endswith(".toml"):
        raise VelplanError(f"-o {out}: a {form} mechanism file is a .toml file")
    emit(convert_text(mech, form, unit=args.unit, pose_deg=args.pose, drawn=drawn), out)
    return 0
