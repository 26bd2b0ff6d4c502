"""Section 6.2: a programmable garment interface, tactile buttons on a forearm sleeve.

The paper's buttons encode different tactile responses; it senses their state with conductive
thread in the bobbin and conductive pads underneath. The demo makes three tiers of buttons with
distinct switching-force thresholds (soft, medium, firm), each chosen by inverse design under a
force band of the switching-force model (docs/force.md; its default data are SYNTHETIC), and
sews the centre triangles of every button in conductive thread for state sensing.

The paper combines bistable buttons (a toggle: pressed, it stays in the other state) with
spring-back buttons (pressed, it returns), the latter sewn with unbalanced top and bobbin
tension (section 7). Here the soft tier springs back and the medium and firm tiers are
bistable: each tier's design is checked with the shell of revolution's bistability verdict
(``button_behaviour.settle``), the soft tier at the smallest natural curvature of
``SPRING_BACK_KAPPA0_PER_MM`` that makes it spring back. The summary and the console say what
the shell found for each tier, including a tier that does not behave as wanted.
"""
from __future__ import annotations

from stitchswitch.demos.button_behaviour import settle
from stitchswitch.demos.demo import Demo, DemoDesign
from stitchswitch.demos.garments import forearm_sleeve_panel
from stitchswitch.demos.inverse_step import choose
from stitchswitch.layout.garment.design import Design, MachineSpec, MaterialRef, Threads
from stitchswitch.layout.garment.placement import add_patches
from stitchswitch.reduced.design_space.inverse import InverseTarget

MAX_DIAMETER_MM = 60.0
#: (label, target height mm, force band N, thread colour, behaviour): distinct thresholds by
#: tier; each height lies inside what its band reaches with d <= 60 mm on the default map (soft
#: 2.3-8.3, medium 14.1-16.0, firm 16.0-16.4 mm)
TIERS = (
    ("soft", 7.0, (0.10, 0.20), "#2a9d8f", "spring-back"),
    ("medium", 15.0, (0.25, 0.35), "#e9c46a", "bistable"),
    ("firm", 16.3, (0.40, 0.50), "#e76f51", "bistable"),
)
#: Natural curvatures (1/mm) of the embroidered layer tried, smallest first, for a spring-back
#: tier: the bias of unbalanced thread tension. Which tension difference gives which curvature
#: is not measured (docs/fem-reference.md); a bistable tier uses balanced tension (0).
SPRING_BACK_KAPPA0_PER_MM = (0.05, 0.1, 0.2)
ROW_Y_MM = (100.0, 170.0)        # two rows of buttons on the forearm
COLUMN_PITCH_MM = 60.0
CONDUCTIVE = "ring:0"            # the centre triangles, in conductive thread


def build() -> DemoDesign:
    design = Design(1, (forearm_sleeve_panel(),), (), MaterialRef("default"),
                    MachineSpec())
    steps, behaviours = [], []
    for k, (label, height, band, colour, wanted) in enumerate(TIERS):
        step = choose(f"{label} buttons", InverseTarget(
            height_mm=height, max_diameter_mm=MAX_DIAMETER_MM, force_range_N=band, count=3))
        step, behaviour = settle(step, wanted, SPRING_BACK_KAPPA0_PER_MM
                                 if wanted == "spring-back" else (0.0,))
        steps.append(step)
        behaviours.append(behaviour)
        c = step.chosen
        x = (k - 1) * COLUMN_PITCH_MM
        design = add_patches(design, "forearm-sleeve", [(x, y) for y in ROW_Y_MM],
                             round(c["d_mm"], 2), round(c["fill"], 4), id_prefix=label,
                             conductive=CONDUCTIVE, threads=Threads(top=colour))
    forces = ", ".join(f"{s.label} {s.chosen['force_N']:.2f} N" for s in steps)
    notes = (f"Switching forces (polynomial model on SYNTHETIC data, docs/force.md): {forces}.",
             *(f"Behaviour, shell of revolution: {b.note()}" for b in behaviours),
             "Conductive: the centre triangles of every button (ring 0) after a colour change; "
             "the paper puts conductive thread in the bobbin instead.")
    return DemoDesign(design, tuple(steps), notes)


FOREARM_INTERFACE = Demo(
    name="forearm-interface",
    title="Programmable forearm interface with tactile buttons",
    paper_section="6.2",
    story=("Six tactile buttons on a forearm sleeve in three tiers with distinct switching-force "
           "thresholds, chosen by inverse design, with conductive centres for sensing the "
           "button state (paper, section 6.2): the soft tier springs back, the medium and firm "
           "tiers are bistable (paper, section 7)."),
    build=build,
)
