"""Candidate hoop placements on a stretched garment piece (garment mode).

A placement is a hoop type, an orientation (0 or 90 degrees) and the position of its field
centre on the stretched piece. It *holds* patch i when the disc of i lies in the field shrunk by
the margin: |x_i - cx| <= W/2 - r_i and |y_i - cy| <= H/2 - r_i (W x H the field minus margins
in that orientation). It is *allowed* when the hoop's outer rectangle (field plus frame ring)
lies on the fabric: inside the piece outline, or inside the uncut blank around it when the piece
is hooped as a blank (``StretchedPiece.blank_mm``); the frame must clamp fabric all round. Both
tests and the search of step 3 are the constraint check's (``layout.check.rules.hoopable``).

Enumeration (exact for the sets that can be held, before the piece-edge rule):

1. Anchors: cx in {x_i - r_i + W/2 (left edge on patch i), x_i + r_i - W/2 (right edge on i),
   x_i (centred on i)}, likewise cy. The set held at any position is contained in the set held
   at the left/bottom anchor of its leftmost/lowest member, so the anchors meet every maximal
   set; the other anchors add smaller sets that may survive the edge rule.
2. The held sets at all anchor pairs are deduplicated (bit sets); for each distinct set S the
   position is chosen in S's feasible box (cx in [max_S(x + r) - W/2, min_S(x - r) + W/2], same
   for y; ``hoopable.feasible_box``, the box the workshop sheet's hoop reason tests too): of a
   5 x 5 grid over the box (``hoopable.box_grid``), the positions whose frame ring touches the
   fewest other patches come first, then those nearest the box centre; the first allowed
   position is kept (and may hold more than S). A set with no allowed position on that grid gets a
   17 x 17 grid; a set with none there either is dropped.
3. A patch that no kept placement holds gets a search of its own: a 2 mm grid over every
   position that holds it, for every hoop and orientation; the allowed position holding the
   most patches is added. If there is none the patch cannot be hooped: ``InvalidInputError``.

Each placement also counts the other patches of its piece that its frame ring touches (the
disc meets the outer rectangle but is not inside the field): the overlap used as tie-breaker.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.rules import hoopable
from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.fabrication.grouping import bitsets

TOL_MM = 1e-9
#: the grids (points per axis) tried in turn over a held set's feasible box
GRIDS = (5, 17)


@dataclass(frozen=True)
class Candidates:
    """Placements as parallel arrays; ``holds`` is (m, n) over the patches of the problem."""
    hoop_index: np.ndarray      # (m,) index into ``hoops``
    orientation_deg: np.ndarray  # (m,) 0 or 90
    centre_mm: np.ndarray       # (m, 2) field centre on the stretched piece
    piece_index: np.ndarray     # (m,)
    holds: np.ndarray           # (m, n) bool
    overlap: np.ndarray         # (m,) patches of the piece under the frame ring, not held
    hoops: tuple[Hoop, ...]
    touches: np.ndarray | None = None   # (m, n) bool: the patches ``overlap`` counts

    def __len__(self) -> int:
        return len(self.hoop_index)


def _variants(hoops):
    for k, hoop in enumerate(hoops):
        for o in hoop.orientations:
            yield k, hoop, o


def _choose_positions(members, x, y, r, hoop, o, piece):
    """For each row of ``members`` (bool (s, n)): an allowed position in its feasible box, or
    NaN. Tries a 5 x 5 grid over the box, fewest frame-ring contacts first, then nearest the
    box centre; the rows with no allowed position on it get a 17 x 17 grid (a box of a few
    hundred mm whose allowed strip is narrower than the 5 x 5 grid's step)."""
    out = _positions_on_grid(members, x, y, r, hoop, o, piece, GRIDS[0])
    for n_grid in GRIDS[1:]:
        miss = np.flatnonzero(~np.isfinite(out[:, 0]))
        if not len(miss):
            break
        out[miss] = _positions_on_grid(members[miss], x, y, r, hoop, o, piece, n_grid)
    return out


def _positions_on_grid(members, x, y, r, hoop, o, piece, n_grid):
    """``_choose_positions`` on one n_grid x n_grid grid over each feasible box."""
    w, h = hoop.usable_mm(o)
    fw, fh = hoop.field_mm(o)
    ow, oh = hoop.outer_mm(o)
    cx, cy, a, b = hoopable.box_grid(*hoopable.feasible_box(members, x, y, r, w, h), n_grid)
    contacts = np.empty(cx.shape, dtype=int)
    for j in range(cx.shape[1]):
        held = hoopable.held(cx[:, j], cy[:, j], x, y, r, w, h)
        ring = hoopable.ring_touches(cx[:, j], cy[:, j], fw, fh, hoop.frame_width_mm, x, y, r)
        contacts[:, j] = (ring & ~held).sum(axis=1)
    centred = (a - 0.5) ** 2 + (b - 0.5) ** 2
    rank = np.argsort(contacts + 0.1 * centred[None, :], axis=1, kind="stable")
    out = np.full((len(members), 2), np.nan)
    todo = np.arange(len(members))
    for step in range(cx.shape[1]):
        if not len(todo):
            break
        j = rank[todo, step]
        px, py = cx[todo, j], cy[todo, j]
        ok = hoopable.allowed(piece, px, py, ow, oh)
        out[todo[ok]] = np.column_stack([px[ok], py[ok]])
        todo = todo[~ok]
    return out


def _rescue(i, x, y, r, hoops, piece):
    """The allowed placement holding patch i and the most others (None if there is none): the
    check's own search (``layout.check.rules.hoopable``), so both agree on what can be hooped."""
    return hoopable.best_placement(i, x, y, r, hoops, piece)


def generate(feet, pieces, hoops: tuple[Hoop, ...]) -> Candidates:
    """Candidate placements for footprints ``feet`` on stretched ``pieces`` (see module doc)."""
    n = len(feet)
    names = [p.name for p in pieces]
    piece_of = np.array([names.index(f.piece) for f in feet])
    x = np.array([f.centre_mm[0] for f in feet], dtype=float)
    y = np.array([f.centre_mm[1] for f in feet], dtype=float)
    r = np.array([f.radius_mm for f in feet], dtype=float)
    _check_sizes(feet, r, hoops)
    rows = []      # (hoop index, orientation, cx, cy, piece index)
    for pi, piece in enumerate(pieces):
        idx = np.flatnonzero(piece_of == pi)
        if not len(idx):
            continue
        poly = hoopable.hoop_region(piece.outline_mm, piece.blank_mm)
        xs, ys, rs = x[idx], y[idx], r[idx]
        for k, hoop, o in _variants(hoops):
            w, h = hoop.usable_mm(o)
            ow, oh = hoop.outer_mm(o)
            fits = 2 * rs <= min(w, h) + TOL_MM
            if not fits.any():
                continue
            ax = np.unique(np.round(np.concatenate([xs - rs + w / 2, xs + rs - w / 2, xs])[
                np.tile(fits, 3)], 9))
            ay = np.unique(np.round(np.concatenate([ys - rs + h / 2, ys + rs - h / 2, ys])[
                np.tile(fits, 3)], 9))
            bx = bitsets.pack(hoopable.held(ax, np.zeros_like(ax), xs, np.zeros_like(ys), rs, w, np.inf))
            by = bitsets.pack(hoopable.held(np.zeros_like(ay), ay, np.zeros_like(xs), ys, rs, np.inf, h))
            sets = (bx[:, None, :] & by[None, :, :]).reshape(-1, bx.shape[1])
            sets = np.unique(sets[np.any(sets != 0, axis=1)], axis=0)
            members = bitsets.unpack(sets, len(idx))
            pos = _choose_positions(members, xs, ys, rs, hoop, o, poly)
            for cx, cy in pos[np.isfinite(pos[:, 0])]:
                rows.append((k, o, float(cx), float(cy), pi))
        held_any = _holds_of(rows, x, y, r, hoops, piece_of, n).any(axis=0) if rows else \
            np.zeros(n, dtype=bool)
        for i in idx[~held_any[idx]]:
            got = _rescue(i, x, y, r, hoops, poly)
            if got is None:
                raise InvalidInputError(
                    f"patch {feet[i].id!r} cannot be hooped: it is too close to the edge of piece "
                    f"{piece.name!r} for any hoop field plus its frame ring to lie on the fabric "
                    "(the frame must clamp fabric all round; `stitchswitch check` names every "
                    "such patch); move it inward or hoop the piece as an uncut blank "
                    "(--blank-margin MM, docs/fabrication.md)")
            k, o, (cx, cy) = got
            rows.append((k, o, cx, cy, pi))
            held_any = _holds_of(rows, x, y, r, hoops, piece_of, n).any(axis=0)
    return _assemble(rows, x, y, r, hoops, piece_of, n)


def _check_sizes(feet, r, hoops) -> None:
    best = max(min(h.usable_mm()) for h in hoops)
    for f, ri in zip(feet, r):
        if 2 * ri > best + TOL_MM:
            big = max(hoops, key=lambda h: (min(h.usable_mm()), h.area_mm2))
            uw, uh = big.usable_mm()
            raise InvalidInputError(
                f"patch {f.id!r}: its {2 * ri:g} mm footprint on the stretched fabric fits no "
                f"hoop; the roomiest is {big} with {uw:g} x {uh:g} mm inside its "
                f"{big.margin_mm:g} mm margin")


def _holds_of(rows, x, y, r, hoops, piece_of, n):
    out = np.zeros((len(rows), n), dtype=bool)
    for j, (k, o, cx, cy, pi) in enumerate(rows):
        w, h = hoops[k].usable_mm(o)
        out[j] = hoopable.held(np.array([cx]), np.array([cy]), x, y, r, w, h)[0] & (piece_of == pi)
    return out


def _assemble(rows, x, y, r, hoops, piece_of, n) -> Candidates:
    holds = np.zeros((len(rows), n), dtype=bool)
    touches = np.zeros((len(rows), n), dtype=bool)
    for j, (k, o, cx, cy, pi) in enumerate(rows):
        hoop = hoops[k]
        w, h = hoop.usable_mm(o)
        fw, fh = hoop.field_mm(o)
        same = piece_of == pi
        c1, c2 = np.array([cx]), np.array([cy])
        holds[j] = hoopable.held(c1, c2, x, y, r, w, h)[0] & same
        touches[j] = (hoopable.ring_touches(c1, c2, fw, fh, hoop.frame_width_mm, x, y, r)[0]
                      & same & ~holds[j])
    # one row per distinct (hoop, orientation, piece, held set): the first found is kept
    key = np.column_stack([np.array([rw[0] for rw in rows]), np.array([rw[1] for rw in rows]),
                           np.array([rw[4] for rw in rows]), bitsets.pack(holds).view(np.int64)]) \
        if rows else np.zeros((0, 4), dtype=np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    keep = np.sort(first)
    return Candidates(np.array([rows[j][0] for j in keep], dtype=int),
                      np.array([rows[j][1] for j in keep], dtype=int),
                      np.array([[rows[j][2], rows[j][3]] for j in keep],
                               dtype=float).reshape(-1, 2),
                      np.array([rows[j][4] for j in keep], dtype=int),
                      holds[keep], touches[keep].sum(axis=1).astype(int), tuple(hoops),
                      touches[keep])
