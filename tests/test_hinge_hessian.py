"""``hinge.hinge_hessian`` skips the products with the known zeros of C; it must give the full
product V^T C V of its definition bit for bit (the solver's iterates depend on every bit)."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms import hinge
from stitchswitch.reduced.model.terms.segment import add_length_hessian
from stitchswitch.reduced.solvers import continuation


def _reference(C, V, c, FX, FY, FD, hess_x, hess_dot, m0, m1, la, lb, uar, uaz, ubr, ubz):
    """The definition: every entry of C V and V^T (C V), summed in index order."""
    C = C.copy()
    C[4, 6] = C[6, 4] = FD
    C[5, 7] = C[7, 5] = FD
    C[6, 7] = C[7, 6] = FY
    W = np.zeros((8, 6))
    for k in range(8):
        for s in range(6):
            acc = 0.0
            for m in range(8):
                acc += C[k, m] * V[m, s]
            W[k, s] = acc
    H = np.zeros((6, 6))
    for p in range(6):
        for s in range(p + 1):
            acc = FX * hess_x[p, s] + FY * hess_dot[p, s]
            for k in range(8):
                acc += V[k, p] * W[k, s]
            H[p, s] = c * acc
    add_length_hessian(H, 0, c * (FD * m0 + FY * lb), uar, uaz, la)
    add_length_hessian(H, 2, c * (FD * m1 + FY * la), ubr, ubz, lb)
    return H


@pytest.mark.parametrize("design", [(15.0, 0.6), (55.0, 1.0)])
def test_hinge_hessian_is_the_full_product_bit_for_bit(design):
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    r, z = continuation.released_state(grid)
    rng = np.random.default_rng(0)
    r = r * (1.0 + 0.05 * rng.standard_normal(r.size))
    r[0] = 0.0
    z = np.sort(z + rng.uniform(0.0, 2.0, z.size))[::-1].copy()
    for i in range(0, r.size - 2, 7):
        ar, az, br, bz, la, lb, m0, m1, X, Y, D = hinge.hinge_geometry(r, z, i)
        V, g = np.zeros((8, 6)), np.empty(6)
        FX, FY, FD, Fr = rng.standard_normal(4)
        c = float(rng.uniform(0.1, 2.0))
        u = hinge.hinge_gradient(g, V, c, Fr, FD, FX, FY, ar, az, br, bz, la, lb, m0, m1)
        C = np.zeros((8, 8))
        block = rng.standard_normal((4, 4))
        C[:4, :4] = block + block.T
        args = (c, FX, FY, FD, hinge.HESS_X, hinge.HESS_DOT, m0, m1, la, lb, *u)
        H = np.zeros((6, 6))
        hinge.hinge_hessian(H, C.copy(), V, np.empty((8, 6)), *args)
        expected = _reference(C, V, *args)
        assert np.array_equal(np.tril(H), np.tril(expected))
