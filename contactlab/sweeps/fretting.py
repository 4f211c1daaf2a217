"""Large fretting maps on all cores or a Dask cluster: :func:`fretting_map_sweep`.

:meth:`contactlab.Contact.fretting_map` computes a map in blocks of grid points
(:data:`~contactlab.effects.fretting.MAP_BLOCK`) and of boundary root searches
(:data:`~contactlab.effects.fretting.BOUNDARY_BLOCK`) in this process. This function runs the same
blocks through :func:`~contactlab.sweeps.run.run_tasks` (serially, on a local process pool or on
a Dask cluster), so its map is the same, bit for bit. It lives here, above ``contact``, because
the layers below never import the sweep machinery.
"""
from __future__ import annotations

from typing import Any

from ..effects.fretting import FrettingMap, MapPlan, finish_map, map_block, plan_map
from .run import run_tasks

__all__ = ["fretting_map_sweep"]


class _Block:
    """One block of a planned map (pickles: the contact and the plan are plain data)."""

    def __init__(self, contact: Any, plan: MapPlan) -> None:
        self.contact = contact
        self.plan = plan

    def __call__(self, block: tuple[str, int, int]) -> Any:
        return map_block(self.contact, self.plan, block)


def fretting_map_sweep(contact: Any, *, force: Any = None, depth: Any = None,
                       displacement_amplitude: Any = None, twist_amplitude: Any = None,
                       method: str | None = None, criterion: str = "energy_ratio",
                       threshold: float | None = None, boundary: bool = True,
                       client: Any = None, workers: int | None = None,
                       progress: bool = True) -> FrettingMap:
    """:meth:`Contact.fretting_map <contactlab.Contact.fretting_map>` on all local cores or a
    Dask cluster; the same map bit for bit.

    The normal states are solved here; the map's blocks (1024 grid points, or 16 boundary root
    searches, each) run where :func:`~contactlab.sweep` would run points: ``workers=1`` in this
    process, ``workers=N`` on a local pool of N processes, ``workers=None`` on every core (or in
    this process when the whole map should take under a second), ``client=`` on a
    ``dask.distributed`` cluster. Worth it for large torsional maps (the exact torsion model
    and the boundary root search take about a millisecond per grid point and per force).

    Parameters
    ----------
    contact : Contact
    force, depth, displacement_amplitude, twist_amplitude, method, criterion, threshold, boundary
        As for :meth:`Contact.fretting_map <contactlab.Contact.fretting_map>`.
    client : dask.distributed.Client, optional
        Run the blocks on this cluster.
    workers : int, optional
        Local process pool size (without a client); 1 runs here.
    progress : bool
        A progress bar (tqdm, if installed) over the blocks when the map should take over 2 s.

    Returns
    -------
    FrettingMap
        Equal (``==``, array for array) to ``contact.fretting_map(...)`` with the same arguments.

    Raises
    ------
    ParameterError
        As :meth:`Contact.fretting_map <contactlab.Contact.fretting_map>`; bad ``workers``, or
        ``workers`` with ``client``.

    Examples
    --------
    >>> import numpy as np, contactlab
    >>> c = contactlab.Contact(contactlab.profiles.Paraboloid(R=0.01),
    ...                        materials=(contactlab.Elastic(E=210e9, nu=0.3),) * 2, friction=0.3)
    >>> kw = dict(force=[10.0, 100.0], twist_amplitude=np.geomspace(1e-4, 1e-2, 5))
    >>> contactlab.fretting_map_sweep(c, **kw, workers=1) == c.fretting_map(**kw)
    True
    """
    plan = plan_map(contact, force=force, depth=depth,
                    displacement_amplitude=displacement_amplitude,
                    twist_amplitude=twist_amplitude, method=method, criterion=criterion,
                    threshold=threshold, boundary=boundary)
    results = run_tasks(_Block(contact, plan), plan.blocks(), client=client, workers=workers,
                        progress=progress, unit="block")
    return finish_map(contact, plan, results, stacklevel=4)
