"""Analyzers: transient response, severity maps, linear stability, energy balance and
the severity coefficient S_SS."""
