"""Measured data (``measured``), validation metrics (``metrics``) and reports (``report``), and
discrepancy discovery (issue 6): the library of candidate effects (``effects``) and the
workflow (``discovery`` with ``discovery_space``, ``discovery_eval``, ``discovery_fit``,
``discovery_cv``, ``discovery_residuals``, ``discovery_signature``, ``discovery_figures``,
``discovery_report``, ``discovery_synthetic``); see docs/discovery.md."""
