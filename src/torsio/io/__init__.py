"""Edges of the library: configuration files, reports (terminal, HTML), plots and the
validation table."""
