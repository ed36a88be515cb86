"""Calibration from rig data: recordings of top-drive speed and surface torque
(:mod:`torsio.calibration.recording`), and the fit of friction and damping to them
(:mod:`torsio.calibration.fit`; docs/calibration.md)."""
