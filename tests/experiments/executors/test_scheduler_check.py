"""``--executor dask`` with a scheduler nobody answers at (issue 16: Dask's client waited
30 s and ended in a traceback). :func:`check_scheduler` answers within about 2 s, naming the
address; a real scheduler passes it (``test_sweep``'s Dask test runs through it).

Its promptness is held against the fault, not against a benchmark: Dask's client waited 30 s,
so a refusal must come well within that (``PROMPT_S``), with Dask already imported (importing
it takes seconds on a loaded machine and is not what the check is about; issue 22)."""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Iterator

import pytest

from experiments.executors.cluster import (
    SCHEDULER_TIMEOUT_S,
    SchedulerUnreachable,
    check_scheduler,
    scheduler_endpoint,
)

DASK_CLIENT_WAIT_S = 30.0  # what Dask's client waited before the check (issue 16)
PROMPT_S = 10 * SCHEDULER_TIMEOUT_S  # 20 s: well within it, 10 times the check's own timeout


@pytest.mark.parametrize(
    ("address", "endpoint"),
    [
        ("tcp://10.0.0.5:8786", ("10.0.0.5", 8786)),
        ("tls://scheduler.example:443", ("scheduler.example", 443)),
        ("host:1", ("host", 1)),
        ("tcp://[::1]:8786", ("::1", 8786)),
    ],
)
def test_scheduler_addresses_are_read(address: str, endpoint: tuple[str, int]) -> None:
    assert scheduler_endpoint(address) == endpoint


@pytest.mark.parametrize(
    ("address", "says"),
    [
        ("", "not a scheduler address"),
        ("tcp://:8786", "not a scheduler address"),
        ("http://host:8786", "not a scheduler address"),
        ("tcp://host", "not a scheduler address"),
        ("tcp://host:0", "port must be a number in [1, 65535]"),
        ("tcp://host:99999", "port must be a number in [1, 65535]"),
        ("tcp://host:port", "port must be a number in [1, 65535]"),
    ],
)
def test_malformed_addresses_are_refused_naming_them(address: str, says: str) -> None:
    with pytest.raises(SchedulerUnreachable) as info:
        scheduler_endpoint(address)
    assert says in str(info.value) and f"'{address}'" in str(info.value)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture
def impostor() -> Iterator[int]:
    """A TCP server that is not a Dask scheduler: it answers every connection with text."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    server.settimeout(0.2)
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            try:
                conn.sendall(b"HTTP/1.0 200 OK\r\n\r\nnot a scheduler\n" * 4)
            finally:
                conn.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield int(server.getsockname()[1])
    stop.set()
    thread.join()
    server.close()


@pytest.fixture(scope="module", autouse=True)
def _dask_imported() -> None:
    """Dask imported before any refusal is timed: the check imports it first."""
    import distributed  # noqa: F401


def _refusal(address: str) -> tuple[str, float]:
    start = time.perf_counter()
    with pytest.raises(SchedulerUnreachable) as info:
        check_scheduler(address)
    return str(info.value), time.perf_counter() - start


def test_a_refused_port_is_one_line_at_once() -> None:
    address = f"tcp://127.0.0.1:{_free_port()}"
    message, seconds = _refusal(address)
    assert address in message and "Connection refused" in message and "\n" not in message
    assert seconds < PROMPT_S < DASK_CLIENT_WAIT_S  # not Dask's 30 s wait


def test_an_unknown_host_is_one_line() -> None:
    message, seconds = _refusal("tcp://no-such-host.invalid:8786")
    assert "no-such-host.invalid" in message and "cannot connect" in message
    assert seconds < PROMPT_S


def test_a_server_that_is_not_a_scheduler_is_refused(impostor: int) -> None:
    message, seconds = _refusal(f"tcp://127.0.0.1:{impostor}")
    assert "no Dask scheduler answers there" in message and "\n" not in message
    assert seconds < PROMPT_S
