"""Batches run without the GIL, and sampling in a loop does not grow memory."""

import os
import signal
import threading
import time

import pytest

import probrobscene as prs
from conftest import EXAMPLES


def test_other_python_threads_run_while_a_batch_samples(table_cube):
    # A ticker thread notes the time about every millisecond. Were the GIL held for the whole
    # batch, it could not run at all in between: its longest silence would span the batch.
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    time.sleep(0.05)
    begin = time.perf_counter()
    try:
        table_cube.sample_batch(60_000, seed=11, threads=1)
    finally:
        end = time.perf_counter()
        done.set()
        ticker.join()
    assert end - begin > 0.2, "the batch was too short to tell"
    inside = [begin] + [t for t in ticks if begin < t < end] + [end]
    silence = max(b - a for a, b in zip(inside, inside[1:]))
    assert silence < 0.5 * (end - begin), (
        f"the other thread was silent for {silence:.3f} s of a {end - begin:.3f} s batch")


def test_a_second_python_thread_samples_while_a_batch_runs(constructs):
    # Thread A starts a long batch (3,000 constructs.prs scenes, about a second); once A is
    # inside it, thread B samples a short batch of its own. With the GIL (or any lock of the
    # library's) held for a whole batch, B could only finish after A; released, B finishes
    # first. What is compared is the order of two events, not a speed.
    a_started, finished = threading.Event(), []

    def long_batch():
        a_started.set()
        constructs.sample_batch(3_000, seed=1, threads=1)
        finished.append("long")

    def short_batch():
        a_started.wait()
        time.sleep(0.05)  # A is inside sample_batch microseconds after setting the event
        constructs.sample_batch(10, seed=2, threads=1)
        finished.append("short")

    threads = [threading.Thread(target=long_batch), threading.Thread(target=short_batch)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert finished == ["short", "long"]


def _thread_count() -> int:
    return len(os.listdir("/proc/self/task"))


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="needs Linux /proc")
def test_a_batch_on_two_threads_runs_two_workers(constructs):
    # While sample_batch(threads=2) runs, another Python thread counts this process's threads:
    # two workers must appear beside the ones that were there before. (With threads=1 the
    # batch samples on the calling thread.)
    counts, done = [], threading.Event()

    def watch():
        while not done.is_set():
            counts.append(_thread_count())
            time.sleep(0.001)

    watcher = threading.Thread(target=watch)
    watcher.start()
    time.sleep(0.02)
    before = _thread_count()  # this thread and the watcher, among others
    try:
        constructs.sample_batch(2_000, seed=5, threads=2)
    finally:
        done.set()
        watcher.join()
    assert max(counts) >= before + 2, f"threads seen: {sorted(set(counts))}, before: {before}"


def _rss_bytes() -> int:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="needs Linux /proc")
def test_no_memory_growth_over_100000_scenes():
    scenario = prs.load(EXAMPLES / "table_cube.prs")

    def sample(first, last):
        for i in range(first, last):
            scene = scenario.sample(seed=3, index=i)
            cube = scene["Cube#5"]
            cube.position, cube.properties, scene.params  # exercise the conversions too
            if i % 10 == 0:
                scene.to_json()

    sample(0, 10_000)  # warm-up: caches, allocator arenas, interned strings
    before = _rss_bytes()
    sample(10_000, 100_000)
    growth = _rss_bytes() - before
    # One leaked scene is kilobytes; 4 MiB over 90,000 scenes is under 47 bytes each.
    assert growth < 4 * 2**20, f"RSS grew by {growth / 2**20:.1f} MiB over 90,000 scenes"


def test_ctrl_c_stops_a_long_batch(constructs):
    # SIGINT reaches Python's handler; the batch polls for it and raises KeyboardInterrupt
    # instead of sampling the whole batch (100,000 constructs.prs scenes: about 15 s on two
    # threads, and a few hundred MB, were the interrupt missed). Python installs its
    # KeyboardInterrupt handler only when SIGINT is not ignored at startup, and a shell
    # ignores SIGINT in the commands it starts in the background, so the handler is set here.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
        start = time.perf_counter()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            constructs.sample_batch(100_000, seed=1, threads=2)
        timer.join()
        assert time.perf_counter() - start < 5.0
    finally:
        signal.signal(signal.SIGINT, previous)
