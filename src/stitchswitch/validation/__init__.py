"""Measured data (``measured``), validation metrics (``metrics``) and reports (``report``).
Discrepancy discovery is not implemented yet (issue 6)."""
