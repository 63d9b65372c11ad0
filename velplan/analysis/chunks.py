"""A long run of crank angles solved a piece at a time, for output written as it is computed
(bounded memory however many angles there are)."""

from __future__ import annotations

from typing import Iterator

import numpy as np

from velplan.analysis.solver import Kinematics, solve
from velplan.mechanism.model import Mechanism


def chunked_kinematics(mech: Mechanism, phi: np.ndarray, *, omega1=None, epsilon1=None, engine: str = "auto",
                       chunk: int = 16384) -> Iterator[tuple[int, Kinematics]]:
    """(first index, solution) of ``phi`` (rad) ``chunk`` angles at a time; ``omega1``,
    ``epsilon1`` (rad/s, rad/s²) one value or one per angle, as in `solve`. Each angle's
    values are those of one `solve` over all of ``phi``."""
    for a in range(0, len(phi), chunk):
        pick = lambda x: x[a:a + chunk] if isinstance(x, np.ndarray) else x  # noqa: E731
        yield a, solve(mech, phi[a:a + chunk], omega1=pick(omega1), epsilon1=pick(epsilon1), engine=engine)
