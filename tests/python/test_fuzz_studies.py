"""Fuzzing the study engine's two doors to the outside: its Zarr store on disk, damaged at
random (files deleted, truncated, overwritten with junk, bytes flipped), and the scheduler
address, malformed at random or pointing at a loopback service that answers random bytes.

The invariants (issue 22, items 1 and 3): a damaged store is either repaired -- the rerun
returns exactly the numbers of the undamaged study (bit for bit), every point done -- or
refused with an InputError naming the store; never NaN, never other numbers, never another
exception. A scheduler address is either accepted or refused with an InputError naming it,
within the stated timeout; never another exception. Examples are few for CI
(SLOSHDYN_FUZZ_EXAMPLES raises them)."""

import math
import os
import shutil
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import sloshdyn
from sloshdyn.studies import cluster
from test_studies import silent_server

pytest.importorskip("dask.distributed")
xr = pytest.importorskip("xarray")

LONG = int(os.environ.get("SLOSHDYN_FUZZ_EXAMPLES", "0"))
FUZZ = settings(max_examples=LONG or 12, deadline=None, derandomize=not LONG,
                suppress_health_check=list(HealthCheck))

P = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075, rho=0.50)
QUICK = sloshdyn.Steady(max_transient_periods=300, window_periods=16)
F, A = [0.505, 0.52], [0.0005, 0.00075]


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


def study(client, store):
    return sloshdyn.response_map(P, F, A, store, client=client, steady=QUICK, points_per_task=2,
                                 progress=False)


@pytest.fixture(scope="module")
def pristine(client, tmp_path_factory):
    """An undamaged store and its dataset; its points are those of a serial loop."""
    store = tmp_path_factory.mktemp("pristine") / "s.zarr"
    ds = study(client, store)
    for i, f in enumerate(F):
        for j, a in enumerate(A):
            assert float(ds.max_x1[i, j]) == sloshdyn.steady_state(
                P.replace(rho=f, A=a), steady=QUICK).max_x1
    return store, ds


def store_files(store):
    return sorted(str(p.relative_to(store)) for p in store.rglob("*") if p.is_file())


#: one damage: (file index, action, position, bytes)
damages = st.tuples(st.integers(0, 10**6),
                    st.sampled_from(["delete", "truncate", "junk", "flip", "empty"]),
                    st.integers(0, 10**6), st.binary(min_size=1, max_size=64))


def damage_store(store, damage):
    files = store_files(store)
    index, action, position, junk = damage
    path = store / files[index % len(files)]
    data = bytearray(path.read_bytes())
    if action == "delete":
        path.unlink()
    elif action == "truncate":
        path.write_bytes(bytes(data[:position % max(1, len(data))]))
    elif action == "junk":
        path.write_bytes(junk)
    elif action == "flip" and data:
        data[position % len(data)] ^= 1 << (position % 8)
        path.write_bytes(bytes(data))
    elif action == "empty":
        path.write_bytes(b"")
    return files[index % len(files)]


@FUZZ
@given(st.lists(damages, min_size=1, max_size=3))
def test_a_damaged_store_is_repaired_exactly_or_refused(client, pristine, tmp_path_factory,
                                                        damage):
    original, expected = pristine
    store = tmp_path_factory.mktemp("damaged") / "s.zarr"
    shutil.copytree(original, store)
    hit = [damage_store(store, d) for d in damage]
    try:
        ds = study(client, store)
    except sloshdyn.InputError as exc:
        assert "s.zarr" in str(exc), (hit, exc)
        return
    assert bool(ds["done"].all()), hit
    for name in expected.data_vars:
        assert ds[name].equals(expected[name]), (hit, name)      # bit for bit, no NaN
    assert ds.attrs["points_computed"] >= ds.attrs["points_repaired"], hit   # repaired: computed


addresses = st.one_of(
    st.text(max_size=40),
    st.builds(lambda scheme, host, port: f"{scheme}{host}:{port}",
              st.sampled_from(["", "tcp://", "tls://", "ftp://", "http://", "inproc://", "://"]),
              st.one_of(st.sampled_from(["", "host", "[::1", "a b", "127.0.0.1.1"]),
                        st.text(max_size=12)),
              st.one_of(st.integers(-10, 70000).map(str), st.text(max_size=6))))


@FUZZ
@given(addresses)
def test_a_scheduler_address_is_accepted_or_named(address):
    try:
        checked, scheme, host, port = cluster.check_scheduler(address)
    except sloshdyn.InputError as exc:
        assert "scheduler = " in str(exc)
        return
    assert scheme in ("tcp", "tls", "ws", "wss", "ucx") and 0 < port < 65536 and host


@FUZZ
@given(st.binary(max_size=32))
def test_a_service_answering_random_bytes_is_no_scheduler(reply):
    address, close = silent_server(reply)
    port = int(address.rsplit(":", 1)[1])
    try:
        start = time.monotonic()
        try:
            cluster.probe_scheduler(f"tcp://127.0.0.1:{port}", "127.0.0.1", port)
            accepted = True
        except sloshdyn.InputError as exc:
            assert f"tcp://127.0.0.1:{port}" in str(exc)
            accepted = False
        assert time.monotonic() - start < cluster.CONNECT_TIMEOUT + 5
    finally:
        close()
    # accepted only where the first 8 bytes read as a Dask message length
    header = np.frombuffer(reply[:8], dtype=np.uint64)[0] if len(reply) >= 8 else None
    assert accepted == (header is not None and 0 < int(header) <= cluster.MAX_HANDSHAKE)
