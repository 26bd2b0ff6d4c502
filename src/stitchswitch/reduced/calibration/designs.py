"""The paper's 25 calibration designs (section 4, "Calibration procedure"): p in
{0.6, 0.7, 0.8, 0.9, 1.0} x d in {20, 40, 60, 70, 90} mm, fill outermost (the order of the
synthetic reference dataset's training rows)."""

CALIBRATION_FILLS = (0.6, 0.7, 0.8, 0.9, 1.0)
CALIBRATION_DIAMETERS_MM = (20.0, 40.0, 60.0, 70.0, 90.0)
CALIBRATION_DESIGNS = tuple((d, p) for p in CALIBRATION_FILLS for d in CALIBRATION_DIAMETERS_MM)
