"""Finite-element shell reference (scikit-fem). Not implemented yet: see issue 5."""
