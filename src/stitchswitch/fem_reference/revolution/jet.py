"""Second-order jets: a value with its gradient and Hessian with respect to a few pointwise
variables, carried through arithmetic by the chain rule.

The shell's energy density is a function of the five fields q = (r, r', z', r'', z'') at every
quadrature point; writing it with jets gives its exact gradient (5, P) and Hessian (5, 5, P) at
all P points at once, so the Newton solver sees the exact second derivative. Every operation
here is checked against finite differences (tests/test_shell_derivatives.py).
"""
from __future__ import annotations

import numpy as np


class Jet:
    """``v`` (P,), ``g`` (m, P), ``h`` (m, m, P): value, gradient and Hessian at P points."""

    __slots__ = ("v", "g", "h")

    def __init__(self, v, g, h):
        self.v, self.g, self.h = v, g, h

    @classmethod
    def variable(cls, q: np.ndarray, k: int, derivatives: bool = True) -> "Jet":
        """The k-th of the m variables ``q`` (m, P); without ``derivatives`` a jet of no
        variables (values only: the cheap energy of a line search)."""
        m, p = q.shape
        if not derivatives:
            return cls(np.array(q[k], dtype=float), np.zeros((0, p)), np.zeros((0, 0, p)))
        g = np.zeros((m, p))
        g[k] = 1.0
        return cls(np.array(q[k], dtype=float), g, np.zeros((m, m, p)))

    def __add__(self, other):
        if not isinstance(other, Jet):
            return Jet(self.v + other, self.g, self.h)
        return Jet(self.v + other.v, self.g + other.g, self.h + other.h)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, -self.g, -self.h)

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if not isinstance(other, Jet):
            c = np.asarray(other, dtype=float)
            return Jet(self.v * c, self.g * c, self.h * c)
        o = other
        h = self.h * o.v + self.v * o.h + np.einsum("ip,jp->ijp", self.g, o.g)
        h = h + np.einsum("ip,jp->ijp", o.g, self.g)
        return Jet(self.v * o.v, self.g * o.v + self.v * o.g, h)

    __rmul__ = __mul__

    def __truediv__(self, other):
        if not isinstance(other, Jet):
            return self * (1.0 / np.asarray(other, dtype=float))
        return self * other.power(-1.0)

    def __rtruediv__(self, other):
        return self.power(-1.0) * other

    def chain(self, f0, f1, f2) -> "Jet":
        """f(self) from f, f' and f'' evaluated at ``self.v``."""
        return Jet(f0, f1 * self.g, f1 * self.h + f2 * np.einsum("ip,jp->ijp", self.g, self.g))

    def power(self, a: float) -> "Jet":
        """self ** a, for a positive value."""
        v = self.v
        return self.chain(v ** a, a * v ** (a - 1.0), a * (a - 1.0) * v ** (a - 2.0))

    def sqrt(self) -> "Jet":
        return self.power(0.5)

    def square(self) -> "Jet":
        return self.chain(self.v * self.v, 2.0 * self.v, 2.0 * np.ones_like(self.v))

    def positive_square(self) -> "Jet":
        """max(self, 0)^2: C1, its second derivative jumps at 0 (tension only)."""
        on = self.v > 0.0
        return self.chain(np.where(on, self.v * self.v, 0.0), np.where(on, 2.0 * self.v, 0.0),
                          np.where(on, 2.0, 0.0))

    @staticmethod
    def where(mask, a: "Jet", b: "Jet") -> "Jet":
        """Pointwise a where ``mask``, else b (a piecewise function's active branch)."""
        return Jet(np.where(mask, a.v, b.v), np.where(mask, a.g, b.g), np.where(mask, a.h, b.h))

    @staticmethod
    def zero_like(a: "Jet") -> "Jet":
        return Jet(np.zeros_like(a.v), np.zeros_like(a.g), np.zeros_like(a.h))
