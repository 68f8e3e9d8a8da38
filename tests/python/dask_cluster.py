"""A real Dask cluster for tests: `dask scheduler` and two `dask worker` processes on
127.0.0.1, on free ports, with bounded waits; every process is ended afterwards."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

DASK = str(Path(sys.executable).with_name("dask"))
START_TIMEOUT = 90.0  # s: a cold start imports pandas and distributed on a shared machine


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(processes):
    for p in processes:
        if p.poll() is None:
            p.terminate()
    for p in processes:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait(timeout=20)


@contextlib.contextmanager
def cluster(workers: int = 2):
    """Yield the scheduler's address once `workers` single-threaded workers are connected."""
    from distributed import Client

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, DASK_DISTRIBUTED__WORKER__DAEMON="False")
    common = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    processes = [
        subprocess.Popen(
            [
                DASK,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                str(port),
                "--dashboard-address",
                "127.0.0.1:0",
            ],
            **common,
        )
    ]
    try:
        for _ in range(workers):
            processes.append(
                subprocess.Popen(
                    [
                        DASK,
                        "worker",
                        address,
                        "--host",
                        "127.0.0.1",
                        "--nworkers",
                        "1",
                        "--nthreads",
                        "1",
                        "--no-dashboard",
                        "--death-timeout",
                        "60",
                    ],
                    **common,
                )
            )
        deadline = time.monotonic() + START_TIMEOUT
        while True:
            try:
                with Client(address, timeout="10s") as client:
                    client.wait_for_workers(workers, timeout=max(deadline - time.monotonic(), 1.0))
                    break
            except (OSError, TimeoutError):
                if time.monotonic() > deadline or any(p.poll() is not None for p in processes):
                    raise RuntimeError(
                        f"dask cluster at {address} did not start within {START_TIMEOUT} s"
                    )
                time.sleep(0.5)
        yield address
    finally:
        _stop(processes)
