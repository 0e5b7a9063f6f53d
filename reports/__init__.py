"""Reports for the hardware team, and the ``irnuc`` command line."""
