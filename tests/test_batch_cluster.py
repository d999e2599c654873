"""ethasp batch on a real Dask cluster on this machine: a scheduler and two workers,
started as users start them (``dask scheduler``, ``dask worker``); one worker is
killed in the middle of the batch, and the results are still complete and equal
to those of the local pool."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from test_batch import by_hash, variants, without_times

import ethasp
from ethasp.batch.output import read_lines
from ethasp.principles.principle import HERA

distributed = pytest.importorskip("distributed")

# Generous: a busy machine starts Python processes slowly.
WAIT = 180.0


def _dask(*arguments: str, folder: Path, log: Path) -> subprocess.Popen:
    environment = dict(os.environ, DASK_TEMPORARY_DIRECTORY=str(folder))
    return subprocess.Popen(
        [sys.executable, "-m", "dask", *arguments],
        cwd=folder,
        env=environment,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=open(log, "wb"),
    )


def _poll(condition, what: str, processes) -> None:
    deadline = time.monotonic() + WAIT
    while not condition():
        for process in processes:
            assert process.poll() is None, f"a Dask process ended while waiting for {what}"
        assert time.monotonic() < deadline, f"no {what} after {WAIT:.0f} s"
        time.sleep(0.2)


@pytest.fixture
def cluster(tmp_path):
    """A scheduler on a free port of 127.0.0.1 and two single-threaded workers without
    nanny (so that killing one kills it), each in its own folder; no dashboards."""
    processes: list[subprocess.Popen] = []
    folder = tmp_path / "scheduler"
    folder.mkdir()
    address_file = folder / "scheduler.json"
    try:
        processes.append(
            _dask(
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(address_file),
                folder=folder,
                log=tmp_path / "scheduler.log",
            )
        )
        _poll(
            lambda: address_file.is_file() and address_file.stat().st_size > 0,
            "scheduler address",
            processes,
        )
        time.sleep(0.1)
        address = json.loads(address_file.read_text())["address"]
        workers = []
        for name in ("one", "two"):
            home = tmp_path / name
            home.mkdir()
            worker = _dask(
                "worker",
                address,
                "--name",
                name,
                "--nthreads",
                "1",
                "--no-nanny",
                "--no-dashboard",
                "--host",
                "127.0.0.1",
                "--local-directory",
                str(home),
                folder=home,
                log=tmp_path / f"{name}.log",
            )
            processes.append(worker)
            workers.append(worker)
        with distributed.Client(address, timeout=60, set_as_default=False) as client:
            _poll(lambda: len(client.scheduler_info()["workers"]) == 2, "two workers", processes)
        yield address, workers
    finally:
        for process in reversed(processes):
            if process.poll() is None:
                process.terminate()
        for process in processes:
            try:
                process.wait(20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def test_a_cluster_computes_the_lines_of_the_local_pool_and_loses_no_case(cluster, tmp_path):
    address, workers = cluster
    cases = tmp_path / "cases"
    variants(cases, 24)
    bad = cases / "zz-syntax.lp"
    bad.write_text("variable(done).\naction(pull).\neff(pull,done,true)\ngoal(done,true).\n")
    local = list(ethasp.batch([cases], ["hera"], workers=2))
    output = tmp_path / "cluster.jsonl"
    running = ethasp.batch([cases], ["hera"], scheduler=address, output=output)
    lines, killed = [], False
    for line in running:
        lines.append(line)
        if not killed and running.cases_done >= 3:
            workers[0].send_signal(signal.SIGKILL)  # a worker lost mid-run
            workers[0].wait()
            killed = True
    assert killed
    assert len(lines) == 24 * len(HERA) + 1, [line for line in lines if "error" in line]
    assert len(list(read_lines(output))) == len(lines)
    assert {h: without_times(line) for h, line in by_hash(lines).items()} == {
        h: without_times(line) for h, line in by_hash(local).items()
    }
    [error] = [line for line in lines if "error" in line]
    assert error["case"] == str(bad) and error["error"].startswith(f"{bad}:4:1")
    # Run again: nothing is missing.
    assert list(ethasp.batch([cases], ["hera"], scheduler=address, output=output)) == []


def test_a_result_is_told_from_an_error_by_itself_not_by_the_futures_status():
    # A worker lost after its result was gathered makes the future's status
    # "lost" while the case's lines are here: they are kept (one error line
    # had replaced a case's lines when a worker was killed at that moment).
    from ethasp.batch.cases import Case
    from ethasp.batch.cluster import DaskCluster, task_error
    from ethasp.batch.task import Work

    lines = [{"case": "c.lp", "principle": "deontology", "permissible": True}]
    assert task_error(lines) is None

    class KilledWorker(Exception):
        pass

    killed = KilledWorker("lost three times")
    assert task_error(killed) is killed
    assert task_error((KilledWorker, killed, None)) is killed  # (Dask's form)
    work = Work(Case.of("c.lp"), ((None, None),))
    assert "ended while computing it" in DaskCluster._failure(work, killed)["error"]
