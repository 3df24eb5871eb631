"""Campaigns from Python: a ``prs test`` or ``prs sample`` run cut into shards, run on a Dask
cluster (or here), and merged into exactly what one machine writes (docs/cluster.md).

The directories are those of ``prs campaign``: a campaign made here can be submitted to Slurm
with ``prs campaign slurm DIR``, one made by ``prs campaign init`` can be run here, and both
write the same shard files, which ``status`` and ``merge`` read. A shard is written atomically,
so a worker that dies leaves nothing half-written and running the campaign again runs only the
shards that are not done::

    from distributed import Client, LocalCluster
    import probrobscene.campaign as campaign

    if __name__ == "__main__":  # Dask's worker processes import the main module again
        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            campaign.run("examples/table_cube.prs", client, dir="camp", n=2000,
                         shard_size=100, seed=1, controller="table-cube")
        campaign.merge("camp", "results.jsonl")
"""

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _core

PathLike = Union[str, "os.PathLike[str]"]


def init(dir: PathLike, path: PathLike, n: int, *, seed: int = 0, shard_size: int = 1000,
         controller: Optional[str] = None, exec: Optional[str] = None, timeout: float = 60.0,
         persistent: bool = False, startup_timeout: float = 120.0,
         params: Optional[Mapping[str, Any]] = None, search_path: Sequence[PathLike] = (),
         max_attempts: int = 10_000, naive: bool = False, search: Optional[str] = None,
         batch: Optional[int] = None, stable: Union[bool, float, None] = None,
         stable_move: float = 0.01, stable_turn: float = 5.0,
         settle: Union[bool, float, None] = None, sampler: str = "rejection",
         estimate: bool = False, dataset: Optional[Mapping[str, Any]] = None) -> str:
    """Makes the campaign directory ``dir`` (new or empty), as ``prs campaign init``: ``n``
    episodes of ``controller`` (a built-in name) or ``exec`` (a shell command, docs/harness.md)
    in the scenario file ``path``, or ``n`` scenes without either, in shards of ``shard_size``.
    ``persistent=True`` starts ``exec`` once per worker thread of a shard rather than once per
    episode (``--persistent``, with ``startup_timeout`` seconds for its handshake).
    With ``search`` ("ce", "anneal" or "random") the episodes are a failure search of budget
    ``n`` in generations of ``batch`` (default as ``prs search``), run generation after
    generation (docs/search.md). With ``estimate=True`` they are ``prs estimate``'s run of
    budget ``n`` (at least 200), also in generations, and :func:`merge` gives its records with
    their weights and the estimate. ``stable`` and ``settle`` as for :func:`probrobscene.load`
    (``--stable``, ``--settle``): every shard keeps only scenes at rest, or settles them;
    ``sampler="gibbs"`` draws the scenes from Gibbs chains (``--sampler gibbs``) and
    ``sampler="partial-rejection"`` by partial rejection sampling, the same scenes for any
    shard layout. With ``dataset`` (a dict of :func:`probrobscene.dataset`'s ``cameras``,
    ``size``, ``format`` and ``labels``, ``{}`` for the defaults) each shard is ``prs dataset``'s
    labelled pictures of its scenes, and :func:`merge` joins them into one dataset
    (docs/dataset.md). Returns the campaign id. Raises ScenarioError for a
    scenario that does not compile and ValueError for a directory that is in use or an unknown
    controller or strategy."""
    from . import _load_options  # the package's own conversion of params and options
    if n < 1 or shard_size < 1:
        raise ValueError(f"n and shard_size must be >= 1, got {n} and {shard_size}")
    options = _load_options(params, search_path, max_attempts, naive, stable, stable_move,
                            stable_turn, settle, sampler)
    if search is not None and search not in ("ce", "anneal", "random"):
        raise ValueError(f"unknown search strategy {search!r} (strategies: ce, anneal, random)")
    if batch is not None and (search is None or batch < 1):
        raise ValueError("batch is a search's generation size (>= 1): give search= too")
    if estimate and sampler != "rejection":
        raise ValueError("an estimate's weights need the rejection sampler: leave out sampler=")
    picture = None
    if dataset is not None:
        unknown = set(dataset) - {"cameras", "size", "format", "labels", "jpeg"}
        if unknown:
            raise ValueError(f"dataset: unknown options {sorted(unknown)} (cameras, size, format, "
                             f"labels, jpeg)")
        fmt = dataset.get("format", "both")
        if fmt not in ("bop", "coco", "both"):
            raise ValueError(f"dataset: format must be 'bop', 'coco' or 'both', not {fmt!r}")
        size = dataset.get("size")
        width, height = (0, 0) if size is None else (int(size[0]), int(size[1]))
        if size is not None and (width < 16 or height < 16 or width > 8192 or height > 8192):
            raise ValueError("dataset: size must be from 16 to 8192 pixels each way")
        picture = {"cameras": list(dataset.get("cameras") or []), "width": width,
                   "height": height, "bop": fmt != "coco", "coco": fmt != "bop",
                   "labels": list(dataset.get("labels") or []),
                   "jpeg": bool(dataset.get("jpeg", False))}
    return _core.campaign_init(os.fspath(dir), os.fspath(path), options, n, shard_size, seed,
                               controller or "", exec or "", float(timeout), bool(persistent),
                               float(startup_timeout), search or "",
                               batch or 0, bool(estimate), picture)


def run_shard(dir: PathLike, shard: int, threads: int = 1) -> int:
    """Runs shard ``shard`` of the campaign in ``dir`` on ``threads`` threads and writes it
    atomically, as ``prs campaign run-shard``; returns ``shard``. Safe to run again."""
    _core.campaign_run_shard(os.fspath(dir), shard, threads)
    return shard


def status(dir: PathLike) -> Dict[str, Any]:
    """Where the campaign stands, as ``prs campaign status`` prints it: ``"counts"`` of done,
    queued, running, failed, missing, bad and waiting (a search's later generations) shards;
    ``"shards"``, one dict per shard (shard, state, why); ``"to_run"``, the shards that can run
    now and are neither done nor queued or running on Slurm; ``"queue"``, None or why squeue
    could not be asked."""
    return _core.campaign_status(os.fspath(dir))


def merge(dir: PathLike, output: PathLike, partial: bool = False) -> Dict[str, Any]:
    """Writes every shard's lines in index order to ``output`` (atomically), as ``prs campaign
    merge``: ``{"lines": N, "skipped": [...]}``. Raises ValueError naming the shards that are
    not done, unless ``partial``. An estimate campaign's records are written as ``prs estimate
    -o`` writes them (with their weights), the dict has ``"estimate"`` (as
    :func:`probrobscene.estimate` returns it, without the records), and ``partial`` is refused.
    A dataset campaign's shards are joined into the dataset ``output`` (``"dataset"`` in the
    dict), the files one ``prs dataset`` run writes; ``partial`` is refused."""
    return _core.campaign_merge(os.fspath(dir), os.fspath(output), partial)


def _is_campaign(path: PathLike) -> bool:
    return os.path.isfile(os.path.join(os.fspath(path), "campaign.json"))


def run(dir_or_spec: PathLike, client=None, *, dir: Optional[PathLike] = None,
        n: Optional[int] = None, threads_per_shard: int = 1, retries: int = 2,
        **init_options) -> Dict[str, Any]:
    """Runs every shard of a campaign that is not done and returns its :func:`status`.

    ``dir_or_spec`` is a campaign directory, or a scenario file: then ``dir`` and ``n`` (and
    any :func:`init` option: seed, shard_size, controller, exec, ...) make the campaign first.
    With a ``dask.distributed`` ``client`` each shard is one task (``retries`` times again if
    its worker dies), run on ``threads_per_shard`` threads; the workers must see ``dir`` (a
    shared file system, or a LocalCluster). Without one the shards run here, on every CPU.
    A search or estimate campaign runs generation after generation, each planned from the
    records of the one before. Shards Slurm has queued or is running are left to it. Raises the first shard's
    error."""
    if _is_campaign(dir_or_spec):
        if dir is not None or n is not None or init_options:
            raise ValueError(f"{os.fspath(dir_or_spec)} is a campaign already: its options are "
                             "in its campaign.json (give only the directory)")
        where = os.fspath(dir_or_spec)
    else:
        if dir is None or n is None:
            raise ValueError(f"{os.fspath(dir_or_spec)} is not a campaign directory: to make one "
                             "from a scenario file, give dir= and n=")
        init(dir, dir_or_spec, n, **init_options)
        where = os.fspath(dir)
    where = os.path.abspath(where)
    while True:
        _core.campaign_plan(where)  # the next generation, once the one before is done
        current = status(where)
        shards = current["to_run"]
        if not shards:
            return current
        if client is None:
            for shard in shards:
                run_shard(where, shard, os.cpu_count() or 1)
        else:
            _map_shards(client, where, current["campaign"], shards, threads_per_shard, retries)


def _map_shards(client, where: str, campaign_id: str, shards: List[int], threads: int,
                retries: int) -> None:
    from distributed import as_completed
    futures = client.map(_run_shard_task, [where] * len(shards), shards,
                         [threads] * len(shards),
                         key=[f"prs-{campaign_id}-shard-{k}" for k in shards],
                         pure=False, retries=retries)
    try:
        for future in as_completed(futures):
            future.result()  # raises the shard's error here
    finally:
        client.cancel(futures)


def _run_shard_task(dir: str, shard: int, threads: int) -> int:
    # What a Dask worker runs: by reference (probrobscene.campaign._run_shard_task), so each
    # worker imports the package itself.
    return run_shard(dir, shard, threads)


__all__: List[str] = ["init", "run", "run_shard", "status", "merge"]
