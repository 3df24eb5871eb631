"""A table-cube test (or estimate) campaign on a Dask LocalCluster of 2 worker processes (1 thread each), timed:
the Dask part of bench/campaign_cluster.sh (docs/benchmarks.md). A file, not a here-document:
Dask's worker processes start by re-importing the main module, which needs a path.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/campaign_dask.py DIR SCENARIO N SHARD [estimate]
"""

import sys
import time


def main() -> None:
    from distributed import Client, LocalCluster
    import probrobscene.campaign as campaign

    work, example, n, shard = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    estimate = sys.argv[5:] == ["estimate"]
    name = "dask_estimate" if estimate else "dask"
    start = time.time()
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        ready = time.time()
        campaign.run(example, client, dir=f"{work}/{name}", n=n, shard_size=shard, seed=1,
                     controller="table-cube", estimate=estimate)
    done = time.time()
    campaign.merge(f"{work}/{name}", f"{work}/{name}.jsonl")
    print(f"Dask LocalCluster, 2 workers of 1 thread{', estimate' if estimate else ''}: "
          f"{done - start:.2f} s "
          f"(of which the cluster's start {ready - start:.2f} s)")


if __name__ == "__main__":
    main()
