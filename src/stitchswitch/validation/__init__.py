"""Measured data, validation reports, discrepancy discovery. Not implemented yet: see issues 4 and 6."""
