"""Section 6.1: a tennis skirt with a pocket that holds a ball.

The paper reports a pocket height of 17.5 mm (17.8 mm after a 1.5-hour session and a wash) and a
tennis ball is about 67 mm across. The demo asks inverse design for h = 17.5 mm with the popped
boundary radius r_a near the ball's radius (33.5 mm), places the chosen patch on the hip of a
skirt front panel, popped outward.
"""
from __future__ import annotations

from stitchswitch.demos.demo import Demo, DemoDesign
from stitchswitch.demos.garments import skirt_front_panel
from stitchswitch.demos.inverse_step import choose
from stitchswitch.layout.garment.design import Design, MachineSpec, MaterialRef
from stitchswitch.layout.garment.patterns import pocket_patch
from stitchswitch.reduced.design_space.inverse import InverseTarget

POCKET_HEIGHT_MM = 17.5          # the paper's measured pocket height (section 6.1)
BALL_DIAMETER_MM = 67.0          # a tennis ball, about 6.7 cm across
POCKET_CENTRE_MM = (-120.0, 270.0)   # on the hip, below the waist band


def build() -> DemoDesign:
    step = choose("pocket", InverseTarget(height_mm=POCKET_HEIGHT_MM,
                                          radius_mm=BALL_DIAMETER_MM / 2.0, count=3))
    c = step.chosen
    design = Design(1, (skirt_front_panel(),), (), MaterialRef("default"),
                    MachineSpec())
    design = pocket_patch(design, "skirt-front", round(c["d_mm"], 2), round(c["fill"], 4),
                          centre_mm=POCKET_CENTRE_MM)
    notes = (f"Ball: {BALL_DIAMETER_MM:g} mm across; the popped patch's boundary radius r_a is "
             f"{c['r_a_mm']:.1f} mm (target {BALL_DIAMETER_MM / 2:g} mm).",)
    return DemoDesign(design, (step,), notes)


TENNIS_POCKET = Demo(
    name="tennis-pocket",
    title="Tennis skirt with a ball pocket",
    paper_section="6.1",
    story=("One large patch on the hip of a skirt front panel pops outward into a stable cavity "
           f"{POCKET_HEIGHT_MM:g} mm deep that holds a tennis ball (paper, section 6.1)."),
    build=build,
)
