"""numba's cache of the kernels is cleared when any kernel source changes (kernel_cache)."""
from pathlib import Path

from stitchswitch.reduced.model import kernel_cache


def _tree(tmp_path):
    reduced = tmp_path / "reduced"
    terms = reduced / "model" / "terms"
    solvers = reduced / "solvers"
    for folder in (terms, solvers):
        (folder / "__pycache__").mkdir(parents=True)
    (terms / "radial.py").write_text("def k(): return 1\n")
    (solvers / "fused.py").write_text("from terms import radial\n")
    return reduced


def _cached(folder: Path):
    for name in ("f.k-3.py311.nbi", "f.k-3.py311.1.nbc"):
        (folder / "__pycache__" / name).write_text("machine code")
    return sorted(p.name for p in (folder / "__pycache__").glob("*.nb?"))


def test_cache_is_cleared_when_a_kernel_changes_and_kept_otherwise(tmp_path):
    reduced = _tree(tmp_path)
    stamp = reduced / "__pycache__" / kernel_cache.STAMP
    files = kernel_cache.kernel_sources(reduced)
    assert [f.name for f in files] == ["radial.py", "fused.py"]
    assert kernel_cache.clear_if_changed(files, stamp)          # no stamp yet: cleared
    solvers = reduced / "solvers"
    assert _cached(solvers)
    assert not kernel_cache.clear_if_changed(files, stamp)      # nothing changed: kept
    assert len(list((solvers / "__pycache__").glob("*.nb?"))) == 2
    (reduced / "model" / "terms" / "radial.py").write_text("def k(): return 2\n")
    assert kernel_cache.clear_if_changed(files, stamp)          # a called kernel changed
    assert list((solvers / "__pycache__").glob("*.nb?")) == []


def test_the_installed_kernels_match_their_stamp():
    """Importing the terms ran the guard: the stamp records the current sources."""
    import stitchswitch.reduced.model.terms  # noqa: F401

    reduced = Path(kernel_cache.__file__).resolve().parent.parent
    stamp = reduced / "__pycache__" / kernel_cache.STAMP
    assert stamp.read_text() == kernel_cache.fingerprint(kernel_cache.kernel_sources(reduced), reduced)
