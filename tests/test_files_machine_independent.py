"""A design's machine file does not depend on the processor's BLAS kernel.

OpenBLAS picks its kernels per CPU model, and they round a dot product differently in the last
bit; stitch counts come from lengths rounded up, so a length computed through BLAS made the same
design give different files on different machines (8369 or 8375 stitches for the guide's
button). The stitch paths use ``layout.embroidery.planar`` instead; here the same command runs
under three OpenBLAS kernels (``OPENBLAS_CORETYPE``) and must write the same bytes."""
import hashlib
import os
import platform
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from stitchswitch.layout.embroidery import planar


def _kernels() -> tuple:
    """OpenBLAS kernels this processor can run: SSE3 and AVX2 ones, and an AVX-512 one (the
    kernel whose rounding differed) where the CPU has AVX-512."""
    cpuinfo = Path("/proc/cpuinfo")
    flags = cpuinfo.read_text() if cpuinfo.is_file() else ""
    return ("Prescott", "Haswell") + (("SkylakeX",) if " avx512f" in flags else ())


KERNELS = _kernels()


def _jef_digest(tmp_path, kernel: str) -> str:
    out = tmp_path / f"{kernel}.jef"
    env = dict(os.environ, OPENBLAS_CORETYPE=kernel)
    r = subprocess.run([sys.executable, "-m", "stitchswitch", "patch", "-d", "60", "-p", "0.794",
                        "--conductive", "ring:0", "-o", str(out)], env=env, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return hashlib.sha256(out.read_bytes()).hexdigest()


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"),
                    reason="OPENBLAS_CORETYPE names x86-64 kernels")
def test_the_same_file_under_every_blas_kernel(tmp_path):
    digests = {k: _jef_digest(tmp_path, k) for k in KERNELS}
    assert len(set(digests.values())) == 1, digests


def test_planar_helpers_match_numpy():
    rng = np.random.default_rng(5)
    u, v = rng.normal(size=2), rng.normal(size=2)
    assert planar.length(u) == np.float64(np.hypot(*u))
    assert abs(planar.dot(u, v) - float(u @ v)) <= 1e-15
    pts, m = rng.normal(size=(7, 2)), rng.normal(size=(2, 2))
    np.testing.assert_allclose(planar.transform(pts, m), pts @ m, rtol=1e-14, atol=1e-15)
