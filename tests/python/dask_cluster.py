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


#: Starts on a fresh port after a scheduler or worker exited early: the port free_port found
#: can be taken by another process before the scheduler binds it.
ATTEMPTS = 3


@contextlib.contextmanager
def cluster(workers: int = 2):
    """Yield the scheduler's address once `workers` single-threaded workers are connected."""
    for attempt in range(ATTEMPTS):
        try:
            address, processes = _start(workers)
            break
        except _Exited:
            if attempt == ATTEMPTS - 1:
                raise
    try:
        yield address
    finally:
        _stop(processes)


class _Exited(RuntimeError):
    """A scheduler or worker process exited before the cluster was up."""


def _start(workers: int):
    """Start a scheduler and `workers` workers; return (address, processes) once connected."""
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
                exited = [p.args[1] for p in processes if p.poll() is not None]
                if exited:
                    raise _Exited(f"dask cluster at {address}: the {exited[0]} exited")
                if time.monotonic() > deadline:
                    raise RuntimeError(
                        f"dask cluster at {address} did not start within {START_TIMEOUT} s"
                    )
                time.sleep(0.5)
        return address, processes
    except BaseException:
        _stop(processes)
        raise
