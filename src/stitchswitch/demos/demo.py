"""What a demo is: a name, a story, and a function that designs and places its patches."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from stitchswitch.layout.garment.design import Design


@dataclass(frozen=True)
class InverseStep:
    """One inverse-design query of a demo and the design it chose (the first candidate)."""
    label: str                  # e.g. "pocket" or "soft buttons"
    target: dict                # the InverseTarget's fields, for the summary
    candidates: list            # Candidate.as_dict() of every suggestion, best first
    chosen: dict                # the chosen candidate


@dataclass(frozen=True)
class DemoDesign:
    design: Design
    inverse: tuple[InverseStep, ...]
    notes: tuple[str, ...] = field(default_factory=tuple)


@dataclass(frozen=True)
class Demo:
    name: str
    title: str
    paper_section: str
    story: str
    build: Callable[[], DemoDesign]
    preview_view: str = "iso"
