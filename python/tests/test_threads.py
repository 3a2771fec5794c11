"""The GIL is released while the library works, and concurrent calls are safe."""

import sys
import threading

import numpy as np

import tessera
from conftest import make_image


def test_encode_releases_the_gil():
    # With a huge switch interval, a thread holding the GIL keeps it until it blocks or a C
    # extension releases it. The encoding thread reads `flags` right after encode returns: the
    # main thread can only have appended to it by then if it ran Python code while encode was
    # running, i.e. if encode released the GIL.
    img = make_image(256, 256, 4)
    flags, seen = [], []

    def work():
        tessera.encode(img, quality="normal", threads=1)
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
    assert seen == [1]


def test_decode_releases_the_gil():
    tex = tessera.encode(make_image(512, 512, 4), quality="fast", mipmaps=True)
    flags, seen = [], []

    def work():
        for level in range(tex.level_count):
            tessera.decode(tex, level=level, threads=1)
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
    assert seen == [1]


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
