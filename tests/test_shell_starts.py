"""Where the shell's Newton solve starts, and whether its result depends on it.

The reduced model's equilibrium is only a guess: an independent start (``cap_start``, a
spherical cap at its natural length) reaches the same certified equilibrium on designs that
have one pop-up state. On designs with more than one, the two starts reach different certified
states (documented in docs/fem-reference.md, "Starts"). When the guess does not certify, the
flat sheet is tried.
"""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch
from stitchswitch.fem_reference.revolution.solve import (
    GUESS_ITERATIONS,
    build,
    cap_start,
    equilibrium,
    reduced_start,
    relax,
)


@pytest.mark.parametrize("d, p", [(90.0, 0.8), (50.0, 1.0)])
def test_an_independent_start_reaches_the_same_equilibrium(d, p):
    patch = Patch(d, p)
    problem = build(patch)
    guess = reduced_start(problem, patch, DEFAULT_MATERIAL)
    cap = cap_start(problem)
    assert np.max(np.abs(cap - guess)) > 1.0            # a genuinely different start (mm)
    from_guess = relax(problem, guess)
    from_cap = relax(problem, cap)
    assert from_guess.certified and from_cap.certified
    assert np.max(np.abs(from_cap.y - from_guess.y)) < 1e-6
    assert from_cap.apex_mm == pytest.approx(from_guess.apex_mm, abs=1e-6)


def test_more_than_one_popup_state_at_d60_p08():
    """The measured limitation: the two starts reach two distinct certified pop-up states."""
    patch = Patch(60.0, 0.8)
    problem = build(patch)
    from_guess = relax(problem, reduced_start(problem, patch, DEFAULT_MATERIAL))
    from_cap = relax(problem, cap_start(problem))
    assert from_guess.certified and from_cap.certified
    assert from_cap.apex_mm - from_guess.apex_mm > 1.0
    assert from_cap.energy < from_guess.energy


def test_an_uncertified_guess_falls_back_to_the_flat_sheet():
    """d 25 mm, p 1.0: from the reduced guess Newton does not certify within the guess budget
    (it heads for a folded flat state); the flat start certifies the flat equilibrium."""
    patch = Patch(25.0, 1.0)
    problem = build(patch)
    guess = relax(problem, reduced_start(problem, patch, DEFAULT_MATERIAL), max_iter=GUESS_ITERATIONS)
    assert not guess.certified
    st = equilibrium(patch)
    assert st.certified
    assert abs(st.apex_mm) < 1e-6
    assert st.energy < guess.energy
