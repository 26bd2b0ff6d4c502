"""Hoop grouping: which patches go into which hooping (docs/fabrication.md).

* ``group``: ``group(design, mode, ...) -> Grouping``, both modes behind one call.
* ``garment``: garment mode (patches stay where they are; hoop placements are chosen from
  ``candidates``); ``free``: free mode (patches packed on separate fabric, ``circle_packing``).
* ``mip``: the weighted set cover as a mixed-integer program (cvxpy + HiGHS); ``greedy``: the
  baselines and the fallback; ``conflict_plan``: garment hoopings and their order planned
  together for the fewest frame conflicts first (exact on small pieces, beam search beyond).
* ``result``: ``Grouping``, ``Hooping``, ``SolveReport``; ``footprints``: patch footprints on the
  stretched fabric; ``bitsets``: packed patch sets.
"""
