"""The output side: the report of a configuration for the terminal, JSON and HTML
(:mod:`torsio.report.document`), and the validation page (:mod:`torsio.report.validation`)."""
