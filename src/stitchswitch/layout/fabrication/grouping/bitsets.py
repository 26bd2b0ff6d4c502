"""Sets of patches as rows of packed 64-bit words (fast subset tests over many candidates)."""
from __future__ import annotations

import numpy as np


def pack(mask: np.ndarray) -> np.ndarray:
    """(m, n) bool -> (m, ceil(n / 64)) uint64; bit j of word w is element 64 w + j."""
    mask = np.asarray(mask, dtype=bool)
    m, n = mask.shape
    words = max(1, -(-n // 64))
    padded = np.zeros((m, words * 64), dtype=bool)
    padded[:, :n] = mask
    bits = padded.reshape(m, words, 64).astype(np.uint64)
    return (bits << np.arange(64, dtype=np.uint64)).sum(axis=2, dtype=np.uint64)


def unpack(words: np.ndarray, n: int) -> np.ndarray:
    """Inverse of ``pack``: (m, w) uint64 -> (m, n) bool."""
    words = np.asarray(words, dtype=np.uint64)
    bits = (words[:, :, None] >> np.arange(64, dtype=np.uint64)) & np.uint64(1)
    return bits.reshape(len(words), -1)[:, :n].astype(bool)


def supersets(rows: np.ndarray, subset: np.ndarray) -> np.ndarray:
    """(m,) bool: which rows contain every element of ``subset`` (one packed row)."""
    return np.all((rows & subset) == subset, axis=1)
