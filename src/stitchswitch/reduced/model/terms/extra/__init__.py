"""Energy terms of physics the reduced model leaves out, each a ``Term`` factory ``term(...)``:
``hoop_bending`` (hoop curvature and Poisson coupling), ``natural_curvature`` (a thread-tension
asymmetry's preferred curvature of the embroidered hinges) and ``gravity`` (the patch's own
weight). The discovery effects (``validation.discovery.effects``) add them to the model; each
has its finite-difference test in tests/test_energy_terms.py.
"""
