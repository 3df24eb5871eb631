"""A table-cube test campaign on a Dask LocalCluster of 2 worker processes (1 thread each), timed:
the Dask part of bench/campaign_cluster.sh (docs/benchmarks.md). A file, not a here-document:
Dask's worker processes start by re-importing the main module, which needs a path.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/campaign_dask.py DIR SCENARIO N SHARD
"""

import sys
import time


def main() -> None:
    from distributed import Client, LocalCluster
    import probrobscene.campaign as campaign

    work, example, n, shard = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    start = time.time()
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        ready = time.time()
        campaign.run(example, client, dir=f"{work}/dask", n=n, shard_size=shard, seed=1,
                     controller="table-cube")
    done = time.time()
    campaign.merge(f"{work}/dask", f"{work}/dask.jsonl")
    print(f"Dask LocalCluster, 2 workers of 1 thread: {done - start:.2f} s "
          f"(of which the cluster's start {ready - start:.2f} s)")


if __name__ == "__main__":
    main()
