"""The GIL is released while the library works, and concurrent calls are safe."""

import sys
import threading

import numpy as np

import tessera
from conftest import make_image


def released_the_gil(call, attempts):
    """Runs `call` in a thread, up to `attempts` times, while the main thread tries to append to
    a list; true when the append happened while a call was running.

    With a huge switch interval a thread holding the GIL keeps it until it blocks or a C
    extension releases it. The main thread waits for the GIL from `Thread.start` on; the worker
    repeats its call until it sees the append, so the main thread only needs one of the calls'
    GIL-free stretches to be scheduled (on a loaded machine the first may pass unseen). If no
    call released the GIL, the append can only come after the worker ends, which it records as
    0.
    """
    flags, seen = [], []

    def work():
        for _ in range(attempts):
            call()
            if flags:
                break
        seen.append(len(flags))

    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        t = threading.Thread(target=work)
        t.start()
        flags.append(1)
        t.join()
    finally:
        sys.setswitchinterval(old)
    return seen == [1]


def test_encode_releases_the_gil():
    img = make_image(256, 256, 4)
    assert released_the_gil(lambda: tessera.encode(img, quality="normal", threads=1), 40)


def test_decode_releases_the_gil():
    tex = tessera.encode(make_image(512, 512, 4), quality="fast", mipmaps=True)

    def decode_all():
        for level in range(tex.level_count):
            tessera.decode(tex, level=level, threads=1)

    assert released_the_gil(decode_all, 200)


def test_the_gil_check_fails_for_a_call_that_keeps_the_gil():
    # Negative control: pure Python work never releases the GIL under the huge switch interval.
    assert not released_the_gil(lambda: sum(range(20000)), 5)


def test_concurrent_encodes_equal_sequential():
    images = [make_image(64, 64, 3 + i % 2, seed=i) for i in range(6)]
    expected = [tessera.encode(im, quality="normal").to_bytes() for im in images]
    results = [None] * len(images)

    def work(i):
        results[i] = tessera.encode(images[i], quality="normal", threads=2).to_bytes()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(images))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == expected
    decoded = [tessera.decode(tessera.from_bytes(b)) for b in results]
    assert all(np.array_equal(d, tessera.decode(tessera.from_bytes(e)))
               for d, e in zip(decoded, expected))
