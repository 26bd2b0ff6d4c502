"""One module per rule of the constraint check (``layout.check.constraints``). Each has
``check(design, limits, eta) -> list[Violation]``; ``eta`` is the material's pre-stretch."""
