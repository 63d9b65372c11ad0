"""A sweep's chunks on a Dask cluster (``pip install velplan[dask]``).

Each chunk of variants is one task, ``chunk_figures(mech, values, positions, engine, delta)``, the very
function a local sweep runs, so a cluster gives the same figures bit for bit. It pays when a
sweep takes minutes on one machine (10⁶ variants and more, or fine grids of angles): a task
of 256 variants × 360 angles is about 0.1 s of work, and the scheduler adds a few ms per
task and the network the chunk's values and figures (a few kB).
"""

from __future__ import annotations

from typing import Iterator

from velplan.errors import VelplanError


def map_chunks(scheduler, task, mech, parts: list[dict], positions: int, progress=None,
               engine: str = "numpy", delta: float | None = None) -> Iterator:
    """Run ``task(mech, part, positions, engine, delta)`` (the sweep's ``chunk_figures``) on every part
    on ``scheduler`` (a ``dask.distributed.Client`` or a scheduler address such as
    ``tcp://10.0.0.5:8786``); the results in order, each as soon as it and those before it are done."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError:
        raise VelplanError("--scheduler needs dask.distributed (pip install 'velplan[dask]')") from None
    own = not isinstance(scheduler, Client)
    if own:
        try:
            client = Client(str(scheduler), timeout="10s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise VelplanError(f"--scheduler: cannot reach the Dask scheduler at {scheduler}: {exc}") from None
    else:
        client = scheduler
    try:
        shared = client.scatter(mech, broadcast=True)
        n = len(parts)
        futures = client.map(task, [shared] * n, parts, [positions] * n, [engine] * n, [delta] * n, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results: dict = {}
        given = 0
        for done, fut in enumerate(as_completed(futures), start=1):
            results[index[fut.key]] = fut.result()
            if progress:
                progress(done, len(parts), "chunks of variants")
            while given in results:  # in order: each chunk once it and those before it are done
                yield results.pop(given)
                given += 1
    finally:
        if own:
            client.close()
